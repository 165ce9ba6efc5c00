#include "core/brdf.h"

#include "core/brdf_energy.h"
#include "core/lights.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>
#include <numbers>

namespace velvet::brdf {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

float max3(glm::vec3 v) {
    return std::max(v.x, std::max(v.y, v.z));
}
float saturate(float x) {
    return std::clamp(x, 0.0f, 1.0f);
}

} // namespace

float sinSquared(glm::vec3 n, glm::vec3 h) {
    const glm::vec3 c = glm::cross(n, h);
    return std::min(glm::dot(c, c), 1.0f);
}

float logOneMinus(float x) {
    if (x < 0.1f) // -sum x^k / k, truncated after x^7 / 7 (relative error < x^7 / 8 < 2e-8)
        return -x *
               (1.0f + x * (1.0f / 2.0f +
                            x * (1.0f / 3.0f +
                                 x * (1.0f / 4.0f +
                                      x * (1.0f / 5.0f + x * (1.0f / 6.0f + x * (1.0f / 7.0f)))))));
    return std::log(std::max(1.0f - x, 1e-30f));
}

namespace {
float sinSquaredFromCos(float c) {
    return std::max((1.0f - c) * (1.0f + c), 0.0f);
}
} // namespace

// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces" (GGX /
// Trowbridge-Reitz), in Filament's form: the denominator (n.h)^2 (alpha^2 - 1) + 1 is rewritten
// as (n.h alpha)^2 + sin^2 so that it keeps its precision near the peak.
float distributionGGX(float NdotH, float sin2H, float alpha) {
    const float a = NdotH * alpha;
    const float k = alpha / (a * a + sin2H);
    return k * k / kPi;
}
float distributionGGX(float NdotH, float alpha) {
    return distributionGGX(NdotH, sinSquaredFromCos(NdotH), alpha);
}

// Beckmann & Spizzichino 1963, "The Scattering of Electromagnetic Waves from Rough Surfaces"
// (alpha = roughness^2, the slope RMS; normalised as in Walter et al. 2007 eq. 25);
// (c^2 - 1) / (alpha^2 c^2) = -sin^2 / (alpha^2 c^2).
float distributionBeckmann(float NdotH, float sin2H, float alpha) {
    const float a2 = alpha * alpha;
    const float c2 = std::max(NdotH * NdotH, 1e-8f);
    return std::exp(-sin2H / (a2 * c2)) / (kPi * a2 * c2 * c2);
}
float distributionBeckmann(float NdotH, float alpha) {
    return distributionBeckmann(NdotH, sinSquaredFromCos(NdotH), alpha);
}

// Blinn 1977, "Models of Light Reflection for Computer Synthesized Pictures" (exponent
// n = 2 / alpha^2 - 2 as Walter et al. 2007, normalisation (n + 2) / 2pi); (n.h)^n =
// exp(n / 2 ln(1 - sin^2)): n reaches 5e5 at kMinRoughness, where pow() of n.h has no digits left.
float distributionBlinnPhong(float /*NdotH*/, float sin2H, float alpha) {
    const float n = std::max(2.0f / (alpha * alpha) - 2.0f, 0.0f);
    return (n + 2.0f) / (2.0f * kPi) * std::exp(0.5f * n * logOneMinus(sin2H));
}
float distributionBlinnPhong(float NdotH, float alpha) {
    return distributionBlinnPhong(NdotH, sinSquaredFromCos(NdotH), alpha);
}

// Smith 1967 with GGX G1, separable form of glTF 2.0 Appendix B: V = G / (4 |n.l| |n.v|)
float visibilitySmithGGXSeparable(float NdotL, float NdotV, float alpha) {
    const float a2 = alpha * alpha;
    const float gl = NdotL + std::sqrt(a2 + (1.0f - a2) * NdotL * NdotL);
    const float gv = NdotV + std::sqrt(a2 + (1.0f - a2) * NdotV * NdotV);
    return 1.0f / (gl * gv);
}

// Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs"
// (height-correlated Smith-GGX, as Filament's V_SmithGGXCorrelated and the glTF Sample Viewer)
float visibilitySmithGGXCorrelated(float NdotL, float NdotV, float alpha) {
    const float a2 = alpha * alpha;
    const float lambdaV = NdotL * std::sqrt(NdotV * NdotV * (1.0f - a2) + a2);
    const float lambdaL = NdotV * std::sqrt(NdotL * NdotL * (1.0f - a2) + a2);
    return 0.5f / (lambdaV + lambdaL);
}

// Karis 2013, "Real Shading in Unreal Engine 4" (Schlick-GGX, k = alpha / 2)
float visibilitySchlickGGX(float NdotL, float NdotV, float alpha) {
    const float k = alpha * 0.5f;
    return 1.0f / (4.0f * (NdotL * (1.0f - k) + k) * (NdotV * (1.0f - k) + k));
}

// Cook & Torrance 1982, "A Reflectance Model for Computer Graphics" (V-cavities G)
float visibilityCookTorrance(float NdotL, float NdotV, float NdotH, float VdotH) {
    const float c = 2.0f * NdotH / std::max(VdotH, 1e-4f);
    const float g = std::min(1.0f, std::min(c * NdotV, c * NdotL));
    return g / (4.0f * NdotL * NdotV);
}

// Implicit G = n.l n.v (e.g. Hoffman 2010, "Crafting Physically Motivated Shading Models")
float visibilityImplicit() {
    return 0.25f;
}

// Neumann et al. 1999, "Compact Metallic Reflectance Models" (G = n.l n.v / max(n.l, n.v))
float visibilityNeumann(float NdotL, float NdotV) {
    return 1.0f / (4.0f * std::max(NdotL, NdotV));
}

// Kelemen & Szirmay-Kalos 2001, "A Microfacet Based Coupled Specular-Matte BRDF Model"
float visibilityKelemen(float VdotH) {
    return 1.0f / (4.0f * std::max(VdotH * VdotH, 1e-4f));
}

// KHR_materials_anisotropy (Khronos glTF extension, README "Definition"): the direction of the
// stretch has alpha_t = mix(alpha, 1, strength^2), the perpendicular one keeps alpha.
glm::vec2 anisotropicAlphas(float roughness, float strength) {
    const float rough = std::max(roughness, kMinRoughness);
    const float alpha = rough * rough;
    return {glm::mix(alpha, 1.0f, strength * strength), alpha};
}

// Burley 2012, "Physically-Based Shading at Disney", addenda (anisotropic GGX), as the
// KHR_materials_anisotropy README's D_GGX_anisotropic: with a2 = at ab and
// f = (ab t.h, at b.h, a2 n.h), D = a2 (a2 / f.f)^2 / pi.
float distributionGGXAnisotropic(float NdotH, float TdotH, float BdotH, float at, float ab) {
    const float a2 = at * ab;
    const glm::vec3 f(ab * TdotH, at * BdotH, a2 * NdotH);
    const float w2 = a2 / glm::dot(f, f);
    return a2 * w2 * w2 / kPi;
}

// Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", the
// height-correlated Smith term for the anisotropic GGX, as the KHR_materials_anisotropy README's
// V_GGX_anisotropic.
float visibilitySmithGGXCorrelatedAnisotropic(float NdotL, float NdotV, float TdotV, float BdotV,
                                              float TdotL, float BdotL, float at, float ab) {
    const float ggxV = NdotL * glm::length(glm::vec3(at * TdotV, ab * BdotV, NdotV));
    const float ggxL = NdotV * glm::length(glm::vec3(at * TdotL, ab * BdotL, NdotL));
    return saturate(0.5f / (ggxV + ggxL));
}

// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering"
glm::vec3 fresnelSchlick(glm::vec3 f0, glm::vec3 f90, float VdotH) {
    const float x = 1.0f - saturate(VdotH);
    const float x2 = x * x;
    return f0 + (f90 - f0) * (x2 * x2 * x);
}
float fresnelSchlick(float f0, float f90, float VdotH) {
    return fresnelSchlick(glm::vec3(f0), glm::vec3(f90), VdotH).x;
}

// Karis 2013, "Real Shading in Unreal Engine 4" (Schlick with a spherical-gaussian exponent)
glm::vec3 fresnelSchlickSphericalGaussian(glm::vec3 f0, glm::vec3 f90, float VdotH) {
    const float c = saturate(VdotH);
    return f0 + (f90 - f0) * std::exp2((-5.55473f * c - 6.98316f) * c);
}

// Walter et al. 2007 eq. 22 / Cook & Torrance 1982: unpolarised Fresnel of a dielectric, eta = IOR
float fresnelDielectricExact(float VdotH, float eta) {
    const float c = saturate(VdotH);
    const float g2 = eta * eta - 1.0f + c * c;
    if (g2 < 0.0f)
        return 1.0f; // total internal reflection (eta < 1 only)
    const float g = std::sqrt(g2);
    const float a = (g - c) / (g + c);
    const float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
    return 0.5f * a * a * (1.0f + b * b);
}

// Lambert 1760, "Photometria"
glm::vec3 diffuseLambert(glm::vec3 diffuseColor) {
    return diffuseColor / kPi;
}

// Burley 2012, "Physically-Based Shading at Disney" (retro-reflection; energy as published, not
// renormalised; roughness is the perceptual one, as the paper's slider)
glm::vec3 diffuseBurley(glm::vec3 diffuseColor, float roughness, float NdotL, float NdotV,
                        float LdotH) {
    const float fd90 = 0.5f + 2.0f * roughness * LdotH * LdotH;
    const float fl = 1.0f + (fd90 - 1.0f) * std::pow(1.0f - NdotL, 5.0f);
    const float fv = 1.0f + (fd90 - 1.0f) * std::pow(1.0f - NdotV, 5.0f);
    return diffuseColor / kPi * (fl * fv);
}

// Estevez & Kulla 2017, "Production Friendly Microfacet Sheen BRDF" (Charlie D)
float distributionCharlie(float /*NdotH*/, float sin2H, float sheenRoughness) {
    const float alpha = std::max(sheenRoughness, kMinSheenRoughness);
    const float invR = 1.0f / (alpha * alpha);
    return (2.0f + invR) * std::pow(std::max(sin2H, 0.0f), invR * 0.5f) / (2.0f * kPi);
}
float distributionCharlie(float NdotH, float sheenRoughness) {
    return distributionCharlie(NdotH, sinSquaredFromCos(NdotH), sheenRoughness);
}

namespace {
// Conty & Kulla 2017's fitted lambda for the Charlie distribution (as the glTF Sample Viewer).
float sheenLambdaHelper(float x, float alphaG) {
    const float t = (1.0f - alphaG) * (1.0f - alphaG);
    const float a = glm::mix(21.5473f, 25.3245f, t);
    const float b = glm::mix(3.82987f, 3.32435f, t);
    const float c = glm::mix(0.19823f, 0.16801f, t);
    const float d = glm::mix(-1.97760f, -1.27393f, t);
    const float e = glm::mix(-4.32054f, -4.85967f, t);
    // x is 1 - cos above cos 0.5: a cosine that rounds above 1 (a direction along the normal)
    // would take the power of a negative number, NaN, and the path tracer drops a NaN sample.
    x = std::max(x, 0.0f);
    return a / (1.0f + b * std::pow(x, c)) + d * x + e;
}
float sheenLambda(float cosTheta, float alphaG) {
    if (std::abs(cosTheta) < 0.5f)
        return std::exp(sheenLambdaHelper(cosTheta, alphaG));
    return std::exp(2.0f * sheenLambdaHelper(0.5f, alphaG) -
                    sheenLambdaHelper(1.0f - cosTheta, alphaG));
}
} // namespace

