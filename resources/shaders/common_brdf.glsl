// BRDF terms, in Filament's surface_brdf.fs layout: configuration, implementations, dispatch.
// Default configuration: glTF 2.0 Appendix B metal-rough (GGX D, separable Smith-GGX V, Schlick F,
// Lambert diffuse) layered with KHR_materials_specular/_ior, _sheen (Charlie D, Conty-Kulla V) and
// _clearcoat. Every other term the seed documents compare is selectable per material at run time
// (GpuMaterial.terms / terms2, a uniform branch: switching compiles nothing). Each implementation
// cites its paper on its first line; the C++ twins in core/brdf.cpp have the same names, order
// and clamps.
#include "common_math.glsl"
#include "render_bindings.glsl"

// ---- Specialisation (render/lighting_features.h) ----
// The lighting pass is built per set of features the frame draws. FIXED_<TERM> n compiles one term
// choice in (the dispatch below folds to it); WITH_<LOBE> 0 compiles a lobe out. Undefined: every
// choice at run time and every lobe, the generic program every other pass uses.
#ifndef WITH_SHEEN
#define WITH_SHEEN 1
#endif
#ifndef WITH_CLEARCOAT
#define WITH_CLEARCOAT 1
#endif
#ifndef WITH_ANISOTROPY
#define WITH_ANISOTROPY 1
#endif
#ifndef WITH_LOBE_CHANNELS
#define WITH_LOBE_CHANNELS 1
#endif

#define MIN_ROUGHNESS 0.045
#define MIN_SHEEN_ROUGHNESS 0.07
#define SHEEN_LUT_SIZE 32.0

// ---- Configuration ----
// Term ids (DISTRIBUTION_*, VISIBILITY_*, FRESNEL_*, DIFFUSE_*, SHEEN_CHARLIE_*): the values of
// the enums in core/material.h, as packed in GpuMaterial.terms (D, V, F, diffuse) and terms2.x
// (sheen model), generated into render_interface.glsl from render/render_interface.cpp.
#include "render_interface.glsl"

layout(binding = BINDING_SHEEN_LUT_TEX) uniform sampler2D uSheenLut;

// ---- Implementations ----

// sin^2 of the angle between unit n and h as |n x h|^2 (twin: velvet::brdf::sinSquared). Near
// the lobe peak 1 - (n.h)^2 cancels: one ulp of n.h is 3 % of alpha^2 at MIN_ROUGHNESS.
float sinSquared(vec3 n, vec3 h) {
    vec3 c = cross(n, h);
    return min(dot(c, c), 1.0);
}

// ln(1 - x), x in [0, 1]: a series below 0.1 (GLSL's log() is only 2^-21 accurate in absolute
// terms near 1, which Blinn-Phong's exponents of up to 5e5 would amplify), log() above.
float logOneMinus(float x) {
    if (x < 0.1)
        return -x * (1.0 + x * (1.0 / 2.0 + x * (1.0 / 3.0 + x * (1.0 / 4.0 +
               x * (1.0 / 5.0 + x * (1.0 / 6.0 + x * (1.0 / 7.0)))))));
    return log(max(1.0 - x, 1e-30));
}

float sinSquaredFromCos(float c) {
    return max((1.0 - c) * (1.0 + c), 0.0);
}

// Every D takes n.h and sin2H = sinSquared(n, h); the (n.h, alpha) overloads derive sin2H from
// an exact cosine and are not for shading.

// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces" (GGX / Trowbridge-Reitz)
// in Filament's form: (n.h)^2 (alpha^2 - 1) + 1 = (n.h alpha)^2 + sin^2.
float distributionGGX(float NdotH, float sin2H, float alpha) {
    float a = NdotH * alpha;
    float k = alpha / (a * a + sin2H);
    return k * k / PI;
}
float distributionGGX(float NdotH, float alpha) {
    return distributionGGX(NdotH, sinSquaredFromCos(NdotH), alpha);
}

