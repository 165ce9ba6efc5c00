#pragma once
/// @file color_encoding.h
/// The sRGB transfer functions (IEC 61966-2-1) used where the editor shows scene-linear values to
/// the artist: colour pickers show display-encoded sRGB, the document stores linear Rec.709.

#include <algorithm>
#include <cmath>

#include <glm/vec3.hpp>

namespace velvet::ui {

/// sRGB EOTF: display-encoded value in [0, 1] -> linear.
inline float srgbToLinear(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

/// sRGB inverse EOTF (OETF): linear value -> display-encoded value in [0, 1].
inline float linearToSrgb(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.0031308f ? v * 12.92f : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

inline glm::vec3 srgbToLinear(glm::vec3 c) {
    return {srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z)};
}

inline glm::vec3 linearToSrgb(glm::vec3 c) {
    return {linearToSrgb(c.x), linearToSrgb(c.y), linearToSrgb(c.z)};
}

} // namespace velvet::ui
