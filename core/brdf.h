#pragma once
/// @file brdf.h
/// CPU twins of the BRDF terms in resources/shaders/common_brdf.glsl (same names, same order,
/// same clamps), laid out like it and Filament's surface_brdf.fs: implementations, then dispatch
/// on the material's term choices. Pure GLM: the tests compare GPU pixels against these, and the
/// offline reference uses them. The default model is glTF 2.0 Appendix B metal-rough with the
/// layering of KHR_materials_specular, _ior, _sheen and _clearcoat; every term of the seed
/// documents is selectable per material (Distribution, Visibility, Fresnel, Diffuse, SheenModel).
/// Conventions: alpha = roughness^2; every visibility term is V = G / (4 n.l n.v).

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

/// sin^2 of the angle between unit vectors @p n and @p h as |n x h|^2. Near the lobe peak
/// (n.h -> 1) 1 - (n.h)^2 cancels catastrophically in float: one ulp of n.h (6e-8) is 1.2e-7 of
/// sin^2, 3 % of alpha^2 at kMinRoughness, and D amplifies it. The cross product keeps the
/// relative accuracy of small angles, so the GPU and the twin agree to ~1e-4 at every roughness
/// (Filament's D_GGX does the same).
float sinSquared(glm::vec3 n, glm::vec3 h);
/// ln(1 - x) for x in [0, 1]: a series below 0.1 (where the GPU's log of 1 - x would lose
/// the 2^-21 absolute accuracy GLSL allows), log() above; used by Blinn-Phong's huge exponents.
float logOneMinus(float x);

/// @name Normal distributions D(h) (normalised: integral of D(h) (n.h) over the hemisphere = 1)
/// Shading passes both n.h and sin2H = sinSquared(n, h); every D is written in terms of sin2H
/// where it matters (near the peak). The two-argument overloads derive sin2H = (1 - n.h)(1 + n.h)
/// and are for an exact n.h (quadrature nodes, tests), not for shading.
/// @{
/// Walter et al. 2007, GGX / Trowbridge-Reitz (default), written as Filament's D_GGX:
/// alpha^2 / (pi ((n.h alpha)^2 + sin^2)^2).
float distributionGGX(float NdotH, float sin2H, float alpha);
float distributionGGX(float NdotH, float alpha);
/// Beckmann & Spizzichino 1963, alpha = roughness^2 as the slope RMS: exp(-tan^2 / alpha^2) with
/// tan^2 = sin^2 / cos^2.
float distributionBeckmann(float NdotH, float sin2H, float alpha);
float distributionBeckmann(float NdotH, float alpha);
/// Blinn 1977, exponent n = 2 / alpha^2 - 2, normalised by (n + 2) / 2pi; (n.h)^n evaluated as
/// exp(n/2 ln(1 - sin^2)).
float distributionBlinnPhong(float NdotH, float sin2H, float alpha);
float distributionBlinnPhong(float NdotH, float alpha);
/// @}

/// @name Visibility V = G / (4 n.l n.v)
/// @{
/// Smith GGX, separable form of glTF 2.0 Appendix B (default).
float visibilitySmithGGXSeparable(float NdotL, float NdotV, float alpha);
/// Heitz 2014 height-correlated Smith GGX (Filament, glTF Sample Viewer).
float visibilitySmithGGXCorrelated(float NdotL, float NdotV, float alpha);
/// Karis 2013 Schlick-GGX with k = alpha / 2.
float visibilitySchlickGGX(float NdotL, float NdotV, float alpha);
/// Cook & Torrance 1982 V-cavities.
float visibilityCookTorrance(float NdotL, float NdotV, float NdotH, float VdotH);
/// Implicit G = n.l n.v, so V = 1/4.
float visibilityImplicit();
/// Neumann et al. 1999: G = n.l n.v / max(n.l, n.v).
float visibilityNeumann(float NdotL, float NdotV);
/// Kelemen & Szirmay-Kalos 2001: V = 1 / (4 (v.h)^2).
float visibilityKelemen(float VdotH);
/// @}

/// @name Fresnel
/// @{
/// Schlick 1994 (default).
glm::vec3 fresnelSchlick(glm::vec3 f0, glm::vec3 f90, float VdotH);
float fresnelSchlick(float f0, float f90, float VdotH);
/// Karis 2013: Schlick with the spherical-gaussian exponent 2^((-5.55473 c - 6.98316) c).
glm::vec3 fresnelSchlickSphericalGaussian(glm::vec3 f0, glm::vec3 f90, float VdotH);
/// Walter et al. 2007 eq. 22: exact unpolarised Fresnel reflectance of a dielectric, eta = IOR.
float fresnelDielectricExact(float VdotH, float eta);
/// @}

