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
    for (int y = -2; y < 2; ++y)
        for (int x = -2; x < 2; ++x) {
            vec2 t = texelFetch(uRaw, clamp(p + ivec2(x, y), ivec2(0), size - 1), 0).rg;
            float d = abs(t.g - center.g) / (0.03 * center.g + 0.01);
            float w = exp(-d * d);
            sum += t.r * w;
            weights += w;
        }
    outOcclusion = vec2(saturate(sum / weights), center.g);
}
