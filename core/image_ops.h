#pragma once
/// @file image_ops.h
/// Resizing, mip chains and GPU-limit fitting of float images, through OpenImageIO's
/// ImageBufAlgo (OIIO headers stay in image_ops.cpp).

#include "core/image.h"

#include <string>
#include <vector>

namespace velvet {

/// Reconstruction filter of resize() (OpenImageIO's filter names, ImageBufAlgo::resize).
enum class ResizeFilter {
    Box,            ///< "box": averages, no ringing; blurry when enlarging
    Triangle,       ///< "triangle" (tent)
    Mitchell,       ///< "mitchell" (Mitchell-Netravali B = C = 1/3): little ringing
    BlackmanHarris, ///< "blackman-harris": sharp, very little ringing (a good default)
    Lanczos3,       ///< "lanczos3": sharpest, rings at edges
};

/// @p image resampled to @p width x @p height with @p filter (edges clamped, not wrapped).
/// Values are clamped to each channel's range in the source, so a filter's negative lobes do
/// not ring data maps (roughness, metallic) outside [0, 1] nor colours below 0. Returns an empty
/// image and sets @p error on bad sizes.
Image resize(const Image& image, int width, int height, std::string* error,
             ResizeFilter filter = ResizeFilter::BlackmanHarris);

/// The full mip chain of @p image: level 0 is a copy of it, each next level halves each side
/// (rounding down, at least 1, as OpenGL 4.5 section 8.14.3 sizes mip levels) down to 1x1.
/// Each level is filtered from the one above with @p filter.
std::vector<Image> mipChain(const Image& image, std::string* error,
                            ResizeFilter filter = ResizeFilter::BlackmanHarris);
/// Number of levels of a full mip chain: floor(log2(max(width, height))) + 1.
int mipLevelCount(int width, int height);

/// The mean of each @p factor x @p factor block of @p image: supersampling's box filter, each
/// output pixel the average of the samples drawn inside it (as the reference path tracer
/// averages its samples over the pixel's square). Both sides must be multiples of @p factor
/// (>= 1); otherwise an empty image. Factor 1 hands @p image back without a copy (moved), so a
/// job that does not supersample pays nothing for the call.
Image boxDownsample(Image image, int factor);

/// Downscales @p image in place when a side is larger than @p maxSide (e.g. the GPU's
/// GL_MAX_TEXTURE_SIZE), keeping the aspect ratio (the longer side becomes @p maxSide, the
/// other is rounded, at least 1). Returns true and sets @p warning, naming @p fileName and both
/// sizes, when it did; returns false and leaves @p image alone when it already fits (or, for an
/// inconsistent image, when it cannot be resized: @p warning then says why).
bool fitToLimit(Image& image, int maxSide, std::string* warning, const std::string& fileName = {});

/// The running mean of images of one size and channel count: frames averaged in linear light
/// (the editor's refinement at rest, `velvet compare --table`'s viewport). An image of another
/// shape starts the mean again from it.
class ImageMean {
public:
    void add(const Image& image);
    void clear();
    /// Images in the mean (0 before the first add and after clear()).
    int count() const { return m_count; }
    /// Their mean (empty when there is none).
    Image mean() const;
    /// Their mean, moved out of the sum (no copy of a frame-sized image); the mean is then empty.
    Image takeMean();

private:
    Image m_sum;
    int m_count = 0;
};

} // namespace velvet
