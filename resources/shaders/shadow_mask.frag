#version 450 core
// The screen-space shadow mask (render/shadow_mask.h, docs/shadows.md), at half the frame's
// resolution: shadow slot uSlot's visibility for mask texel t, looked up at pixel 2t, written to
// the mask's channel uSlot (the other channels are masked off by glColorMaski), and that pixel's
// view depth and material id to the key, by which the lighting passes' upsample
// (shadow_mask.glsl) weighs the texel. No depth test: a background texel writes 1. Scissored to
// the part of the frame where a receiver can be inside the slot's map (elsewhere the mask keeps
// its clear value, 1: what the lookup returns there).
#include "gbuffer_read.glsl"
#include "shadow_sampling.glsl"

layout(location = 0) uniform int uSlot;
layout(location = 0) out vec4 outMask;
layout(location = 1) out vec2 outKey; // the texel's pixel: view depth, material id

void main() {
    ivec2 pixel = min(ivec2(gl_FragCoord.xy) * 2, ivec2(frame.viewport.xy) - 1);
    float depth = texelFetch(gDepthTex, pixel, 0).r;
    vec2 centre = vec2(pixel) + 0.5;
    vec2 ndcXY = centre * frame.viewport.zw * 2.0 - 1.0;
    vec3 posView = viewPositionFromDepth(ndcXY, depth);
    vec3 posWorld = (frame.invViewMatrix * vec4(posView, 1.0)).xyz;
    vec3 n = octDecodeUnorm16(texelFetch(gNormalTex, pixel, 0).rg);
    // Towards the light as the lighting passes see it: the frame block's direction for a
    // directional light, the way to a local light's centre (light_common.glsl).
    vec4 L = stage.shadowLight[uSlot];
    vec3 l = L.w < 0.5 ? L.xyz : normalize(L.xyz - posWorld);
    // The same noise as a full-resolution lookup at that pixel: its centre.
    float v = shadowVisibility(uSlot, posWorld, n, l, interleavedGradientNoise(centre));
    outMask = vec4(depth >= 1.0 ? 1.0 : v);
    outKey = depth >= 1.0 ? vec2(1e30, -1.0) : vec2(-posView.z, float(readMaterialId(pixel)));
}