/// @name Diffuse
/// @{
/// Lambert (default): diffuseColor / pi.
glm::vec3 diffuseLambert(glm::vec3 diffuseColor);
/// Burley 2012 (Disney) with its retro-reflection, energy as published (not renormalised);
/// @p roughness is the perceptual roughness.
glm::vec3 diffuseBurley(glm::vec3 diffuseColor, float roughness, float NdotL, float NdotV,
                        float LdotH);
/// @}

/// @name Sheen (Charlie D with three visibility terms)
/// @{
/// Estevez & Kulla 2017 Charlie D; alpha = max(sheenRoughness, kMinSheenRoughness)^2;
/// (sin^2)^(1 / 2 alpha^2) with sin2H = sinSquared(n, h) (two-argument overload: exact n.h).
float distributionCharlie(float NdotH, float sin2H, float sheenRoughness);
float distributionCharlie(float NdotH, float sheenRoughness);
/// Conty & Kulla 2017 fitted visibility (default).
float visibilitySheenContyKulla(float NdotL, float NdotV, float sheenRoughness);
/// Ashikhmin & Premoze 2007: V = 1 / (4 (n.l + n.v - n.l n.v)), clamped to [0, 1].
float visibilityAshikhmin(float NdotL, float NdotV);
/// Neubelt & Pettineo 2013: the same function as visibilityAshikhmin (they adopt its
/// denominator; Filament's V_Neubelt and the glTF Sample Viewer's V_Ashikhmin coincide).
float visibilityNeubelt(float NdotL, float NdotV);
/// @}

/// @name Dispatch on the per-material term choices (mirrors the GLSL dispatch functions)
/// @{
float distribution(Distribution which, float NdotH, float sin2H, float alpha);
float distribution(Distribution which, float NdotH, float alpha);
float visibility(Visibility which, float NdotL, float NdotV, float NdotH, float VdotH, float alpha);
/// Dielectric Fresnel with f90 = 1. ExactDielectric keeps KHR_materials_specular's coloured F0 by
/// rescaling the exact curve: f0 + (1 - f0) (F(c) - F(1)) / (1 - F(1)); equal to
/// fresnelDielectricExact() when the specular colour is white.
glm::vec3 fresnelDielectric(Fresnel which, glm::vec3 f0, float ior, float VdotH);
/// Conductor Fresnel, F0 = base colour; ExactDielectric falls back to Schlick for metals (no
/// complex IOR in the model).
glm::vec3 fresnelConductor(Fresnel which, glm::vec3 f0, float VdotH);
glm::vec3 diffuse(Diffuse which, glm::vec3 diffuseColor, float roughness, float NdotL, float NdotV,
                  float LdotH);
float visibilitySheen(SheenModel which, float NdotL, float NdotV, float sheenRoughness);
/// @}

/// @name Anisotropic GGX (KHR_materials_anisotropy)
/// The extension stretches the base specular lobe along a tangent-space direction t (b =
/// n x t): alpha_t = mix(alpha, 1, strength^2), alpha_b = alpha, D is Burley 2012's anisotropic
/// GGX and V the height-correlated Smith term of Heitz 2014 for it, both as the extension's
/// README writes them (D_GGX_anisotropic, V_GGX_anisotropic). With alpha_t = alpha_b they are
/// distributionGGX() and visibilitySmithGGXCorrelated().
/// @{
/// (alpha_t, alpha_b) from the perceptual @p roughness (clamped to kMinRoughness, as every lobe)
/// and the anisotropy @p strength in [0, 1].
glm::vec2 anisotropicAlphas(float roughness, float strength);
/// 1 / (pi at ab ((t.h / at)^2 + (b.h / ab)^2 + (n.h)^2)^2); normalised like every D.
float distributionGGXAnisotropic(float NdotH, float TdotH, float BdotH, float at, float ab);
/// 0.5 / (n.l |(at t.v, ab b.v, n.v)| + n.v |(at t.l, ab b.l, n.l)|), clamped to [0, 1].
float visibilitySmithGGXCorrelatedAnisotropic(float NdotL, float NdotV, float TdotV, float BdotV,
                                              float TdotL, float BdotL, float at, float ab);
/// @}

