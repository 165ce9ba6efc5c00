#version 450 core
// BRDF probe (render/brdf_probe.h): evaluates the layered BRDF of common_brdf.glsl and each of
// its selectable terms at arbitrary (n, l, v, material) samples, so tests can compare the GPU
// functions with their C++ twins in core/brdf.cpp at sampled points rather than through pixels.
// The twin (brdf::Surface::multipleScattering) compensates by default; no IblBlock is bound here.
#define FIXED_MULTIPLE_SCATTERING 1
#include "common_brdf.glsl"

layout(local_size_x = 64) in;

// Mirrors ProbeSample in render/brdf_probe.cpp (std430, vec4 only).
struct ProbeSample {
    vec4 n;                  // xyz unit normal
    vec4 l;                  // xyz unit direction to the light
    vec4 v;                  // xyz unit direction to the eye
    vec4 baseColorMetallic;  // rgb base colour, a metallic
    vec4 specularColorWeight;// rgb specular colour, a weight
    vec4 sheenColorRoughness;// rgb sheen colour, a sheen roughness
    vec4 scalars;            // roughness, ior, clearcoat, clearcoat roughness
    ivec4 terms;             // distribution, visibility, fresnel, diffuse
    ivec4 terms2;            // sheen model
    vec4 anisotropy;         // xyz direction (perpendicular to n), w strength
};
// Mirrors ProbeResult: the layered BRDF x n.l and each selected term alone.
struct ProbeResult {
    vec4 full;     // rgb shadeDirectional()
    vec4 dvs;      // D, V, sheen D (Charlie), sheen V
    vec4 fresnel;  // rgb dielectric Fresnel (f0 from IOR and specular colour)
    vec4 diffuse;  // rgb diffuse lobe (no n.l)
};

layout(std430, binding = 0) readonly buffer Samples { ProbeSample samples[]; };
layout(std430, binding = 1) writeonly buffer Results { ProbeResult results[]; };
layout(location = 0) uniform int uCount;

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount)
        return;
    ProbeSample p = samples[i];
    Surface s;
    s.baseColor = p.baseColorMetallic.rgb;
    s.metallic = p.baseColorMetallic.a;
    s.specularColor = p.specularColorWeight.rgb;
    s.specularWeight = p.specularColorWeight.a;
    s.sheenColor = p.sheenColorRoughness.rgb;
    s.sheenRoughness = p.sheenColorRoughness.a;
    s.roughness = p.scalars.x;
    s.ior = p.scalars.y;
    s.clearcoat = p.scalars.z;
    s.clearcoatRoughness = p.scalars.w;
    s.emissive = vec3(0.0);
    s.terms = p.terms;
    s.sheenModel = p.terms2.x;

    vec3 n = p.n.xyz, l = p.l.xyz, v = p.v.xyz;
    setIsotropicSingleNormal(s, n);
    s.anisotropyStrength = p.anisotropy.w;
    s.anisotropyDirection = p.anisotropy.xyz;
    float NdotL = max(dot(n, l), 1e-4);
    float NdotV = max(dot(n, v), 1e-4);
    vec3 h = normalize(l + v);
    float NdotH = saturate(dot(n, h));
    float sin2H = sinSquared(n, h);
    float VdotH = saturate(dot(v, h));
    float rough = max(s.roughness, MIN_ROUGHNESS);
    float alpha = rough * rough;

    ProbeResult r;
    r.full = vec4(shadeDirectional(s, n, v, l), 0.0);
    r.dvs = vec4(distribution(s.terms.x, NdotH, sin2H, alpha),
                 visibility(s.terms.y, NdotL, NdotV, NdotH, VdotH, alpha),
                 distributionCharlie(NdotH, sin2H, s.sheenRoughness),
                 visibilitySheen(s.sheenModel, NdotL, NdotV, s.sheenRoughness));
    r.fresnel = vec4(fresnelDielectric(s.terms.z, dielectricF0(s), s.ior, VdotH), 0.0);
    r.diffuse = vec4(diffuse(s.terms.w, s.baseColor, rough, NdotL, NdotV, VdotH), 0.0);
    results[i] = r;
}
