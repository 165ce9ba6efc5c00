#pragma once
/// @file image_compare.h
/// Per-pixel CIEDE2000 between two images after the same display transform, its statistics and
/// a heat map with a legend (issue 15, `velvet compare`; docs/reference-renderer.md).

#include "core/image.h"

#include <glm/vec3.hpp>
#include <string>

namespace velvet {

/// Statistics of a ΔE map.
struct DeltaEStats {
    double mean = 0.0;
    double p95 = 0.0; ///< 95th percentile, nearest rank: the ceil(0.95 n)-th smallest value
    double max = 0.0;
    size_t pixels = 0;
};

/// The display transform `velvet render` applies by default, on the CPU: exposure 0, the
/// Khronos PBR Neutral tone mapper (core/tone_curves.h, the twin of common_tonemap.glsl),
/// clamped to [0, 1], then the sRGB encoding of the shipped config's default display
/// ("sRGB - Display", IEC 61966-2-1 piecewise). For scene-linear (EXR) inputs. Alpha is kept.
Image defaultDisplayTransform(const Image& sceneLinear);

/// Per-pixel CIEDE2000 between @p a and @p b, both display-referred sRGB (encoded, [0, 1]);
/// alpha is ignored. @p deltaE gets a one-channel image of the differences. False + @p error when
/// the sizes differ or an image is empty.
bool compareImages(const Image& a, const Image& b, Image& deltaE, DeltaEStats& stats,
                   std::string* error);

/// Statistics of a one-channel ΔE map.
DeltaEStats deltaEStats(const Image& deltaE);
/// Statistics of the pixels of @p deltaE whose @p coverage (one channel, the same size) is 1:
/// the mesh's own pixels when coverage is the reference's (reference::Result::coverage), so a
/// background the viewport blurs does not count against the material. Empty (pixels 0) when the
/// sizes differ or no pixel is covered.
DeltaEStats deltaEStats(const Image& deltaE, const Image& coverage);

/// The colour the heat map gives ΔE @p value on a scale to @p scaleMax (display-referred sRGB):
/// a piecewise-linear ramp black (0) - blue - green - yellow - red (scaleMax and above).
glm::vec3 heatMapColor(double value, double scaleMax);

/// @p deltaE drawn as a heat map (RGB, display-referred) with a legend strip below it: the ramp
/// from 0 to @p scaleMax with five labelled ticks (0, 1/4, 1/2, 3/4, max), drawn with a built-in
/// bitmap font. The map's pixels are the image's first @p deltaE.height rows, unscaled; the image
/// is widened (black) when the legend needs more room than the map is wide.
Image heatMapWithLegend(const Image& deltaE, double scaleMax);

/// Height of the legend strip heatMapWithLegend() adds below the map, in pixels.
int heatMapLegendHeight();

} // namespace velvet
