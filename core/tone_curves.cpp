#include "core/tone_curves.h"

#include <algorithm>
#include <glm/common.hpp>

namespace velvet::tone {

glm::vec3 khronosPbrNeutral(glm::vec3 color) {
    // The specification's constants: compression starts at 0.8 minus the toe's offset.
    constexpr float kStartCompression = 0.8f - 0.04f;
    constexpr float kDesaturation = 0.15f;
    const float x = std::min(color.r, std::min(color.g, color.b));
    const float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
    color -= offset;
    const float peak = std::max(color.r, std::max(color.g, color.b));
    if (peak < kStartCompression)
        return color;
    const float d = 1.0f - kStartCompression;
    const float newPeak = 1.0f - d * d / (peak + d - kStartCompression);
    color *= newPeak / peak;
    const float g = 1.0f - 1.0f / (kDesaturation * (peak - newPeak) + 1.0f);
    return glm::mix(color, glm::vec3(newPeak), g);
}

} // namespace velvet::tone
