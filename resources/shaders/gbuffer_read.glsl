// One pixel of the G-buffer read back and decoded, ready to shade: the one decode the full-screen
// lighting (lighting.frag) and the many-light paths (light_common.glsl) share. The encodings are
// common_gbuffer.glsl's; what is per material comes from the material table by the pixel's id.
#include "common_frame.glsl"
#include "common_gbuffer.glsl"
#include "common_material.glsl"
#include "common_brdf.glsl"

// View-space position from the hardware depth through the inverse projection (works for
// perspective and orthographic projections alike).
vec3 viewPositionFromDepth(vec2 ndcXY, float depth) {
    vec4 p = frame.invProjMatrix * vec4(ndcXY, depth * 2.0 - 1.0, 1.0);
    return p.xyz / p.w;
}

struct ShadingPoint {
    Surface s;
    vec3 n;          // world normal
    vec3 v;          // world direction to the eye
    vec3 posView;    // view-space position
    vec3 posWorld;   // world position
    float occlusion; // ambient occlusion (RT0 alpha): of image-based light's diffuse terms
    float specularOcclusion; // of its specular terms (RT2 alpha; gbuffer.frag)
    int materialId;  // index into the material table
    // The surface's geometric normal where the material bends its shading normal per pixel
    // (a normal map, a fabric's relief: GpuMaterial.sheenWeightAnisotropy.w), reconstructed from
    // the depth (geometricNormalFromDepth); n elsewhere.
    vec3 ng;
    bool bentShading; // the material bends n: light below ng's horizon is kept out
};

// WITH_GEOMETRIC_HORIZON 0 (render/lighting_features.h): no drawn material bends its normal.
#ifndef WITH_GEOMETRIC_HORIZON
#define WITH_GEOMETRIC_HORIZON 1
#endif
// WITH_GBUFFER_VALUES 0: every drawn record reads its base colour, metallic and roughness from
// the table (RECORD_VALUES_PER_MATERIAL; readShadingPoint).
#ifndef WITH_GBUFFER_VALUES
#define WITH_GBUFFER_VALUES 1
#endif

