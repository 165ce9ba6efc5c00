// BRDF terms. Configuration: glTF 2.0 Appendix B metal-rough (GGX D, separable Smith-GGX V,
// Schlick F, Lambert diffuse) layered with KHR_materials_specular/_ior, _sheen (Charlie D,
// Conty-Kulla V) and _clearcoat. Each implementation cites its paper on its first line; the C++
// twins in core/brdf.cpp have the same names, order and clamps. The renderer issue adds the other
// selectable terms and dispatches on GpuMaterial.terms.
#include "common_math.glsl"
#include "render_bindings.glsl"

#define MIN_ROUGHNESS 0.045
#define MIN_SHEEN_ROUGHNESS 0.07
#define SHEEN_LUT_SIZE 32.0

layout(binding = BINDING_SHEEN_LUT_TEX) uniform sampler2D uSheenLut;

// ---- Implementations ----

// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces" (GGX / Trowbridge-Reitz)
float distributionGGX(float NdotH, float alpha) {
    float a2 = alpha * alpha;
    float f = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return a2 / (PI * f * f);
}

// Smith 1967 with GGX G1, separable form of glTF 2.0 Appendix B: V = G / (4 |n.l| |n.v|)
float visibilitySmithGGXSeparable(float NdotL, float NdotV, float alpha) {
    float a2 = alpha * alpha;
    float gl = NdotL + sqrt(a2 + (1.0 - a2) * NdotL * NdotL);
    float gv = NdotV + sqrt(a2 + (1.0 - a2) * NdotV * NdotV);
    return 1.0 / (gl * gv);
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

// Estevez & Kulla 2017, "Production Friendly Microfacet Sheen BRDF" (Charlie D)
float distributionCharlie(float NdotH, float sheenRoughness) {
    float alpha = max(sheenRoughness, MIN_SHEEN_ROUGHNESS);
    float invR = 1.0 / (alpha * alpha);
    float sin2h = max(1.0 - NdotH * NdotH, 0.0);
    return (2.0 + invR) * pow(sin2h, invR * 0.5) / (2.0 * PI);
}

float sheenLambdaHelper(float x, float alphaG) {
    float t = (1.0 - alphaG) * (1.0 - alphaG);
    float a = mix(21.5473, 25.3245, t);
    float b = mix(3.82987, 3.32435, t);
    float c = mix(0.19823, 0.16801, t);
    float d = mix(-1.97760, -1.27393, t);
    float e = mix(-4.32054, -4.85967, t);
    return a / (1.0 + b * pow(x, c)) + d * x + e;
}
float sheenLambda(float cosTheta, float alphaG) {
    if (abs(cosTheta) < 0.5)
        return exp(sheenLambdaHelper(cosTheta, alphaG));
    return exp(2.0 * sheenLambdaHelper(0.5, alphaG) - sheenLambdaHelper(1.0 - cosTheta, alphaG));
}

// Conty & Kulla 2017, "Revisiting Physically Based Shading at Imageworks" (sheen visibility)
float visibilitySheenContyKulla(float NdotL, float NdotV, float sheenRoughness) {
    float r = max(sheenRoughness, MIN_SHEEN_ROUGHNESS);
    float alphaG = r * r;
    return saturate(1.0 / ((1.0 + sheenLambda(NdotV, alphaG) + sheenLambda(NdotL, alphaG)) *
                           (4.0 * NdotV * NdotL)));
}

// Neubelt & Pettineo 2013, "Crafting a Next-Gen Material Pipeline for The Order: 1886"
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

// Directional albedo of the sheen lobe, tabulated on the CPU (core/brdf.cpp, sheenAlbedoLut).
float sheenDirectionalAlbedo(float NdotV, float sheenRoughness) {
    vec2 uv = (vec2(saturate(NdotV), saturate(sheenRoughness)) * (SHEEN_LUT_SIZE - 1.0) + 0.5) /
              SHEEN_LUT_SIZE;
    return textureLod(uSheenLut, uv, 0.0).r;
}

// ---- Dispatch ----

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
    vec3 emissive;
};

vec3 dielectricF0(Surface s) {
    float r = (s.ior - 1.0) / (s.ior + 1.0);
    return min(vec3(r * r) * s.specularColor, vec3(1.0));
}

// f(l, v) * max(n.l, 0), all lobes layered. Mirrors velvet::brdf::evalDirectional().
vec3 shadeDirectional(Surface s, vec3 n, vec3 v, vec3 l) {
    float NdotL = dot(n, l);
    if (NdotL <= 0.0)
        return vec3(0.0);
    float NdotV = max(dot(n, v), 1e-4);
    vec3 h = normalize(l + v);
    float NdotH = saturate(dot(n, h));
    float VdotH = saturate(dot(v, h));

    float rough = max(s.roughness, MIN_ROUGHNESS);
    float alpha = rough * rough;
    float specular = distributionGGX(NdotH, alpha) * visibilitySmithGGXSeparable(NdotL, NdotV, alpha);

    vec3 fDielectric = s.specularWeight * fresnelSchlick(dielectricF0(s), vec3(1.0), VdotH);
    vec3 fMetal = fresnelSchlick(s.baseColor, vec3(1.0), VdotH);
    vec3 diffuse = s.baseColor / PI;
    vec3 dielectric = (1.0 - max3(fDielectric)) * diffuse + fDielectric * specular;
    vec3 metal = fMetal * specular;
    vec3 f = mix(dielectric, metal, s.metallic);

    if (max3(s.sheenColor) > 0.0) {
        float sheen = distributionCharlie(NdotH, s.sheenRoughness) *
                      visibilitySheenContyKulla(NdotL, NdotV, s.sheenRoughness);
        float scaling = min(1.0 - max3(s.sheenColor) * sheenDirectionalAlbedo(NdotV, s.sheenRoughness),
                            1.0 - max3(s.sheenColor) * sheenDirectionalAlbedo(NdotL, s.sheenRoughness));
        f = f * scaling + s.sheenColor * sheen;
    }

    if (s.clearcoat > 0.0) {
        float cr = max(s.clearcoatRoughness, MIN_ROUGHNESS);
        float ca = cr * cr;
        float coat = fresnelSchlick(0.04, 1.0, VdotH) * distributionGGX(NdotH, ca) *
                     visibilitySmithGGXSeparable(NdotL, NdotV, ca);
        float fc = fresnelSchlick(0.04, 1.0, NdotV);
        f = f * (1.0 - s.clearcoat * fc) + s.clearcoat * coat;
    }
    return f * NdotL;
}