// Conty & Kulla 2017, "Revisiting Physically Based Shading at Imageworks" (sheen visibility)
float visibilitySheenContyKulla(float NdotL, float NdotV, float sheenRoughness) {
    const float r = std::max(sheenRoughness, kMinSheenRoughness);
    const float alphaG = r * r;
    const float v = 1.0f / ((1.0f + sheenLambda(NdotV, alphaG) + sheenLambda(NdotL, alphaG)) *
                            (4.0f * NdotV * NdotL));
    return saturate(v);
}

// Ashikhmin & Premoze 2007, "Distribution-based BRDFs" (smooth denominator 4 (n.l + n.v - n.l n.v))
float visibilityAshikhmin(float NdotL, float NdotV) {
    return saturate(1.0f / (4.0f * (NdotL + NdotV - NdotL * NdotV)));
}

// Neubelt & Pettineo 2013, "Crafting a Next-Gen Material Pipeline for The Order: 1886"
// The same form as visibilityAshikhmin (Neubelt & Pettineo adopt Ashikhmin & Premoze's
// denominator; Filament's V_Neubelt and the glTF Sample Viewer's V_Ashikhmin are this line, as is
// three.js's V_Neubelt in seed 003): the two sheen models render identically.
float visibilityNeubelt(float NdotL, float NdotV) {
    return saturate(1.0f / (4.0f * (NdotL + NdotV - NdotL * NdotV)));
}

/// E(v) = integral over the hemisphere of D_Charlie * V_model * (n.l) dl, midpoint rule in
/// (theta_l, phi_l), using the symmetry phi -> -phi.
std::vector<float> integrateSheenAlbedo(SheenModel model) {
    constexpr int N = kSheenLutSize;
    constexpr int kTheta = 96, kPhi = 48;
    std::vector<float> t(size_t(N) * N);
    for (int ri = 0; ri < N; ++ri) {
        const float rough = std::max(float(ri) / float(N - 1), kMinSheenRoughness);
        for (int vi = 0; vi < N; ++vi) {
            const float NdotV = std::max(float(vi) / float(N - 1), 1e-3f);
            const glm::vec3 v(std::sqrt(1.0f - NdotV * NdotV), 0.0f, NdotV);
            double sum = 0.0;
            for (int a = 0; a < kTheta; ++a) {
                const float theta = (float(a) + 0.5f) / kTheta * 0.5f * kPi;
                const float ct = std::cos(theta), st = std::sin(theta);
                for (int b = 0; b < kPhi; ++b) {
                    const float phi = (float(b) + 0.5f) / kPhi * kPi;
                    const glm::vec3 l(st * std::cos(phi), st * std::sin(phi), ct);
                    const glm::vec3 h = glm::normalize(l + v);
                    const float f =
                        distributionCharlie(h.z, rough) * visibilitySheen(model, ct, NdotV, rough);
                    sum += double(f) * ct * st;
                }
            }
            const double dOmega = (0.5 * kPi / kTheta) * (kPi / kPhi) * 2.0;
            t[size_t(ri) * N + vi] = float(std::min(sum * dOmega, 1.0));
        }
    }
    return t;
}

namespace {
// The tables integrateSheenAlbedo() makes, shipped (issue 16: 9.4 million BRDF evaluations took
// about 0.2 s of every process start). Generated by `velvet sheen-table`; test_core_brdf checks
// them against the integration.
#include "core/sheen_albedo_table.inc"
} // namespace

