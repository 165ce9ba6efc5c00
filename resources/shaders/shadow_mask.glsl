// The lighting passes' side of the screen-space shadow mask (render/shadow_mask.h,
// docs/shadows.md): shadow_mask.frag has filtered every shadow slot's map for each geometry pixel
// (PCSS, shadow_sampling.glsl) into one channel of an RGBA8 texture, so a lighting pass reads one
// texel instead of running the lookup inside its own, much larger shader. This is the
// screen-space shadow mask of deferred renderers (Unity's "screen space shadows", Unreal's
// shadow projection pass); on llvmpipe, which runs every side of a branch, the lighting shaders
// are cheaper without the lookup's code and the lookup cheaper in a pass of its own
// (BENCHMARKS.md). Channel s is slot s's light: kMaxShadowLights (4) fit one texel.
#include "stage_interface.glsl"
#include "common_frame.glsl"

layout(binding = BINDING_SHADOW_MASK_TEX) uniform sampler2D uShadowMask;

// The frame's pixel of a view-space position (for passes without gl_FragCoord).
vec2 pixelOfViewPosition(vec3 posView) {
    vec4 clip = frame.projMatrix * vec4(posView, 1.0);
    return (clip.xy / clip.w * 0.5 + 0.5) * frame.viewport.xy;
}

// Fraction of shadow slot s's light that reaches the surface at @p pixel (0 facing away from it or
// with the ground in between, 1 outside its map).
float shadowMask(int s, ivec2 pixel) {
    return texelFetch(uShadowMask, pixel, 0)[s];
}

// Directional light i of the frame block: its shadow at @p pixel, 1 when it casts none.
// WITH_DIRECTIONAL_SHADOWS 0 (render/lighting_features.h): no directional light has a map.
#ifndef WITH_DIRECTIONAL_SHADOWS
#define WITH_DIRECTIONAL_SHADOWS 1
#endif
float directionalShadow(int i, ivec2 pixel) {
#if !WITH_DIRECTIONAL_SHADOWS
    return 1.0;
#endif
    int s = int(frame.lightDirection[i].w) - 1;
    return s < 0 ? 1.0 : shadowMask(s, pixel);
}
