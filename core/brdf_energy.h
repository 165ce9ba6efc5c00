#pragma once
/// @file brdf_energy.h
/// Multiple-scattering energy compensation of the base specular lobe for direct light and the
/// offline reference (issue 15): Turquin 2019, "Practical multiple scattering compensation for
/// microfacet models", f_ms = f_ss (1 + F0 (1 - E(mu_o)) / E(mu_o)), where E is the directional
/// albedo of the single-scattering lobe with F = 1 — the DFG LUT's A + B (core/ibl.h). For
/// F0 = 1 the compensated lobe reflects exactly all the light that reaches it (a white furnace),
/// as the viewport's image-based light does with Fdez-Agüera 2019 (ibl::specularAlbedo; both
/// are exact for F0 = 1 and differ by a few per cent of the multiply scattered part for
/// coloured F0). Twin of multipleScatteringFactor() in resources/shaders/common_brdf.glsl.
///
/// E is tabulated for the default lobe (GGX D, separable Smith-GGX V, as the DFG LUT) and used
/// for every Distribution / Visibility choice and for the anisotropic lobe at its base roughness,
/// the same approximation the image-based light makes.

#include <glm/vec3.hpp>
#include <vector>

namespace velvet::brdf {

/// E(n.v, perceptual roughness) on a kSheenLutSize^2 grid laid out as sheenAlbedoLut(): row-major,
/// index = roughnessIndex * size + NdotVIndex, cell i at i / (size - 1) (roughness clamped to
/// kMinRoughness, n.v to 1e-4), each A + B of ibl::integrateDfg (the GPU DFG LUT's integrator and
/// sample count), integrated now (~1M GGX samples, 0.1-0.2 s).
std::vector<float> integrateSpecularAlbedo();
/// The shipped copy of integrateSpecularAlbedo()'s table (core/specular_albedo_table.inc; `velvet
/// specular-table` writes it, test_core_brdf checks it). The GPU reads the same numbers from the
/// alpha channel of the sheen albedo texture (render/sheen_lut.h).
const std::vector<float>& specularAlbedoLut();
/// Bilinear lookup of specularAlbedoLut(), exactly as the GPU samples it (see
/// sheenDirectionalAlbedo()).
float specularDirectionalAlbedo(float NdotV, float perceptualRoughness);
/// Turquin 2019's factor 1 + f0 (1 - E) / E for a lobe of Fresnel F0 @p f0 seen at @p NdotV with
/// perceptual roughness @p roughness (clamped to kMinRoughness); 1 when @p enabled is false
/// (FrameSettings::specularMultiScatter off: the single-scattering lobe).
glm::vec3 multipleScatteringFactor(glm::vec3 f0, float NdotV, float roughness, bool enabled = true);

} // namespace velvet::brdf
