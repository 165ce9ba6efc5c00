#pragma once
/// @file ibl.h
/// CPU twins of the image-based lighting in render/ibl_bake.cpp and resources/shaders/ibl_*.comp
/// and common_environment.glsl: the split-sum approximation (Karis 2013, "Real Shading in Unreal
/// Engine 4"), its DFG LUT, the multiple-scattering energy compensation (Fdez-Agüera 2019, "A
/// Multiple-Scattering Microfacet Model for Real-Time Image-based Lighting") and the mapping of
/// roughness to the prefiltered specular mip chain. Pure GLM: the tests compare the GPU LUT and
/// the GPU prefiltered cube against these.
///
/// Conventions (shared with the GLSL): the specular lobe is the default model of core/brdf.h, GGX
/// D with the separable Smith-GGX visibility of glTF 2.0 Appendix B and Schlick F with f90 = 1;
/// alpha = perceptualRoughness^2, perceptual roughness clamped to brdf::kMinRoughness.

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

namespace velvet::ibl {

/// @name Sampling (Karis 2013)
/// @{
/// Point i of an n-point Hammersley set in [0, 1)^2 (radical inverse in base 2).
glm::vec2 hammersley(std::uint32_t i, std::uint32_t n);
/// GGX-distributed half vector in tangent space (z = normal) for uniform @p xi; pdf(h) = D(h) n.h.
glm::vec3 importanceSampleGgx(glm::vec2 xi, float alpha);
/// @}

/// @name The DFG (environment BRDF) LUT
/// The directional albedo of the specular lobe is E(v) = f0 * A + B (Karis 2013): A and B are the
/// integrals over the hemisphere of f / F * (n.l) weighted by (1 - Fc) and Fc, Fc = (1 - v.h)^5.
/// @{
/// Side of the square DFG LUT (texel (i, j): n.v = (i + 0.5) / size, roughness = (j + 0.5) /
/// size; sampled bilinearly at uv = (n.v, roughness) with clamp to edge).
inline constexpr int kDfgLutSize = 64;
/// Importance samples per texel of the GPU-made LUT (the same count for integrateDfg()).
inline constexpr int kDfgLutSamples = 1024;
/// (A, B) by importance sampling GGX with @p samples Hammersley points: the same algorithm, line
/// for line, as resources/shaders/ibl_dfg.comp.
glm::vec2 integrateDfg(float NdotV, float perceptualRoughness, int samples = kDfgLutSamples);
/// (A, B) by a deterministic midpoint product rule in double precision over (u, phi), where u is
/// the GGX CDF of the half-vector angle (a change of variables, so the quadrature stays accurate
/// for the narrowest lobes). An independent reference for the LUT.
glm::vec2 integrateDfgQuadrature(float NdotV, float perceptualRoughness, int nU = 512,
                                 int nPhi = 128);
/// (A, B) of texel (i, j) of the LUT (the parameters above).
glm::vec2 dfgTexelParams(int i, int j, int size = kDfgLutSize);
/// @}

/// Directional albedo of the specular lobe from (A, B): f0 A + B, plus, with @p multiScatter,
/// the energy of the multiply scattered light (Fdez-Agüera 2019, eq. 11-16: Ems = 1 - (A + B),
/// Favg = f0 + (1 - f0) / 21, Fms Ems = (f0 A + B) Favg Ems / (1 - Favg Ems)). For f0 = 1 the
/// compensated albedo is exactly 1 (a white furnace).
glm::vec3 specularAlbedo(glm::vec3 f0, glm::vec2 dfg, bool multiScatter);

/// @name The prefiltered specular mip chain
/// Level k of a chain of @p levels holds the radiance convolved with the GGX lobe of perceptual
/// roughness k / (levels - 1) (level 0 is the mirror image); lookups use lod = r (levels - 1).
/// @{
float roughnessOfLevel(int level, int levels);
float lodOfRoughness(float perceptualRoughness, int levels);
/// Colbert & Krivanek 2007, "GPU-Based Importance Sampling" (GPU Gems 3, ch. 20): the source mip
/// whose texel solid angle matches the sample's, lod = 0.5 log2(Omega_s / Omega_p) + 1, with
/// Omega_s = 1 / (N pdf) and Omega_p = 4 pi / (6 size^2) for a cube of @p faceSize texels.
float sourceLod(float pdf, int sampleCount, int faceSize);
/// @}

} // namespace velvet::ibl
