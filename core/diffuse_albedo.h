#pragma once
/// @file diffuse_albedo.h
/// The material's chosen diffuse term under image-based light (issue 15). The viewport lights the
/// diffuse lobe of the environment with the SH9 irradiance E(n) / pi times the base colour, which
/// is exact for Lambert (its directional albedo is 1 for every view). Burley 2012's diffuse is not
/// energy conserving: its directional albedo is below 1 on smooth surfaces and above 1 towards
/// grazing on rough ones (the retro-reflection), so the viewport scales the irradiance term by the
/// chosen term's albedo relative to Lambert's, pre-integrated over (n.v, roughness) as Lagarde & de
/// Rousiers 2014, "Moving Frostbite to PBR" (§4.9, image based lights) pre-integrate their Disney
/// diffuse next to the DFG terms. Direct light and the offline reference evaluate the term itself
/// (brdf::diffuse); this is the split-sum counterpart for the environment: exact under a uniform
/// environment, the lobe's shape (the retro-reflection's direction) otherwise ignored.
///
/// Twin of diffuseDirectionalAlbedo() in resources/shaders/common_brdf.glsl, which reads the same
/// table from the blue channel of the albedo texture (render/sheen_lut.h).

#include "core/material.h"

#include <vector>

namespace velvet::brdf {

/// Directional albedo of @p which with a white diffuse colour, seen at @p NdotV (clamped to
/// 1e-4, as shading clamps n.v) with perceptual @p roughness (clamped to kMinRoughness, as
/// shading clamps it): the integral over the hemisphere of f_d(l, v) (n.l) with l.h of the half
/// vector, by the midpoint rule in (theta_l, phi_l) (@p nTheta x @p nPhi over the half
/// hemisphere phi in [0, pi], the integrand being symmetric in phi). Exactly 1 for Lambert; for
/// Burley head-on 1 + 5 r / 84 - 1 / 42 (test_core_diffuse_albedo derives it).
double integrateDiffuseAlbedo(Diffuse which, float NdotV, float roughness, int nTheta = 96,
                              int nPhi = 48);
/// Burley's albedo on the kSheenLutSize^2 grid, laid out as sheenAlbedoLut(): row-major, index =
/// roughnessIndex * size + NdotVIndex, cell i at i / (size - 1), integrated now.
std::vector<float> integrateBurleyAlbedoTable();
/// The shipped copy of integrateBurleyAlbedoTable() (core/diffuse_albedo_table.inc; `velvet
/// diffuse-table` writes it, test_core_diffuse_albedo checks it against the integration).
const std::vector<float>& burleyAlbedoLut();
/// The albedo of @p which relative to Lambert's: 1 for Lambert; for Burley a bilinear lookup of
/// burleyAlbedoLut() exactly as the GPU samples it (texel centres at i / (size - 1), clamped).
float diffuseDirectionalAlbedo(Diffuse which, float NdotV, float perceptualRoughness);

} // namespace velvet::brdf
