#include "core/spherical_harmonics.h"

#include <cmath>
#include <glm/common.hpp>
#include <numbers>

namespace velvet {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

/// Real SH basis up to l = 2 (Ramamoorthi & Hanrahan 2001, eq. 3), in world x, y, z.
std::array<float, 9> basis(glm::vec3 d) {
    return {0.282095f,
            0.488603f * d.y,
            0.488603f * d.z,
            0.488603f * d.x,
            1.092548f * d.x * d.y,
            1.092548f * d.y * d.z,
            0.315392f * (3.0f * d.z * d.z - 1.0f),
            1.092548f * d.x * d.z,
            0.546274f * (d.x * d.x - d.y * d.y)};
}

} // namespace

glm::vec3 equirectDirection(float u, float v) {
    // Must match equirectDirection() in resources/shaders/common_environment.glsl.
    const float phi = (u - 0.5f) * 2.0f * kPi;
    const float theta = v * kPi;
    const float st = std::sin(theta);
    return {st * std::sin(phi), std::cos(theta), -st * std::cos(phi)};
}

SH9 projectEquirect(const Image& radiance) {
    SH9 sh{};
    if (radiance.empty())
        return sh;
    // Solid angle of a texel: (2pi / W) (pi / H) sin(theta). The weights are renormalised to 4pi
    // so that a constant image projects exactly onto L00 (midpoint-rule error would otherwise be
    // O(1/H^2)).
    double weightSum = 0.0;
    std::array<glm::dvec3, 9> acc{};
    for (int y = 0; y < radiance.height; ++y) {
        const float v = (float(y) + 0.5f) / float(radiance.height);
        const double w = std::sin(double(v) * kPi);
        for (int x = 0; x < radiance.width; ++x) {
            const float u = (float(x) + 0.5f) / float(radiance.width);
            const glm::vec3 d = equirectDirection(u, v);
            const glm::dvec3 L = glm::dvec3(glm::vec3(radiance.rgba(x, y)));
            const auto Y = basis(d);
            for (int k = 0; k < 9; ++k)
                acc[k] += L * (w * Y[k]);
            weightSum += w;
        }
    }
    const double scale = 4.0 * kPi / weightSum;
    for (int k = 0; k < 9; ++k)
        sh[k] = glm::vec3(acc[k] * scale);
    return sh;
}

SH9 uniformSH9(glm::vec3 radiance) {
    SH9 sh{};
    sh[0] = radiance * (0.282095f * 4.0f * kPi);
    return sh;
}

glm::vec3 evalIrradianceOverPi(const SH9& sh, glm::vec3 n) {
    // E(n) = sum_l A_l L_lm Y_lm(n) with A_0 = pi, A_1 = 2pi/3, A_2 = pi/4 (R&H 2001, eq. 8);
    // divided by pi. Must match evalIrradianceOverPi() in common_environment.glsl.
    const auto Y = basis(n);
    const float A[9] = {1.0f,  2.0f / 3.0f, 2.0f / 3.0f, 2.0f / 3.0f, 0.25f,
                        0.25f, 0.25f,       0.25f,       0.25f};
    glm::vec3 e(0.0f);
    for (int k = 0; k < 9; ++k)
        e += sh[k] * (A[k] * Y[k]);
    return glm::max(e, glm::vec3(0.0f));
}

} // namespace velvet
