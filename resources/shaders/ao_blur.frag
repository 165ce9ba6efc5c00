#version 450 core
// The half-resolution occlusion's 4x4 pattern averaged away: a 4x4 box whose taps weigh by depth
// likeness (a cross-bilateral filter), so no occlusion bleeds across silhouettes.
#include "common_math.glsl"
#include "stage_interface.glsl"

layout(binding = BINDING_OCCLUSION_RAW_TEX) uniform sampler2D uRaw;
layout(location = 0) out vec2 outOcclusion;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = ivec2(stage.occlusion.zw);
    vec2 center = texelFetch(uRaw, p, 0).rg;
    float sum = 0.0, weights = 0.0;
    vec2 texel = 1.0 / vec2(size);
    // The 4x4 window p - 2 .. p + 1 as four 2x2 gathers of each channel (clamped edges): on
    // llvmpipe a little cheaper than sixteen texelFetch (BENCHMARKS.md, "The occlusion by
    // gathers").
    for (int k = 0; k < 4; ++k) {
        vec2 corner = vec2(p + ivec2((k & 1) * 2 - 1, (k >> 1) * 2 - 1)) * texel;
        vec4 vis = textureGather(uRaw, corner, 0);
        vec4 depth = textureGather(uRaw, corner, 1);
        vec4 d = abs(depth - center.g) / (0.03 * center.g + 0.01);
        vec4 w = exp(-d * d);
        sum += dot(vis, w);
        weights += dot(w, vec4(1.0));
    }
    outOcclusion = vec2(saturate(sum / weights), center.g);
}
