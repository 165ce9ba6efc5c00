#version 450 core
// The split-sum environment BRDF (Karis 2013, "Real Shading in Unreal Engine 4", IntegrateBRDF)
// for glTF's separable Smith-GGX visibility: texel (i, j) holds (A, B) at n.v = (i + 0.5) / N,
// roughness = (j + 0.5) / N, so that E = f0 A + B. Rows uRowOffset.. only (the bake runs in
// slices). Mirrored by velvet::ibl::integrateDfg() in core/ibl.cpp.
#include "common_ibl_sampling.glsl"

layout(local_size_x = 64, local_size_y = 1) in; // one row per group: slices of single rows
layout(binding = 0, rg32f) uniform writeonly image2D uTarget;
layout(location = 0) uniform int uSize;
layout(location = 1) uniform int uRowOffset;
layout(location = 2) uniform int uSamples;
layout(location = 3) uniform float uMinRoughness;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, uRowOffset);
    if (texel.x >= uSize || texel.y >= uSize)
        return;
    vec2 p = (vec2(texel) + 0.5) / float(uSize);
    float NdotV = clamp(p.x, 1e-4, 1.0);
    float rough = max(p.y, uMinRoughness);
    float alpha = rough * rough;
    float a2 = alpha * alpha;
    vec3 v = vec3(sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    float gv = NdotV + sqrt(a2 + (1.0 - a2) * NdotV * NdotV);
    float A = 0.0, B = 0.0;
    for (int i = 0; i < uSamples; ++i) {
        vec3 h = importanceSampleGgx(hammersley(uint(i), uint(uSamples)), alpha);
        float VdotH = dot(v, h);
        vec3 l = 2.0 * VdotH * h - v;
        float NdotL = l.z;
        if (NdotL <= 0.0 || VdotH <= 0.0)
            continue;
        float gl = NdotL + sqrt(a2 + (1.0 - a2) * NdotL * NdotL);
        float w = 4.0 * NdotL * VdotH / (h.z * gl * gv);
        float x = 1.0 - VdotH;
        float fc = x * x * x * x * x;
        A += (1.0 - fc) * w;
        B += fc * w;
    }
    imageStore(uTarget, texel, vec4(A, B, 0.0, 0.0) / float(uSamples));
}
