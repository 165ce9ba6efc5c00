#pragma once
/// @file spherical_harmonics.h
/// Order-2 (9 coefficient) spherical harmonics of an environment's radiance and the irradiance
/// they give (Ramamoorthi & Hanrahan 2001, "An Efficient Representation for Irradiance
/// Environment Maps"). The CPU reference for the renderer's diffuse ambient term.

#include "core/image.h"

#include <array>
#include <glm/vec3.hpp>

namespace velvet {

using SH9 = std::array<glm::vec3, 9>;

/// Direction of an equirectangular texel centre (u, v in [0,1], v = 0 at the top = +Y), Y up,
/// u = 0.5 looking down -Z. The same mapping as the shaders (common_environment.glsl).
glm::vec3 equirectDirection(float u, float v);

/// Projects an equirectangular radiance image onto SH9 (solid-angle weighted).
SH9 projectEquirect(const Image& radiance);
/// SH9 of a uniform radiance.
SH9 uniformSH9(glm::vec3 radiance);
/// Irradiance E(n) / pi from SH9 radiance coefficients (the cosine-convolved, divided by pi, so a
/// uniform radiance L gives L for a white Lambertian surface).
glm::vec3 evalIrradianceOverPi(const SH9& sh, glm::vec3 n);

} // namespace velvet
