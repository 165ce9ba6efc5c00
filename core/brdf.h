#pragma once
/// @file brdf.h
/// CPU twins of the BRDF terms in resources/shaders/common_brdf.glsl (same names, same order,
/// same clamps). Pure GLM: the tests compare GPU pixels against these, and the offline reference
/// uses them. The default model is glTF 2.0 Appendix B metal-rough with the layering of
/// KHR_materials_specular, _ior, _sheen and _clearcoat.

#include "core/material.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

namespace velvet::brdf {

/// Smallest perceptual roughness used in shading (fp16/fp32 safety, as Filament's
/// MIN_PERCEPTUAL_ROUGHNESS); alpha = roughness^2.
inline constexpr float kMinRoughness = 0.045f;
/// Smallest sheen roughness used in shading (Charlie D degenerates at 0).
inline constexpr float kMinSheenRoughness = 0.07f;

/// @name Terms (each cites its source in brdf.cpp and common_brdf.glsl)
/// @{
float distributionGGX(float NdotH, float alpha);
float visibilitySmithGGXSeparable(float NdotL, float NdotV, float alpha);
glm::vec3 fresnelSchlick(glm::vec3 f0, glm::vec3 f90, float VdotH);
float fresnelSchlick(float f0, float f90, float VdotH);
float distributionCharlie(float NdotH, float sheenRoughness);
float visibilitySheenContyKulla(float NdotL, float NdotV, float sheenRoughness);
float visibilityNeubelt(float NdotL, float NdotV);
/// Karis 2014's analytic fit of the split-sum environment BRDF: returns (scale, bias) so that the
/// directional albedo of the specular lobe is f0 * scale + bias. An approximation (the renderer
/// issue replaces it with a DFG LUT).
glm::vec2 envBrdfApprox(float roughness, float NdotV);
/// @}

/// Directional albedo E(NdotV, roughness) of the sheen lobe (Charlie D x Conty-Kulla V, white
/// sheen colour), for KHR_materials_sheen's albedo scaling. Tabulated once by numerical
/// integration on a kSheenLutSize^2 grid and looked up bilinearly, exactly as the GPU samples the
/// same table (texel centres at (i + 0.5) / size, clamped).
inline constexpr int kSheenLutSize = 32;
/// The table, row-major: index = roughnessIndex * size + NdotVIndex; cell i holds the value at
/// NdotV = i / (size - 1) (likewise roughness).
const std::vector<float>& sheenAlbedoLut();
float sheenDirectionalAlbedo(float NdotV, float sheenRoughness);

/// Material values as shading uses them.
struct Surface {
    glm::vec3 baseColor{0.8f};
    float metallic = 0.0f;
    float roughness = 0.5f;
    float specularWeight = 1.0f;
    glm::vec3 specularColor{1.0f};
    float ior = 1.5f;
    glm::vec3 sheenColor{0.0f}; ///< KHR_materials_sheen sheenColorFactor (weight x colour)
    float sheenRoughness = 0.3f;
    float clearcoat = 0.0f;
    float clearcoatRoughness = 0.03f;
    glm::vec3 emissive{0.0f}; ///< colour x strength
};
Surface surfaceFromMaterial(const Material& m);

/// Dielectric F0 from IOR and KHR_materials_specular's colour (before the weight).
glm::vec3 dielectricF0(const Surface& s);

/// Outgoing radiance towards @p v per unit illuminance from direction @p l (towards the light):
/// f(l, v) * max(n.l, 0), all lobes layered. Vectors unit length, world space.
glm::vec3 evalDirectional(const Surface& s, glm::vec3 n, glm::vec3 v, glm::vec3 l);

} // namespace velvet::brdf
