#include "core/brdf_energy.h"

#include "core/brdf.h"
#include "core/ibl.h"

#include <algorithm>
#include <glm/common.hpp>

namespace velvet::brdf {

const std::vector<float>& specularAlbedoLut() {
    // The same integrator and sample count as the GPU's DFG LUT (ibl_dfg.comp), so the direct
    // light's E and the image-based light's A + B are the same function; only the grid differs
    // (this one shares the sheen table's texture and layout).
    static const std::vector<float> table = [] {
        constexpr int N = kSheenLutSize;
        std::vector<float> t(size_t(N) * N);
        for (int j = 0; j < N; ++j)
            for (int i = 0; i < N; ++i) {
                const glm::vec2 ab = ibl::integrateDfg(
                    float(i) / float(N - 1), float(j) / float(N - 1), ibl::kDfgLutSamples);
                t[size_t(j) * N + size_t(i)] = std::clamp(ab.x + ab.y, 1e-3f, 1.0f);
            }
        return t;
    }();
    return table;
}

float specularDirectionalAlbedo(float NdotV, float perceptualRoughness) {
    // Bilinear with texel centres at i / (N - 1), as sheenDirectionalAlbedo() and the GPU.
    const auto& t = specularAlbedoLut();
    constexpr int N = kSheenLutSize;
    const float x = std::clamp(NdotV, 0.0f, 1.0f) * (N - 1);
    const float y = std::clamp(perceptualRoughness, 0.0f, 1.0f) * (N - 1);
    const int x0 = std::min(int(x), N - 2), y0 = std::min(int(y), N - 2);
    const float fx = x - float(x0), fy = y - float(y0);
    const auto at = [&](int xi, int yi) { return t[size_t(yi) * N + size_t(xi)]; };
    const float a = glm::mix(at(x0, y0), at(x0 + 1, y0), fx);
    const float b = glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx);
    return glm::mix(a, b, fy);
}

glm::vec3 multipleScatteringFactor(glm::vec3 f0, float NdotV, float roughness, bool enabled) {
    if (!enabled)
        return glm::vec3(1.0f);
    // Turquin 2019 eq. 8: the energy 1 - E lost by single scattering comes back in proportion to
    // F0, relative to what single scattering already reflects (E).
    const float e = specularDirectionalAlbedo(NdotV, std::max(roughness, kMinRoughness));
    return glm::vec3(1.0f) + f0 * ((1.0f - e) / e);
}

} // namespace velvet::brdf