const std::vector<float>& sheenAlbedoLut(SheenModel model) {
    // One table per sheen model (KHR_materials_sheen's albedo scaling needs the albedo of the
    // lobe actually drawn). Ashikhmin and Neubelt are the same visibility function (see
    // visibilityNeubelt), so their tables are equal by construction; both are kept so that every
    // SheenModel has its own entry, as the GPU's three-channel texture has.
    static const std::vector<float> tables[2] = {
        std::vector<float>(std::begin(kShippedSheenAlbedo[0]), std::end(kShippedSheenAlbedo[0])),
        std::vector<float>(std::begin(kShippedSheenAlbedo[1]), std::end(kShippedSheenAlbedo[1]))};
    return model == SheenModel::CharlieContyKulla ? tables[0] : tables[1];
}

float sheenDirectionalAlbedo(float NdotV, float sheenRoughness, SheenModel model) {
    // Bilinear lookup with texel centres at i / (N - 1): the GPU samples the same table at
    // (i * (N - 1) + 0.5) / N with GL_LINEAR and clamp-to-edge, which is the same function.
    const auto& t = sheenAlbedoLut(model);
    constexpr int N = kSheenLutSize;
    const float x = saturate(NdotV) * (N - 1), y = saturate(sheenRoughness) * (N - 1);
    const int x0 = std::min(int(x), N - 2), y0 = std::min(int(y), N - 2);
    const float fx = x - float(x0), fy = y - float(y0);
    const auto at = [&](int xi, int yi) { return t[size_t(yi) * N + xi]; };
    const float a = glm::mix(at(x0, y0), at(x0 + 1, y0), fx);
    const float b = glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx);
    return glm::mix(a, b, fy);
}

// ---- Dispatch (mirrors common_brdf.glsl) ----

float distribution(Distribution which, float NdotH, float sin2H, float alpha) {
    switch (which) {
    case Distribution::Beckmann:
        return distributionBeckmann(NdotH, sin2H, alpha);
    case Distribution::BlinnPhong:
        return distributionBlinnPhong(NdotH, sin2H, alpha);
    case Distribution::GGX:
        break;
    }
    return distributionGGX(NdotH, sin2H, alpha);
}
float distribution(Distribution which, float NdotH, float alpha) {
    return distribution(which, NdotH, sinSquaredFromCos(NdotH), alpha);
}

float visibility(Visibility which, float NdotL, float NdotV, float NdotH, float VdotH,
                 float alpha) {
    switch (which) {
    case Visibility::SmithGGXCorrelated:
        return visibilitySmithGGXCorrelated(NdotL, NdotV, alpha);
    case Visibility::SchlickGGX:
        return visibilitySchlickGGX(NdotL, NdotV, alpha);
    case Visibility::CookTorrance:
        return visibilityCookTorrance(NdotL, NdotV, NdotH, VdotH);
    case Visibility::Implicit:
        return visibilityImplicit();
    case Visibility::Neumann:
        return visibilityNeumann(NdotL, NdotV);
    case Visibility::Kelemen:
        return visibilityKelemen(VdotH);
    case Visibility::SmithGGXSeparable:
        break;
    }
    return visibilitySmithGGXSeparable(NdotL, NdotV, alpha);
}

glm::vec3 fresnelDielectric(Fresnel which, glm::vec3 f0, float ior, float VdotH) {
    switch (which) {
    case Fresnel::SchlickSphericalGaussian:
        return fresnelSchlickSphericalGaussian(f0, glm::vec3(1.0f), VdotH);
    case Fresnel::ExactDielectric: {
        const float f0Exact = fresnelDielectricExact(1.0f, ior);
        const float w =
            (fresnelDielectricExact(VdotH, ior) - f0Exact) / std::max(1.0f - f0Exact, 1e-6f);
        return f0 + (glm::vec3(1.0f) - f0) * w;
    }
    case Fresnel::Schlick:
        break;
    }
    return fresnelSchlick(f0, glm::vec3(1.0f), VdotH);
}

// Metals have no real IOR here, so the exact dielectric choice keeps Schlick for them (a
// complex-IOR conductor Fresnel would need n and k).
glm::vec3 fresnelConductor(Fresnel which, glm::vec3 f0, float VdotH) {
    if (which == Fresnel::SchlickSphericalGaussian)
        return fresnelSchlickSphericalGaussian(f0, glm::vec3(1.0f), VdotH);
    return fresnelSchlick(f0, glm::vec3(1.0f), VdotH);
}

