#pragma once
/// @file color_difference.h
/// Perceptual colour difference for comparing images (issue 15, `velvet compare`): CIELAB from
/// display-referred sRGB and the CIEDE2000 colour difference. Pure functions, double precision.

#include <glm/vec3.hpp>

namespace velvet {

/// A CIE 1976 L*a*b* colour (L* in [0, 100]).
struct Lab {
    double L = 0.0, a = 0.0, b = 0.0;
};

/// CIEDE2000 (CIE 142-2001) between @p x and @p y, with the parametric factors kL = kC = kH = 1
/// (the reference conditions). Implemented as Sharma, Wu and Dalal, "The CIEDE2000
/// Color-Difference Formula: Implementation Notes, Supplementary Test Data, and Mathematical
/// Observations", Color Res. Appl. 30(1), 2005, equations (1)-(17), including their notes on the
/// mean hue and hue difference when a chroma is zero. Symmetric in its arguments.
double ciede2000(const Lab& x, const Lab& y, double kL = 1.0, double kC = 1.0, double kH = 1.0);

/// CIE XYZ (Y = 1 for the reference white) to L*a*b* relative to the D65 white (CIE 15:2004,
/// section 8.2.1), the white point of sRGB.
Lab xyzToLab(const glm::dvec3& xyz);

/// A display-referred sRGB colour, each channel encoded in [0, 1] (IEC 61966-2-1: the
/// piecewise EOTF, Rec.709 primaries, D65), to L*a*b*. Values are clamped to [0, 1] first.
Lab srgbToLab(const glm::vec3& encoded);

} // namespace velvet
