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
};

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
    p.materialId = decodeMaterialId(rt2.b);
    GpuMaterial m = materials[p.materialId];
    p.s.baseColor = decodeBaseColor(rt0.rgb);
    p.s.metallic = rt2.r;
    p.s.roughness = rt2.g;
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