// Beckmann & Spizzichino 1963, "The Scattering of Electromagnetic Waves from Rough Surfaces"
// (alpha = roughness^2, the slope RMS; normalised as in Walter et al. 2007 eq. 25);
// (c^2 - 1) / (alpha^2 c^2) = -sin^2 / (alpha^2 c^2).
float distributionBeckmann(float NdotH, float sin2H, float alpha) {
    float a2 = alpha * alpha;
    float c2 = max(NdotH * NdotH, 1e-8);
    return exp(-sin2H / (a2 * c2)) / (PI * a2 * c2 * c2);
}
float distributionBeckmann(float NdotH, float alpha) {
    return distributionBeckmann(NdotH, sinSquaredFromCos(NdotH), alpha);
}

// Blinn 1977, "Models of Light Reflection for Computer Synthesized Pictures" (exponent
// n = 2 / alpha^2 - 2 as Walter et al. 2007, normalisation (n + 2) / 2pi);
// (n.h)^n = exp(n / 2 ln(1 - sin^2)).
float distributionBlinnPhong(float NdotH, float sin2H, float alpha) {
    float n = max(2.0 / (alpha * alpha) - 2.0, 0.0);
    return (n + 2.0) / (2.0 * PI) * exp(0.5 * n * logOneMinus(sin2H));
}
float distributionBlinnPhong(float NdotH, float alpha) {
    return distributionBlinnPhong(NdotH, sinSquaredFromCos(NdotH), alpha);
}

// Smith 1967 with GGX G1, separable form of glTF 2.0 Appendix B: V = G / (4 |n.l| |n.v|)
float visibilitySmithGGXSeparable(float NdotL, float NdotV, float alpha) {
    float a2 = alpha * alpha;
    float gl = NdotL + sqrt(a2 + (1.0 - a2) * NdotL * NdotL);
    float gv = NdotV + sqrt(a2 + (1.0 - a2) * NdotV * NdotV);
    return 1.0 / (gl * gv);
}

// Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs"
// (height-correlated Smith-GGX, as Filament's V_SmithGGXCorrelated and the glTF Sample Viewer)
float visibilitySmithGGXCorrelated(float NdotL, float NdotV, float alpha) {
    float a2 = alpha * alpha;
    float lambdaV = NdotL * sqrt(NdotV * NdotV * (1.0 - a2) + a2);
    float lambdaL = NdotV * sqrt(NdotL * NdotL * (1.0 - a2) + a2);
    return 0.5 / (lambdaV + lambdaL);
}

// Karis 2013, "Real Shading in Unreal Engine 4" (Schlick-GGX, k = alpha / 2)
float visibilitySchlickGGX(float NdotL, float NdotV, float alpha) {
    float k = alpha * 0.5;
    return 1.0 / (4.0 * (NdotL * (1.0 - k) + k) * (NdotV * (1.0 - k) + k));
}

// Cook & Torrance 1982, "A Reflectance Model for Computer Graphics" (V-cavities G)
float visibilityCookTorrance(float NdotL, float NdotV, float NdotH, float VdotH) {
    float c = 2.0 * NdotH / max(VdotH, 1e-4);
    float g = min(1.0, min(c * NdotV, c * NdotL));
    return g / (4.0 * NdotL * NdotV);
}

// Implicit G = n.l n.v (e.g. Hoffman 2010, "Crafting Physically Motivated Shading Models")
float visibilityImplicit() {
    return 0.25;
}

// Neumann et al. 1999, "Compact Metallic Reflectance Models" (G = n.l n.v / max(n.l, n.v))
float visibilityNeumann(float NdotL, float NdotV) {
    return 1.0 / (4.0 * max(NdotL, NdotV));
}

// Kelemen & Szirmay-Kalos 2001, "A Microfacet Based Coupled Specular-Matte BRDF Model"
float visibilityKelemen(float VdotH) {
    return 1.0 / (4.0 * max(VdotH * VdotH, 1e-4));
}

// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering"
vec3 fresnelSchlick(vec3 f0, vec3 f90, float VdotH) {
    float x = 1.0 - saturate(VdotH);
    float x2 = x * x;
    return f0 + (f90 - f0) * (x2 * x2 * x);
}
float fresnelSchlick(float f0, float f90, float VdotH) {
    return fresnelSchlick(vec3(f0), vec3(f90), VdotH).x;
}

// Karis 2013, "Real Shading in Unreal Engine 4" (Schlick with a spherical-gaussian exponent)
vec3 fresnelSchlickSphericalGaussian(vec3 f0, vec3 f90, float VdotH) {
    float c = saturate(VdotH);
    return f0 + (f90 - f0) * exp2((-5.55473 * c - 6.98316) * c);
}

// Walter et al. 2007 eq. 22 / Cook & Torrance 1982: unpolarised Fresnel of a dielectric, eta = IOR
float fresnelDielectricExact(float VdotH, float eta) {
    float c = saturate(VdotH);
    float g2 = eta * eta - 1.0 + c * c;
    if (g2 < 0.0)
        return 1.0; // total internal reflection (eta < 1 only)
    float g = sqrt(g2);
    float a = (g - c) / (g + c);
    float b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

// Lambert 1760, "Photometria"
vec3 diffuseLambert(vec3 diffuseColor) {
    return diffuseColor / PI;
}

// Burley 2012, "Physically-Based Shading at Disney" (retro-reflection; energy as published, not
// renormalised; roughness is the perceptual one, as the paper's slider)
vec3 diffuseBurley(vec3 diffuseColor, float roughness, float NdotL, float NdotV, float LdotH) {
    float fd90 = 0.5 + 2.0 * roughness * LdotH * LdotH;
    float fl = 1.0 + (fd90 - 1.0) * pow(1.0 - NdotL, 5.0);
    float fv = 1.0 + (fd90 - 1.0) * pow(1.0 - NdotV, 5.0);
    return diffuseColor / PI * (fl * fv);
}

// Estevez & Kulla 2017, "Production Friendly Microfacet Sheen BRDF" (Charlie D)
float distributionCharlie(float NdotH, float sin2H, float sheenRoughness) {
    float alpha = max(sheenRoughness, MIN_SHEEN_ROUGHNESS);
    float invR = 1.0 / (alpha * alpha);
    return (2.0 + invR) * pow(max(sin2H, 0.0), invR * 0.5) / (2.0 * PI);
}
float distributionCharlie(float NdotH, float sheenRoughness) {
    return distributionCharlie(NdotH, sinSquaredFromCos(NdotH), sheenRoughness);
}

float sheenLambdaHelper(float x, float alphaG) {
    float t = (1.0 - alphaG) * (1.0 - alphaG);
    float a = mix(21.5473, 25.3245, t);
    float b = mix(3.82987, 3.32435, t);
    float c = mix(0.19823, 0.16801, t);
    float d = mix(-1.97760, -1.27393, t);
    float e = mix(-4.32054, -4.85967, t);
    x = max(x, 0.0); // as the twin: a cosine rounded above 1 would take pow of a negative number
    return a / (1.0 + b * pow(x, c)) + d * x + e;
}
// Lambda(cos) = exp(L(cos)) below cos 0.5, exp(2 L(0.5) - L(1 - cos)) above (the twin's two
// branches), written with one L per call and L(0.5) (@p helperHalf) computed once per pair:
// llvmpipe runs both sides of a branch, so the branchy form cost three L's (each a pow) per call.
float sheenLambda(float cosTheta, float alphaG, float helperHalf) {
    bool below = abs(cosTheta) < 0.5;
    float h = sheenLambdaHelper(below ? cosTheta : 1.0 - cosTheta, alphaG);
    return exp(below ? h : 2.0 * helperHalf - h);
}

// Conty & Kulla 2017, "Revisiting Physically Based Shading at Imageworks" (sheen visibility)
float visibilitySheenContyKulla(float NdotL, float NdotV, float sheenRoughness) {
    float r = max(sheenRoughness, MIN_SHEEN_ROUGHNESS);
    float alphaG = r * r;
    float half_ = sheenLambdaHelper(0.5, alphaG);
    return saturate(1.0 / ((1.0 + sheenLambda(NdotV, alphaG, half_) +
                            sheenLambda(NdotL, alphaG, half_)) *
                           (4.0 * NdotV * NdotL)));
}

// Ashikhmin & Premoze 2007, "Distribution-based BRDFs" (smooth denominator 4 (n.l + n.v - n.l n.v))
float visibilityAshikhmin(float NdotL, float NdotV) {
    return saturate(1.0 / (4.0 * (NdotL + NdotV - NdotL * NdotV)));
}

// Neubelt & Pettineo 2013, "Crafting a Next-Gen Material Pipeline for The Order: 1886"
// The same form as visibilityAshikhmin (Neubelt & Pettineo adopt Ashikhmin & Premoze's
// denominator; Filament's V_Neubelt and the glTF Sample Viewer's V_Ashikhmin are this line, as is
// three.js's V_Neubelt in seed 003): the two sheen models render identically.
float visibilityNeubelt(float NdotL, float NdotV) {
    return saturate(1.0 / (4.0 * (NdotL + NdotV - NdotL * NdotV)));
}

// Karis 2014, "Physically Based Shading on Mobile" (analytic environment BRDF approximation)
vec2 envBrdfApprox(float roughness, float NdotV) {
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    vec4 r = roughness * c0 + c1;
    float a004 = min(r.x * r.x, exp2(-9.28 * NdotV)) * r.x + r.y;
    return vec2(-1.04, 1.04) * a004 + r.zw;
}

// Directional albedo of the sheen lobe of each sheen model, tabulated on the CPU (core/brdf.cpp,
// sheenAlbedoLut) and uploaded by render/sheen_lut.cpp: red Conty-Kulla, green Ashikhmin and
// Neubelt (one visibility function, one table).
float sheenDirectionalAlbedo(float NdotV, float sheenRoughness, int model) {
    vec2 uv = (vec2(saturate(NdotV), saturate(sheenRoughness)) * (SHEEN_LUT_SIZE - 1.0) + 0.5) /
              SHEEN_LUT_SIZE;
#ifdef FIXED_SHEEN_MODEL
    model = FIXED_SHEEN_MODEL;
#endif
    return textureLod(uSheenLut, uv, 0.0)[clamp(model, 0, 1)];
}

// The diffuse term's directional albedo relative to Lambert's, for image-based light (twin:
// velvet::brdf::diffuseDirectionalAlbedo, core/diffuse_albedo.h): 1 for Lambert, whose irradiance
// term is exact; Burley 2012's is not energy conserving (below 1 when smooth, above 1 towards
// grazing when rough), its albedo pre-integrated on the CPU into the blue channel (as Lagarde & de
// Rousiers 2014 pre-integrate their Disney diffuse for image-based light).
float diffuseDirectionalAlbedo(int which, float NdotV, float perceptualRoughness) {
#ifdef FIXED_DIFFUSE
    which = FIXED_DIFFUSE;
#endif
    if (which != DIFFUSE_BURLEY)
        return 1.0;
    vec2 uv = (vec2(saturate(NdotV), saturate(perceptualRoughness)) * (SHEEN_LUT_SIZE - 1.0) + 0.5) /
              SHEEN_LUT_SIZE;
    return textureLod(uSheenLut, uv, 0.0).b;
}

// Whether multiple-scattering energy is on, for direct and image-based light alike
// (FrameSettings::specularMultiScatter: the IblBlock's state.w, or compiled in as
// FIXED_MULTIPLE_SCATTERING by render/lighting_features.h).
bool multipleScatteringOn() {
#ifdef FIXED_MULTIPLE_SCATTERING
    return FIXED_MULTIPLE_SCATTERING == 1;
#else
    return ibl.state.w > 0.5;
#endif
}

// Directional albedo E(n.v, roughness) of the single-scattering base specular lobe with F = 1
// (the DFG LUT's A + B, default GGX model), tabulated on the CPU (core/brdf_energy.cpp) into the
// sheen texture's alpha channel, so every pass that shades direct light already has it bound.
float specularDirectionalAlbedo(float NdotV, float perceptualRoughness) {
    vec2 uv = (vec2(saturate(NdotV), saturate(perceptualRoughness)) * (SHEEN_LUT_SIZE - 1.0) + 0.5) /
              SHEEN_LUT_SIZE;
    return textureLod(uSheenLut, uv, 0.0).a;
}

// Turquin 2019, "Practical multiple scattering compensation for microfacet models" (eq. 8): the
// base specular lobe of Fresnel F0 scaled by 1 + F0 (1 - E) / E, so a white rough metal reflects
// all the direct light it receives, as the image-based light's Fdez-Aguera 2019 term does
// (specularAlbedo() in common_environment.glsl). Off (FrameSettings::specularMultiScatter, the
// IblBlock's state.w or FIXED_MULTIPLE_SCATTERING 0): 1. Mirrors
// velvet::brdf::multipleScatteringFactor().
vec3 multipleScatteringFactor(vec3 f0, float NdotV, float rough) {
    if (!multipleScatteringOn())
        return vec3(1.0);
    float e = specularDirectionalAlbedo(NdotV, rough);
    return 1.0 + f0 * ((1.0 - e) / e);
}

// ---- Dispatch ----
// Term choice per material: a uniform branch on GpuMaterial.terms (no recompilation). The
// clearcoat lobe keeps KHR_materials_clearcoat's fixed terms (GGX, separable Smith-GGX, Schlick
// with F0 = 0.04); the choices apply to the base lobes and the sheen. Direct lights use them; the
// ambient/IBL path keeps the default model's split-sum approximation for the specular lobe and
// takes the diffuse choice through its directional albedo (diffuseDirectionalAlbedo).

// Normal distribution D(h), alpha = roughness^2, sin2H = sinSquared(n, h).
float distribution(int which, float NdotH, float sin2H, float alpha) {
#ifdef FIXED_DISTRIBUTION
    which = FIXED_DISTRIBUTION;
#endif
    if (which == DISTRIBUTION_BECKMANN)
        return distributionBeckmann(NdotH, sin2H, alpha);
    if (which == DISTRIBUTION_BLINN_PHONG)
        return distributionBlinnPhong(NdotH, sin2H, alpha);
    return distributionGGX(NdotH, sin2H, alpha);
}
float distribution(int which, float NdotH, float alpha) {
    return distribution(which, NdotH, sinSquaredFromCos(NdotH), alpha);
}

// Visibility V = G / (4 n.l n.v), for every choice.
float visibility(int which, float NdotL, float NdotV, float NdotH, float VdotH, float alpha) {
#ifdef FIXED_VISIBILITY
    which = FIXED_VISIBILITY;
#endif
    if (which == VISIBILITY_SMITH_GGX_CORRELATED)
        return visibilitySmithGGXCorrelated(NdotL, NdotV, alpha);
    if (which == VISIBILITY_SCHLICK_GGX)
        return visibilitySchlickGGX(NdotL, NdotV, alpha);
    if (which == VISIBILITY_COOK_TORRANCE)
        return visibilityCookTorrance(NdotL, NdotV, NdotH, VdotH);
    if (which == VISIBILITY_IMPLICIT)
        return visibilityImplicit();
    if (which == VISIBILITY_NEUMANN)
        return visibilityNeumann(NdotL, NdotV);
    if (which == VISIBILITY_KELEMEN)
        return visibilityKelemen(VdotH);
    return visibilitySmithGGXSeparable(NdotL, NdotV, alpha);
}

// Dielectric Fresnel (f90 = 1). The exact form keeps KHR_materials_specular's coloured F0 by
// rescaling its angular shape: F = f0 + (1 - f0) (Fexact - F0exact) / (1 - F0exact), which is
// exactly Fexact(IOR) when the specular colour is white.
vec3 fresnelDielectric(int which, vec3 f0, float ior, float VdotH) {
#ifdef FIXED_FRESNEL
    which = FIXED_FRESNEL;
#endif
    if (which == FRESNEL_SCHLICK_SPHERICAL_GAUSSIAN)
        return fresnelSchlickSphericalGaussian(f0, vec3(1.0), VdotH);
    if (which == FRESNEL_EXACT_DIELECTRIC) {
        float f0Exact = fresnelDielectricExact(1.0, ior);
        float w = (fresnelDielectricExact(VdotH, ior) - f0Exact) / max(1.0 - f0Exact, 1e-6);
        return f0 + (vec3(1.0) - f0) * w;
    }
    return fresnelSchlick(f0, vec3(1.0), VdotH);
}

// Conductor Fresnel, F0 = base colour. Metals have no real IOR here, so the exact dielectric
// choice keeps Schlick for them (a complex-IOR conductor Fresnel would need n and k).
vec3 fresnelConductor(int which, vec3 f0, float VdotH) {
#ifdef FIXED_FRESNEL
    which = FIXED_FRESNEL;
#endif
    if (which == FRESNEL_SCHLICK_SPHERICAL_GAUSSIAN)
        return fresnelSchlickSphericalGaussian(f0, vec3(1.0), VdotH);
    return fresnelSchlick(f0, vec3(1.0), VdotH);
}

vec3 diffuse(int which, vec3 diffuseColor, float roughness, float NdotL, float NdotV,
             float LdotH) {
#ifdef FIXED_DIFFUSE
    which = FIXED_DIFFUSE;
#endif
    if (which == DIFFUSE_BURLEY)
        return diffuseBurley(diffuseColor, roughness, NdotL, NdotV, LdotH);
    return diffuseLambert(diffuseColor);
}

// Sheen visibility paired with Charlie D. Ashikhmin and Neubelt are the same function (see
// visibilityNeubelt); both enum values are kept because the seed documents name both.
float visibilitySheen(int which, float NdotL, float NdotV, float sheenRoughness) {
#ifdef FIXED_SHEEN_MODEL
    which = FIXED_SHEEN_MODEL;
#endif
    if (which == SHEEN_CHARLIE_ASHIKHMIN)
        return visibilityAshikhmin(NdotL, NdotV);
    if (which == SHEEN_CHARLIE_NEUBELT)
        return visibilityNeubelt(NdotL, NdotV);
    return visibilitySheenContyKulla(NdotL, NdotV, sheenRoughness);
}

struct Surface {
    vec3 baseColor;
    float metallic;
    float roughness;
    float specularWeight;
    vec3 specularColor;
    float ior;
    vec3 sheenColor;
    float sheenRoughness;
    float clearcoat;
    float clearcoatRoughness;
    vec3 clearcoatNormal; // KHR_materials_clearcoat: the coat's own normal (the base's: n)
    vec3 emissive;
    ivec4 terms; // distribution, visibility, fresnel, diffuse (core/material.h enums)
    int sheenModel;
    float anisotropyStrength; // KHR_materials_anisotropy (0: isotropic)
    vec3 anisotropyDirection; // world-space unit stretch direction, perpendicular to n
};

// The lobe values a Surface has when nothing sets them: isotropic, the coat on the base normal.
void setIsotropicSingleNormal(inout Surface s, vec3 n) {
    s.clearcoatNormal = n;
    s.anisotropyStrength = 0.0;
    s.anisotropyDirection = vec3(1.0, 0.0, 0.0);
}

// ---- Anisotropic GGX (KHR_materials_anisotropy; twins in core/brdf.cpp) ----------------------
// The stretch direction has alpha_t = mix(alpha, 1, strength^2); the perpendicular one alpha.
vec2 anisotropicAlphas(float roughness, float strength) {
    float rough = max(roughness, MIN_ROUGHNESS);
    float alpha = rough * rough;
    return vec2(mix(alpha, 1.0, strength * strength), alpha);
}
// Burley 2012, "Physically-Based Shading at Disney" (anisotropic GGX), as the extension's
// D_GGX_anisotropic: a2 = at ab, f = (ab t.h, at b.h, a2 n.h), D = a2 (a2 / f.f)^2 / pi.
float distributionGGXAnisotropic(float NdotH, float TdotH, float BdotH, float at, float ab) {
    float a2 = at * ab;
    vec3 f = vec3(ab * TdotH, at * BdotH, a2 * NdotH);
    float w2 = a2 / dot(f, f);
    return a2 * w2 * w2 / PI;
}
// Heitz 2014, the height-correlated Smith term of the anisotropic GGX (V_GGX_anisotropic).
float visibilitySmithGGXCorrelatedAnisotropic(float NdotL, float NdotV, float TdotV, float BdotV,
                                              float TdotL, float BdotL, float at, float ab) {
    float ggxV = NdotL * length(vec3(at * TdotV, ab * BdotV, NdotV));
    float ggxL = NdotV * length(vec3(at * TdotL, ab * BdotL, NdotL));
    return saturate(0.5 / (ggxV + ggxL));
}
bool usesAnisotropy(Surface s) {
#if !WITH_ANISOTROPY
    return false;
#endif
    return s.anisotropyStrength > 0.0 && s.terms.x == 0; // GGX only (core/material.h)
}
// The base specular lobe's D x V: the anisotropic pair when the surface is anisotropic (the
// Visibility choice is then ignored, as in the Khronos sample viewer), else the term choices.
float specularDV(Surface s, vec3 n, vec3 v, vec3 l, vec3 h, float NdotL, float NdotV,
                 float NdotH, float sin2H, float VdotH, float alpha) {
    if (!usesAnisotropy(s))
        return distribution(s.terms.x, NdotH, sin2H, alpha) *
               visibility(s.terms.y, NdotL, NdotV, NdotH, VdotH, alpha);
    vec3 t = s.anisotropyDirection;
    vec3 b = cross(n, t);
    vec2 a = anisotropicAlphas(s.roughness, s.anisotropyStrength);
    return distributionGGXAnisotropic(NdotH, dot(t, h), dot(b, h), a.x, a.y) *
           visibilitySmithGGXCorrelatedAnisotropic(NdotL, NdotV, dot(t, v), dot(b, v), dot(t, l),
                                                   dot(b, l), a.x, a.y);
}

// The clear coat's lobe for one light through its own normal @p nc (KHR_materials_clearcoat):
// Fresnel at the half vector times GGX at the coat roughness, n.l included; 0 below its horizon.
float clearcoatLobe(Surface s, vec3 nc, vec3 v, vec3 l, float widenNormalization) {
    float NdotL = dot(nc, l);
    if (NdotL <= 0.0)
        return 0.0;
    float NdotV = max(dot(nc, v), 1e-4);
    vec3 h = normalize(l + v);
    float cr = max(s.clearcoatRoughness, MIN_ROUGHNESS);
    float ca = cr * cr;
    return fresnelSchlick(0.04, 1.0, saturate(dot(v, h))) *
           distributionGGX(saturate(dot(nc, h)), sinSquared(nc, h), ca) *
           visibilitySmithGGXSeparable(NdotL, NdotV, ca) * widenNormalization * NdotL;
}

vec3 dielectricF0(Surface s) {
    float r = (s.ior - 1.0) / (s.ior + 1.0);
    return min(vec3(r * r) * s.specularColor, vec3(1.0));
}

// f(l, v) * max(n.l, 0), all lobes layered. Mirrors velvet::brdf::evalDirectional().
// sheenAlbedoV: the sheen's directional albedo along the view, sheenDirectionalAlbedo(NdotV,
// ...), which depends on no light: a pass that lights a pixel by several lights and reads it for
// the image-based light too fetches it once (lighting.frag; llvmpipe pays every fetch).
vec3 shadeDirectional(Surface s, vec3 n, vec3 v, vec3 l, float sheenAlbedoV) {
    float NdotL = dot(n, l);
    if (NdotL <= 0.0)
        return vec3(0.0);
    float NdotV = max(dot(n, v), 1e-4);
    vec3 h = normalize(l + v);
    float NdotH = saturate(dot(n, h));
    float sin2H = sinSquared(n, h);
    float VdotH = saturate(dot(v, h));

    float rough = max(s.roughness, MIN_ROUGHNESS);
    float alpha = rough * rough;
    float specular = specularDV(s, n, v, l, h, NdotL, NdotV, NdotH, sin2H, VdotH, alpha);

    vec3 fDielectric =
        s.specularWeight * fresnelDielectric(s.terms.z, dielectricF0(s), s.ior, VdotH);
    vec3 fMetal = fresnelConductor(s.terms.z, s.baseColor, VdotH);
    vec3 diffuseLobe = diffuse(s.terms.w, s.baseColor, rough, NdotL, NdotV, VdotH); // l.h = v.h
    // Turquin 2019: the energy single scattering loses, per F0 (multipleScatteringFactor).
    vec3 dielectric = (1.0 - max3(fDielectric)) * diffuseLobe +
                      fDielectric * specular * multipleScatteringFactor(dielectricF0(s), NdotV, rough);
    vec3 metal = fMetal * specular * multipleScatteringFactor(s.baseColor, NdotV, rough);
    vec3 f = mix(dielectric, metal, s.metallic);

#if WITH_SHEEN
    if (max3(s.sheenColor) > 0.0) {
        // The albedo scaling uses the table of the sheen model drawn; see
        // velvet::brdf::sheenDirectionalAlbedo().
        float sheen = distributionCharlie(NdotH, sin2H, s.sheenRoughness) *
                      visibilitySheen(s.sheenModel, NdotL, NdotV, s.sheenRoughness);
        float scaling =
            min(1.0 - max3(s.sheenColor) * sheenAlbedoV,
                1.0 - max3(s.sheenColor) * sheenDirectionalAlbedo(NdotL, s.sheenRoughness, s.sheenModel));
        f = f * scaling + s.sheenColor * sheen;
    }
#endif

    f *= NdotL;
#if WITH_CLEARCOAT
    if (s.clearcoat > 0.0) {
        // The coat through its own normal (the base's unless a coat normal is given); with
        // nc = n this is the twin's f (1 - c Fc) + c coat, times n.l.
        float fc = fresnelSchlick(0.04, 1.0, max(dot(s.clearcoatNormal, v), 1e-4));
        f = f * (1.0 - s.clearcoat * fc) +
            s.clearcoat * clearcoatLobe(s, s.clearcoatNormal, v, l, 1.0);
    }
#endif
    return f;
}

vec3 shadeDirectional(Surface s, vec3 n, vec3 v, vec3 l) {
#if WITH_SHEEN
    float sheenAlbedoV =
        sheenDirectionalAlbedo(max(dot(n, v), 1e-4), s.sheenRoughness, s.sheenModel);
#else
    float sheenAlbedoV = 0.0;
#endif
    return shadeDirectional(s, n, v, l, sheenAlbedoV);
}