glm::vec3 diffuse(Diffuse which, glm::vec3 diffuseColor, float roughness, float NdotL, float NdotV,
                  float LdotH) {
    if (which == Diffuse::Burley)
        return diffuseBurley(diffuseColor, roughness, NdotL, NdotV, LdotH);
    return diffuseLambert(diffuseColor);
}

// Ashikhmin and Neubelt are the same function (see visibilityNeubelt); both enum values are kept
// because the seed documents name both.
float visibilitySheen(SheenModel which, float NdotL, float NdotV, float sheenRoughness) {
    switch (which) {
    case SheenModel::CharlieAshikhmin:
        return visibilityAshikhmin(NdotL, NdotV);
    case SheenModel::CharlieNeubelt:
        return visibilityNeubelt(NdotL, NdotV);
    case SheenModel::CharlieContyKulla:
        break;
    }
    return visibilitySheenContyKulla(NdotL, NdotV, sheenRoughness);
}

Surface surfaceFromMaterial(const Material& m) {
    Surface s;
    s.baseColor = m.color(ParamId::BaseColor);
    s.metallic = m.scalar(ParamId::Metallic);
    s.roughness = m.scalar(ParamId::Roughness);
    s.specularWeight = m.scalar(ParamId::SpecularWeight);
    s.specularColor = m.color(ParamId::SpecularColor);
    s.ior = m.scalar(ParamId::Ior);
    s.sheenColor = m.scalar(ParamId::SheenWeight) * m.color(ParamId::SheenColor);
    s.sheenRoughness = m.scalar(ParamId::SheenRoughness);
    s.clearcoat = m.scalar(ParamId::ClearcoatWeight);
    s.clearcoatRoughness = m.scalar(ParamId::ClearcoatRoughness);
    s.emissive = m.color(ParamId::EmissiveColor) * m.scalar(ParamId::EmissiveStrength);
    s.distribution = m.distribution();
    s.visibility = m.visibility();
    s.fresnel = m.fresnel();
    s.diffuse = m.diffuse();
    s.sheenModel = m.sheenModel();
    s.anisotropyStrength = m.scalar(ParamId::AnisotropyStrength);
    return s;
}

bool usesAnisotropy(const Surface& s) {
    return s.anisotropyStrength > 0.0f && s.distribution == Distribution::GGX;
}

float specularDV(const Surface& s, glm::vec3 n, glm::vec3 v, glm::vec3 l, glm::vec3 h, float NdotL,
                 float NdotV, float NdotH, float sin2H, float VdotH, float alpha) {
    if (!usesAnisotropy(s))
        return distribution(s.distribution, NdotH, sin2H, alpha) *
               visibility(s.visibility, NdotL, NdotV, NdotH, VdotH, alpha);
    // KHR_materials_anisotropy: t the stretch direction, b = n x t; the height-correlated V
    // replaces the Visibility choice (the Khronos sample viewer does the same).
    const glm::vec3 t = s.anisotropyDirection;
    const glm::vec3 b = glm::cross(n, t);
    const glm::vec2 a = anisotropicAlphas(s.roughness, s.anisotropyStrength);
    return distributionGGXAnisotropic(NdotH, glm::dot(t, h), glm::dot(b, h), a.x, a.y) *
           visibilitySmithGGXCorrelatedAnisotropic(NdotL, NdotV, glm::dot(t, v), glm::dot(b, v),
                                                   glm::dot(t, l), glm::dot(b, l), a.x, a.y);
}

glm::vec3 dielectricF0(const Surface& s) {
    const float r = (s.ior - 1.0f) / (s.ior + 1.0f);
    return glm::min(glm::vec3(r * r) * s.specularColor, glm::vec3(1.0f));
}

