// The lighting passes' side of the screen-space shadow mask (render/shadow_mask.h,
// docs/shadows.md): shadow_mask.frag has filtered every shadow slot's map for every other pixel
// (PCSS, shadow_sampling.glsl) into one channel of a half-resolution RGBA8 texture, so a lighting
// pass reads upsampled texels instead of running the lookup inside its own, much larger shader.
// This is the screen-space shadow mask of deferred renderers (Unity's "screen space shadows",
// Unreal's shadow projection pass); on llvmpipe, which runs every side of a branch, the lighting
// shaders are cheaper without the lookup's code and the lookup cheaper in a pass of its own, at
// half resolution (BENCHMARKS.md). Channel s is slot s's light: kMaxShadowLights (4) fit one texel.
#include "stage_interface.glsl"
#include "common_frame.glsl"
#include "common_math.glsl"

layout(binding = BINDING_SHADOW_MASK_TEX) uniform sampler2D uShadowMask;
layout(binding = BINDING_SHADOW_KEY_TEX) uniform sampler2D uShadowKey;
layout(binding = BINDING_GROUND_SHADOW_MASK_TEX) uniform sampler2D uGroundShadowMask;

// Every slot's visibility at @p pixel, whose view depth is @p viewDepth and material id
// @p materialId, from the mask at the stage's downsample D (stage.counts.y: 2, or 4 while the
// camera moves): texel t holds the lookup at pixel D t, so such a pixel reads its own texel and
// the others blend the two or four around them, each weighed by its
// key (a joint bilateral upsample, Kopf et al. 2007, as the occlusion term's in
// stage_shading.glsl): a texel of another material (the ground beside the mesh) or another depth
// (across a silhouette) drops out; where none is alike, the same material nearest in depth wins,
// else the nearest in depth. Two gathers of the key and four fetches of the mask: call it once
// per pixel and pass the result on.
vec4 shadowMaskAll(ivec2 pixel, float viewDepth, int materialId) {
    ivec2 last = textureSize(uShadowMask, 0) - 1;
    int D = stage.counts.y;
    ivec2 b = pixel / D;
    vec2 f = vec2(pixel - b * D) / float(D);
    // textureGather's texels around the corner b + 1: (0,1), (1,1), (1,0), (0,0) from b; the
    // key's edges clamp (render/frame_targets.cpp).
    vec2 cornerUv = (vec2(b) + 1.0) / vec2(last + 1);
    vec4 depths = textureGather(uShadowKey, cornerUv, 0);
    vec4 ids = textureGather(uShadowKey, cornerUv, 1);
    vec4 bilinear = gatherBilinearWeights(f);
    vec4 d = abs(depths - viewDepth) / (0.03 * viewDepth + 0.01);
    vec4 same = vec4(equal(ids, vec4(float(materialId))));
    vec4 nearness = 1.0 / (1.0 + d);
    vec4 w = bilinear * same * max(1.0 - d * d, 0.0) + (1e-3 * same + 1e-6) * nearness;
    vec4 sum = texelFetch(uShadowMask, clamp(b + ivec2(0, 1), ivec2(0), last), 0) * w.x +
               texelFetch(uShadowMask, clamp(b + ivec2(1, 1), ivec2(0), last), 0) * w.y +
               texelFetch(uShadowMask, clamp(b + ivec2(1, 0), ivec2(0), last), 0) * w.z +
               texelFetch(uShadowMask, clamp(b, ivec2(0), last), 0) * w.w;
    return sum / (w.x + w.y + w.z + w.w);
}

// The frame's shadow mask at @p pixel (shadowMaskAll) where shading may read it: compiled out to
// "no shadow" without a shadow slot this frame (WITH_SHADOW_MASK 0) or, for the surfaces, without
// a shadowed directional light (WITH_DIRECTIONAL_SHADOWS 0; render/lighting_features.h): llvmpipe
// would run the upsample even where no slot reads it.
#ifndef WITH_SHADOW_MASK
#define WITH_SHADOW_MASK 1
#endif
#ifndef WITH_DIRECTIONAL_SHADOWS
#define WITH_DIRECTIONAL_SHADOWS 1
#endif
vec4 frameShadowMask(ivec2 pixel, float viewDepth, int materialId) {
#if WITH_SHADOW_MASK
    return shadowMaskAll(pixel, viewDepth, materialId);
#else
    return vec4(1.0);
#endif
}
vec4 surfaceShadowMask(ivec2 pixel, float viewDepth, int materialId) {
#if WITH_SHADOW_MASK && WITH_DIRECTIONAL_SHADOWS
    return shadowMaskAll(pixel, viewDepth, materialId);
#else
    return vec4(1.0);
#endif
}

// Every slot's visibility on the ground seen at @p pixel, from the ground's mask at the stage's
// downsample D (shadow_mask.frag's SHADOW_MASK_GROUND): it holds the ground behind the mesh too,
// so it is smooth across the mesh's silhouettes and one bilinear fetch upsamples it (texel t is
// pixel D t, so pixel p sits at texel p / D). Compiled out without a shadow slot
// (WITH_SHADOW_MASK 0).
vec4 groundShadowMask(ivec2 pixel) {
#if WITH_SHADOW_MASK
    vec2 size = vec2(textureSize(uGroundShadowMask, 0));
    return textureLod(uGroundShadowMask, (vec2(pixel) / float(stage.counts.y) + 0.5) / size, 0.0);
#else
    return vec4(1.0);
#endif
}

// Directional light i of the frame block: its shadow from @p mask (shadowMaskAll), 1 when it
// casts none.
float directionalShadow(int i, vec4 mask) {
    int s = int(frame.lightDirection[i].w) - 1;
    return s < 0 ? 1.0 : mask[clamp(s, 0, 3)];
}