/// Directional albedo E(NdotV, roughness) of the sheen lobe (Charlie D x the visibility of
/// @p model, white sheen colour), for KHR_materials_sheen's albedo scaling and the sheen IBL term.
/// One table per SheenModel (Ashikhmin and Neubelt are the same function, so their tables are
/// equal). Tabulated once by numerical integration on a kSheenLutSize^2 grid and looked up
/// bilinearly, exactly as the GPU samples the same tables (channel = model; texel centres at
/// (i + 0.5) / size, clamped).
inline constexpr int kSheenLutSize = 32;
/// The table of @p model integrated now (sheenAlbedoLut() returns the shipped copy of it,
/// core/sheen_albedo_table.inc; `velvet sheen-table` writes that file).
std::vector<float> integrateSheenAlbedo(SheenModel model);
/// The table of @p model, row-major: index = roughnessIndex * size + NdotVIndex; cell i holds the
/// value at NdotV = i / (size - 1) (likewise roughness).
const std::vector<float>& sheenAlbedoLut(SheenModel model = SheenModel::CharlieContyKulla);
float sheenDirectionalAlbedo(float NdotV, float sheenRoughness,
                             SheenModel model = SheenModel::CharlieContyKulla);

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
    /// KHR_materials_anisotropy strength (texture's blue already applied). Above 0 with the GGX
    /// distribution, the base specular lobe is the anisotropic GGX D and V (the Visibility choice
    /// is then ignored, as in the Khronos sample viewer); at 0 nothing changes.
    float anisotropyStrength = 0.0f;
    /// World-space unit direction of the stretch, perpendicular to n: the mesh tangent rotated by
    /// the anisotropy rotation (and the texture's direction). Its bitangent is cross(n, t).
    /// surfaceFromMaterial() leaves the default; callers with geometry set it.
    glm::vec3 anisotropyDirection{1.0f, 0.0f, 0.0f};
    Distribution distribution = Distribution::GGX;
    Visibility visibility = Visibility::SmithGGXSeparable;
    Fresnel fresnel = Fresnel::Schlick;
    Diffuse diffuse = Diffuse::Lambert;
    SheenModel sheenModel = SheenModel::CharlieContyKulla;
    /// Turquin 2019's multiple-scattering energy compensation of the base specular lobe
    /// (core/brdf_energy.h), as FrameSettings::specularMultiScatter switches it on the GPU; off:
    /// the single-scattering lobe.
    bool multipleScattering = true;
};
/// The material's values; anisotropyDirection stays at its default (no geometry here).
Surface surfaceFromMaterial(const Material& m);
/// True when @p s draws the base specular lobe with the anisotropic GGX terms.
bool usesAnisotropy(const Surface& s);
/// The base specular lobe's D x V for one light: the anisotropic GGX pair when
/// usesAnisotropy(@p s), else the material's Distribution and Visibility choices.
float specularDV(const Surface& s, glm::vec3 n, glm::vec3 v, glm::vec3 l, glm::vec3 h, float NdotL,
                 float NdotV, float NdotH, float sin2H, float VdotH, float alpha);

/// Dielectric F0 from IOR and KHR_materials_specular's colour (before the weight).
glm::vec3 dielectricF0(const Surface& s);

/// Outgoing radiance towards @p v per unit illuminance from direction @p l (towards the light):
/// f(l, v) * max(n.l, 0), all lobes layered, the base specular lobe with its multiple-scattering
/// compensation (Surface::multipleScattering). Vectors unit length, world space.
glm::vec3 evalDirectional(const Surface& s, glm::vec3 n, glm::vec3 v, glm::vec3 l);

/// The layered BRDF split into its lobes (twin of Lobes / shadeLobes() in
/// resources/shaders/light_lobes.glsl), for area lights: @p lDiffuse (unit, towards the light's
/// centre) drives the diffuse and sheen lobes, @p lSpecular (unit, towards Karis 2013's
/// representative point) the base specular and clearcoat lobes, whose D is renormalised by
/// lights::areaSpecularNormalization(alpha, @p widen). Each lobe includes its n.l. With
/// lDiffuse = lSpecular and widen = 0 the sum equals evalDirectional().
struct Lobes {
    glm::vec3 diffuse{0.0f}, specular{0.0f}, sheen{0.0f}, clearcoat{0.0f};
    glm::vec3 sum() const { return diffuse + specular + sheen + clearcoat; }
};
Lobes evalLobes(const Surface& s, glm::vec3 n, glm::vec3 v, glm::vec3 lDiffuse, glm::vec3 lSpecular,
                float widen);

} // namespace velvet::brdf