glm::vec3 evalDirectional(const Surface& s, glm::vec3 n, glm::vec3 v, glm::vec3 l) {
    // Mirrors shadeDirectional() in common_brdf.glsl line for line.
    const float NdotL = glm::dot(n, l);
    if (NdotL <= 0.0f)
        return glm::vec3(0.0f);
    const float NdotV = std::max(glm::dot(n, v), 1e-4f);
    const glm::vec3 h = glm::normalize(l + v);
    const float NdotH = saturate(glm::dot(n, h));
    const float sin2H = sinSquared(n, h);
    const float VdotH = saturate(glm::dot(v, h));

    const float rough = std::max(s.roughness, kMinRoughness);
    const float alpha = rough * rough;
    const float specular = specularDV(s, n, v, l, h, NdotL, NdotV, NdotH, sin2H, VdotH, alpha);

    // glTF 2.0 Appendix B + KHR_materials_specular: fresnel_mix for the dielectric,
    // conductor_fresnel for the metal, mixed by metallic. LdotH = VdotH (h is the half vector).
    const glm::vec3 fDielectric =
        s.specularWeight * fresnelDielectric(s.fresnel, dielectricF0(s), s.ior, VdotH);
    const glm::vec3 fMetal = fresnelConductor(s.fresnel, s.baseColor, VdotH);
    const glm::vec3 diffuseLobe = diffuse(s.diffuse, s.baseColor, rough, NdotL, NdotV, VdotH);
    // Turquin 2019 (core/brdf_energy.h): the energy single scattering loses, per F0 of each.
    const glm::vec3 dielectric =
        (1.0f - max3(fDielectric)) * diffuseLobe +
        fDielectric * specular *
            multipleScatteringFactor(dielectricF0(s), NdotV, rough, s.multipleScattering);
    const glm::vec3 metal =
        fMetal * specular *
        multipleScatteringFactor(s.baseColor, NdotV, rough, s.multipleScattering);
    glm::vec3 f = glm::mix(dielectric, metal, s.metallic);

    // KHR_materials_sheen: sheen on top, base scaled by the albedo of the sheen lobe drawn (one
    // table per sheen model; see sheenDirectionalAlbedo()).
    if (max3(s.sheenColor) > 0.0f) {
        const float sheen = distributionCharlie(NdotH, sin2H, s.sheenRoughness) *
                            visibilitySheen(s.sheenModel, NdotL, NdotV, s.sheenRoughness);
        const float scaling =
            std::min(1.0f - max3(s.sheenColor) *
                                sheenDirectionalAlbedo(NdotV, s.sheenRoughness, s.sheenModel),
                     1.0f - max3(s.sheenColor) *
                                sheenDirectionalAlbedo(NdotL, s.sheenRoughness, s.sheenModel));
        f = f * scaling + s.sheenColor * sheen;
    }

    // KHR_materials_clearcoat: the base is attenuated by the coat's Fresnel at n.v. The coat keeps
    // the extension's fixed terms whatever the base lobe's choices.
    if (s.clearcoat > 0.0f) {
        const float cr = std::max(s.clearcoatRoughness, kMinRoughness);
        const float ca = cr * cr;
        const float coat = fresnelSchlick(0.04f, 1.0f, VdotH) * distributionGGX(NdotH, sin2H, ca) *
                           visibilitySmithGGXSeparable(NdotL, NdotV, ca);
        const float fc = fresnelSchlick(0.04f, 1.0f, NdotV);
        f = f * (1.0f - s.clearcoat * fc) + s.clearcoat * coat;
    }
    return f * NdotL;
}

