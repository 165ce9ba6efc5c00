#version 450 core
// The screen-space shadow masks (render/shadow_mask.h, docs/shadows.md), at half the frame's
// resolution (a quarter while the camera moves): shadow slot uSlot's visibility for mask texel t,
// looked up for pixel D t (D = stage.counts.y, the stage's downsample), written to channel uSlot (the other channels are masked off by glColorMaski). The receiver is
//   SHADOW_MASK_GROUND  the ground where the pixel's view ray meets it (behind the mesh too): the
//                       ground's mask, which the shadow catcher filters bilinearly, and the mask
//                       (the mesh's texels are overwritten by the mesh's passes)
//   (otherwise)         the pixel's own surface, the mesh's texels only: the mask
// and the pass
//   SHADOW_MASK_SETTLE  the visibility where the maps' depth bounds settle it
//                       (shadowVisibilityBound: no blocker within reach, or every texel a
//                       blocker), else 1, and the depth 0 where settled, 1 where not; the key
//                       (the pixel's view depth and material id, by which the lighting passes'
//                       upsample weighs the texel: shadow_mask.glsl)
//   (otherwise)         the PCSS lookup, drawn at depth 0.5 with the test LESS: only the texels
//                       left unsettled. llvmpipe tests depth before shading, so blocks of settled
//                       texels skip the lookup.
// Together they give exactly what the lookup alone would (shadow_sampling.glsl): a settled value
// does not depend on the noise. The mesh's passes are built twice: WITH_GEOMETRIC_HORIZON 0 when
// no drawn material bends its normal.
#include "gbuffer_read.glsl"
#include "shadow_sampling.glsl"

layout(location = 0) uniform int uSlot;
layout(location = 1) uniform int uSettle; // 0: settle nothing, every receiver is filtered
layout(location = 0) out vec4 outMask;
layout(location = 1) out vec2 outKey;        // the texel's pixel: view depth, material id
layout(location = 2) out vec4 outGroundMask; // SHADOW_MASK_GROUND

void main() {
    ivec2 pixel = min(ivec2(gl_FragCoord.xy) * stage.counts.y, ivec2(frame.viewport.xy) - 1);
    float depth = texelFetch(gDepthTex, pixel, 0).r;
    int materialId = readMaterialId(pixel);
    vec2 centre = vec2(pixel) + 0.5;
    vec2 ndcXY = centre * frame.viewport.zw * 2.0 - 1.0;
    vec3 posView = viewPositionFromDepth(ndcXY, depth);
#if defined(SHADOW_MASK_GROUND)
    // Two points of the pixel's view ray (perspective or orthographic), to the ground's plane; a
    // ray that does not come down to it from above sees no ground (settled: 1).
    vec3 a = (frame.invViewMatrix * vec4(viewPositionFromDepth(ndcXY, 0.0), 1.0)).xyz;
    vec3 b = (frame.invViewMatrix * vec4(viewPositionFromDepth(ndcXY, 0.5), 1.0)).xyz;
    vec3 ray = b - a;
    float t = (stage.ground.x - a.y) / min(ray.y, -1e-20);
    bool receiver = ray.y < 0.0 && a.y > stage.ground.x;
    vec3 posWorld = a + ray * max(t, 0.0);
    vec3 n = vec3(0.0, 1.0, 0.0);
#else
    bool receiver = depth < 1.0 && materialId != GROUND_PLAIN_MATERIAL_ID &&
                    materialId != GROUND_CATCHER_MATERIAL_ID;
#if defined(SHADOW_MASK_SETTLE)
    if (!receiver)
        discard; // the ground's pass (or the clear) has it
#endif
    vec3 posWorld = (frame.invViewMatrix * vec4(posView, 1.0)).xyz;
    vec3 n = octDecodeUnorm16(texelFetch(gNormalTex, pixel, 0).rg);
    // The biases offset the receiver along its surface: the face's normal where a material
    // bends its shading normal (surfaceNormalAt), not the weave's, which tilted threads away from
    // the light offset into the surface and shadowed it.
    n = surfaceNormalAt(pixel, receiver ? materialId : -1, posView, n);
#endif
    // Towards the light as the lighting passes see it: the frame block's direction for a
    // directional light, the way to a local light's centre (light_common.glsl).
    vec4 L = stage.shadowLight[uSlot];
    vec3 l = L.w < 0.5 ? L.xyz : normalize(L.xyz - posWorld);
#if defined(SHADOW_MASK_SETTLE)
    float settled = !receiver         ? 1.0
                    : uSettle == 0    ? -1.0
                                      : shadowVisibilityBound(uSlot, posWorld, n, l);
    float v = settled < 0.0 ? 1.0 : settled;
    gl_FragDepth = settled < 0.0 ? 1.0 : 0.0;
    outKey = depth >= 1.0 ? vec2(1e30, -1.0) : vec2(-posView.z, float(materialId));
#else
    // The same noise as a full-resolution lookup at that pixel: its centre.
    float v = shadowVisibility(uSlot, posWorld, n, l, interleavedGradientNoise(centre));
    outKey = vec2(0.0); // masked off: the settle pass wrote the key
#endif
    outMask = vec4(v);
    outGroundMask = vec4(v);
}
