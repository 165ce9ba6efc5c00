#version 450 core
// The screen-space shadow mask (render/shadow_mask.h, docs/shadows.md): shadow slot uSlot's
// visibility at every geometry pixel, written to the mask's channel uSlot (the other channels are
// masked off by glColorMaski). Drawn as a triangle at the far plane against the G-buffer's depth
// (GL_GREATER, read-only), so only geometry pixels run it, and scissored to the part of the frame
// where a receiver can be inside the slot's map (elsewhere the mask keeps its clear value, 1:
// what the lookup returns there). The lighting passes read it through shadow_mask.glsl.
#include "gbuffer_read.glsl"
#include "shadow_sampling.glsl"

layout(location = 0) uniform int uSlot;
layout(location = 0) out vec4 outMask;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec2 ndcXY = gl_FragCoord.xy * frame.viewport.zw * 2.0 - 1.0;
    vec3 posView = viewPositionFromDepth(ndcXY, texelFetch(gDepthTex, pixel, 0).r);
    vec3 posWorld = (frame.invViewMatrix * vec4(posView, 1.0)).xyz;
    vec3 n = octDecodeUnorm16(texelFetch(gNormalTex, pixel, 0).rg);
    // Towards the light as the lighting passes see it: the frame block's direction for a
    // directional light, the way to a local light's centre (light_common.glsl).
    vec4 L = stage.shadowLight[uSlot];
    vec3 l = L.w < 0.5 ? L.xyz : normalize(L.xyz - posWorld);
    // The same noise as the lookup had in the lighting passes: the pixel's centre.
    outMask = vec4(shadowVisibility(uSlot, posWorld, n, l, interleavedGradientNoise(gl_FragCoord.xy)));
}