Lobes evalLobes(const Surface& s, glm::vec3 n, glm::vec3 v, glm::vec3 lDiffuse, glm::vec3 lSpecular,
                float widen) {
    // Mirrors shadeLobes() in light_lobes.glsl line for line.
    Lobes o;
    const float NdotV = std::max(glm::dot(n, v), 1e-4f);
    const float rough = std::max(s.roughness, kMinRoughness);
    const float alpha = rough * rough;
    const float fc = s.clearcoat > 0.0f ? s.clearcoat * fresnelSchlick(0.04f, 1.0f, NdotV) : 0.0f;
    const float coatAttenuation = 1.0f - fc;
    const bool hasSheen = max3(s.sheenColor) > 0.0f;
    const float sheenAlbedoV =
        hasSheen ? sheenDirectionalAlbedo(NdotV, s.sheenRoughness, s.sheenModel) : 0.0f;
    auto sheenScaling = [&](float NdotL) {
        return std::min(1.0f - max3(s.sheenColor) * sheenAlbedoV,
                        1.0f - max3(s.sheenColor) *
                                   sheenDirectionalAlbedo(NdotL, s.sheenRoughness, s.sheenModel));
    };

    const float NdotLd = glm::dot(n, lDiffuse);
    if (NdotLd > 0.0f) {
        const glm::vec3 h = glm::normalize(lDiffuse + v);
        const float VdotH = saturate(glm::dot(v, h));
        const glm::vec3 fDielectric =
            s.specularWeight * fresnelDielectric(s.fresnel, dielectricF0(s), s.ior, VdotH);
        const glm::vec3 diffuseLobe = diffuse(s.diffuse, s.baseColor, rough, NdotLd, NdotV, VdotH);
        float scaling = 1.0f;
        if (hasSheen) {
            scaling = sheenScaling(NdotLd);
            const float NdotH = saturate(glm::dot(n, h));
            const float sheen = distributionCharlie(NdotH, sinSquared(n, h), s.sheenRoughness) *
                                visibilitySheen(s.sheenModel, NdotLd, NdotV, s.sheenRoughness);
            o.sheen = s.sheenColor * sheen * coatAttenuation * NdotLd;
        }
        o.diffuse = (1.0f - s.metallic) * (1.0f - max3(fDielectric)) * diffuseLobe * scaling *
                    coatAttenuation * NdotLd;
    }

    const float NdotL = glm::dot(n, lSpecular);
    if (NdotL > 0.0f) {
        const glm::vec3 h = glm::normalize(lSpecular + v);
        const float NdotH = saturate(glm::dot(n, h));
        const float sin2H = sinSquared(n, h);
        const float VdotH = saturate(glm::dot(v, h));
        const float specular =
            specularDV(s, n, v, lSpecular, h, NdotL, NdotV, NdotH, sin2H, VdotH, alpha) *
            lights::areaSpecularNormalization(alpha, widen);
        const glm::vec3 fDielectric =
            s.specularWeight * fresnelDielectric(s.fresnel, dielectricF0(s), s.ior, VdotH);
        const glm::vec3 fMetal = fresnelConductor(s.fresnel, s.baseColor, VdotH);
        const float scaling = hasSheen ? sheenScaling(NdotL) : 1.0f;
        o.specular = glm::mix(fDielectric * multipleScatteringFactor(dielectricF0(s), NdotV, rough,
                                                                     s.multipleScattering),
                              fMetal * multipleScatteringFactor(s.baseColor, NdotV, rough,
                                                                s.multipleScattering),
                              s.metallic) *
                     specular * scaling * coatAttenuation * NdotL;
        if (s.clearcoat > 0.0f) {
            const float cr = std::max(s.clearcoatRoughness, kMinRoughness);
            const float ca = cr * cr;
            const float coat = fresnelSchlick(0.04f, 1.0f, VdotH) *
                               distributionGGX(NdotH, sin2H, ca) *
                               visibilitySmithGGXSeparable(NdotL, NdotV, ca) *
                               lights::areaSpecularNormalization(ca, widen);
            o.clearcoat = glm::vec3(s.clearcoat * coat * NdotL);
        }
    }
    return o;
}

} // namespace velvet::brdf