// The view-space position of full-resolution pixel @p q (clamped to the frame) from its depth.
vec3 viewPositionAt(ivec2 q) {
    q = clamp(q, ivec2(0), ivec2(frame.viewport.xy) - 1);
    vec2 ndcXY = (vec2(q) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
    return viewPositionFromDepth(ndcXY, texelFetch(gDepthTex, q, 0).r);
}

// The geometric (face) normal at @p pixel, whose view-space position is @p posView, from the
// depth of its four neighbours: on each axis the neighbour nearer in depth, so a silhouette's
// background or another surface does not bend it (the "accurate normal reconstruction" of
// Turanszki 2019 and Bavoil's HBAO+). World space, towards the viewer; @p fallback where the
// neighbours give no plane.
vec3 geometricNormalFromDepth(ivec2 pixel, vec3 posView, vec3 fallback) {
    vec3 px = viewPositionAt(pixel + ivec2(1, 0)), mx = viewPositionAt(pixel - ivec2(1, 0));
    vec3 py = viewPositionAt(pixel + ivec2(0, 1)), my = viewPositionAt(pixel - ivec2(0, 1));
    // At the frame's edge the missing neighbour (clamped: the pixel itself) is never chosen.
    bvec2 last = greaterThanEqual(pixel + 1, ivec2(frame.viewport.xy));
    bvec2 first = lessThanEqual(pixel, ivec2(0));
    vec3 dx = !last.x && (first.x || abs(px.z - posView.z) < abs(mx.z - posView.z))
                  ? px - posView : posView - mx;
    vec3 dy = !last.y && (first.y || abs(py.z - posView.z) < abs(my.z - posView.z))
                  ? py - posView : posView - my;
    vec3 c = cross(dx, dy);
    if (dot(c, c) < 1e-24)
        return fallback;
    vec3 ngView = normalize(c);
    vec3 toEye = frame.cameraPosition.w > 0.5 ? vec3(0.0, 0.0, 1.0) : -posView;
    if (dot(ngView, toEye) < 0.0)
        ngView = -ngView;
    return normalize((frame.invViewMatrix * vec4(ngView, 0.0)).xyz);
}

// Whether material @p m bends its shading normal per pixel (a normal map, a fabric's relief).
bool bendsShadingNormal(GpuMaterial m) { return m.sheenWeightAnisotropy.w > 0.5; }

// The normal of the surface itself at @p pixel (view position @p posView) for the passes that
// measure the surface rather than shade it (the occlusion's hemisphere, the shadow mask's
// biases): the face's, from the depth, where material @p materialId bends its shading normal
// @p n (the part of a bent normal's hemisphere below the face is no open sky, and an offset
// along it goes into the surface), else @p n. A @p materialId outside the table (-1: none)
// gives @p n.
vec3 surfaceNormalAt(ivec2 pixel, int materialId, vec3 posView, vec3 n) {
#if WITH_GEOMETRIC_HORIZON
    if (materialId >= 0 && materialId < materials.length() &&
        bendsShadingNormal(materials[materialId]))
        return geometricNormalFromDepth(pixel, posView, n);
#endif
    return n;
}

// How much of a light in direction @p l (unit, towards it) is above the surface's geometric
// horizon: a normal map bends the shading, not the surface, so light from below it never arrives
// (the reference path tracer's test, reference/light_sampling.cpp). @p angularRadius: the light's
// (radians; 0 for a point or a direction, a hard horizon): the share of its disc above it.
// 1 for a material that does not bend its normal (there n.l <= 0 shades nothing anyway).
float geometricHorizon(ShadingPoint p, vec3 l, float angularRadius) {
#if WITH_GEOMETRIC_HORIZON
    if (!p.bentShading)
        return 1.0;
    float e = dot(p.ng, l);
    return angularRadius > 0.0 ? saturate(0.5 + e / (2.0 * angularRadius)) : (e > 0.0 ? 1.0 : 0.0);
#else
    return 1.0;
#endif
}

// The material id of @p pixel alone (passes that keep only some materials test it first).
int readMaterialId(ivec2 pixel) {
    return decodeMaterialId(texelFetch(gMaterialTex, pixel, 0).b);
}

// The lobe values the material's map (render/lobe_channels.h: @p map, and @p iorEntry for the IOR)
// puts in the lobe channels, over the material table's values in @p s. Encodings: gbuffer.frag.
void readLobeChannels(ivec2 pixel, int map, int iorEntry, vec3 n, inout Surface s) {
#if !WITH_LOBE_CHANNELS
    return; // no drawn material has a lobe map (render/lighting_features.h)
#endif
    if (map == -1 && iorEntry == LOBE_PER_MATERIAL) // nothing per pixel
        return;
    vec4 l0 = texelFetch(gLobes0Tex, pixel, 0);
    vec4 l1 = texelFetch(gLobes1Tex, pixel, 0);
    float ch[LOBE_CHANNEL_COUNT] = float[](l0.r, l0.g, l0.b, l0.a, l1.r, l1.g, l1.b, l1.a);
    int c = lobeChannel(map, LOBE_ANISOTROPY);
    if (c != LOBE_PER_MATERIAL) {
        s.anisotropyStrength = ch[c];
        s.anisotropyDirection = decodeTangentAngle(ch[c + 1], n);
    }
    c = lobeChannel(map, LOBE_SHEEN_COLOR);
    if (c != LOBE_PER_MATERIAL)
        s.sheenColor = srgbDecode(vec3(ch[c], ch[c + 1], ch[c + 2]));
    c = lobeChannel(map, LOBE_SHEEN_ROUGHNESS);
    if (c != LOBE_PER_MATERIAL)
        s.sheenRoughness = ch[c];
    c = lobeChannel(map, LOBE_CLEARCOAT);
    if (c != LOBE_PER_MATERIAL)
        s.clearcoat = ch[c];
    c = lobeChannel(map, LOBE_CLEARCOAT_ROUGHNESS);
    if (c != LOBE_PER_MATERIAL)
        s.clearcoatRoughness = ch[c];
    c = lobeChannel(map, LOBE_CLEARCOAT_NORMAL);
    if (c != LOBE_PER_MATERIAL)
        s.clearcoatNormal = decodeNormalInFrame(vec2(ch[c], ch[c + 1]), n);
    c = lobeChannel(map, LOBE_SPECULAR_WEIGHT);
    if (c != LOBE_PER_MATERIAL)
        s.specularWeight = ch[c];
    c = lobeChannel(map, LOBE_SPECULAR_COLOR);
    if (c != LOBE_PER_MATERIAL)
        s.specularColor = srgbDecode(vec3(ch[c], ch[c + 1], ch[c + 2]));
    if (iorEntry != LOBE_PER_MATERIAL)
        s.ior = 1.0 + 2.0 * ch[iorEntry];
}

// Decodes @p pixel, whose hardware depth is @p depth (read by the caller, which decides what the
// far plane means for it).
ShadingPoint readShadingPoint(ivec2 pixel, float depth) {
    ShadingPoint p;
    vec2 ndcXY = (vec2(pixel) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
    p.posView = viewPositionFromDepth(ndcXY, depth);
    p.posWorld = (frame.invViewMatrix * vec4(p.posView, 1.0)).xyz;
    vec3 toEyeView = frame.cameraPosition.w > 0.5 ? vec3(0.0, 0.0, 1.0) : -p.posView;
    p.v = normalize((frame.invViewMatrix * vec4(toEyeView, 0.0)).xyz);

    vec4 rt0 = texelFetch(gBaseColorOcclusionTex, pixel, 0);
    vec2 rt1 = texelFetch(gNormalTex, pixel, 0).rg;
    vec4 rt2 = texelFetch(gMaterialTex, pixel, 0);
    // FIXED_MATERIAL_ID (render/lighting_features.h): every pixel this program shades has it, and
    // the table read below at a constant index is one load for a block of pixels on llvmpipe.
#ifdef FIXED_MATERIAL_ID
    p.materialId = FIXED_MATERIAL_ID;
#else
    p.materialId = decodeMaterialId(rt2.b);
#endif
    GpuMaterial m = materials[p.materialId];
    // A record whose base colour, metallic and roughness are the same at every pixel
    // (RECORD_VALUES_PER_MATERIAL: render/material_table.h) reads them from the table, quantised
    // to the G-buffer's 8 bits as the geometry pass would have written them (the base colour
    // decoded on the CPU: GpuMaterial::storedBaseColor), so a value edit keeps the G-buffer it
    // drew (Renderer::Impl::keepsGBuffer). A select, not a branch; WITH_GBUFFER_VALUES 0 (every
    // drawn record is such a one: render/lighting_features.h) compiles the G-buffer's side and
    // its sRGB decode out, which llvmpipe would otherwise run at every pixel.
#if WITH_GBUFFER_VALUES
    bool perMaterial = (m.terms2.y & RECORD_VALUES_PER_MATERIAL) != 0;
#else
    const bool perMaterial = true;
#endif
    p.s.baseColor = perMaterial ? m.storedBaseColor.rgb : decodeBaseColor(rt0.rgb);
    p.s.metallic = perMaterial ? unorm8(m.baseColorMetallic.a) : rt2.r;
    p.s.roughness = perMaterial ? unorm8(m.roughIorOcclusionNormal.x) : rt2.g;
    p.s.specularWeight = m.specularColorWeight.a;
    p.s.specularColor = m.specularColorWeight.rgb;
    p.s.ior = m.roughIorOcclusionNormal.y;
    p.s.sheenColor = m.sheenColorRoughness.rgb * m.sheenWeightAnisotropy.x;
    p.s.sheenRoughness = m.sheenColorRoughness.a;
    p.s.clearcoat = m.clearcoat.x;
    p.s.clearcoatRoughness = m.clearcoat.y;
    p.s.emissive = m.emissive.rgb * m.emissive.a; // the emissive debug view's fallback
    p.s.terms = m.terms;
    p.s.sheenModel = m.terms2.x;
    p.occlusion = rt0.a;
    p.specularOcclusion = rt2.a;
    p.n = octDecodeUnorm16(rt1);
    setIsotropicSingleNormal(p.s, p.n);
    readLobeChannels(pixel, m.terms2.w, int(m.clearcoat.w), p.n, p.s);
#if WITH_GEOMETRIC_HORIZON
    p.bentShading = bendsShadingNormal(m);
    p.ng = p.bentShading ? geometricNormalFromDepth(pixel, p.posView, p.n) : p.n;
#else
    p.bentShading = false;
    p.ng = p.n;
#endif
    // Lobes no drawn material has are constants, so the code that shades them folds away.
#if !WITH_SHEEN
    p.s.sheenColor = vec3(0.0);
#endif
#if !WITH_CLEARCOAT
    p.s.clearcoat = 0.0;
#endif
#if !WITH_ANISOTROPY
    p.s.anisotropyStrength = 0.0;
#endif
    return p;
}
