// The look-dev stage in the full-screen lighting pass (docs/shadows.md): the screen-space ambient
// occlusion term (ao_gtao.frag, half resolution, read back with a depth-aware bilinear
// upsample), and the ground's two looks: the shadow catcher (the background times how much of
// the light the ground would receive, shadowed / unshadowed) and the plain ground's fade into it.
// Needs common_environment.glsl; the shadows come from the shadow mask (shadow_mask.glsl).
#include "shadow_mask.glsl"

layout(binding = BINDING_OCCLUSION_TEX) uniform sampler2D uOcclusion;

// The occlusion of full-resolution pixel `pixel` at view depth `viewDepth` (m, positive): 1 when
// the term is off. The four neighbours at the stage's downsample (stage.counts.y) weigh by bilinear position times depth
// likeness, so occlusion does not bleed across silhouettes.
// WITH_OCCLUSION 0 (render/lighting_features.h): the term is off, a constant 1.
#ifndef WITH_OCCLUSION
#define WITH_OCCLUSION 1
#endif
float screenSpaceOcclusion(ivec2 pixel, float viewDepth) {
#if !WITH_OCCLUSION
    return 1.0;
#endif
    if (stage.occlusion.x < 0.5)
        return 1.0;
    vec2 size = stage.occlusion.zw;
    vec2 h = (vec2(pixel) + 0.5) / float(stage.counts.y) - 0.5;
    vec2 b = floor(h);
    vec2 f = h - b;
    // Texels b .. b + 1 outside those the occlusion's passes drew are exactly 1 (render/ao_pass.h):
    // the upsample is a loop run once or not at all, which llvmpipe leaves for a whole block of
    // such pixels (the shadow catcher's ground far from the mesh), where it runs both sides of
    // an `if`.
    // Nor where the occlusion rides in the shadow masks (stage.counts.z: stageOcclusion()).
    ivec4 drawn = stage.occlusionTexels;
    bool reads = stage.counts.z == 0 && all(greaterThanEqual(ivec2(b) + 1, drawn.xy)) &&
                 all(lessThan(ivec2(b), drawn.zw));
    float result = 1.0;
    for (int once = 0; once < (reads ? 1 : 0); ++once) {
        // The 2x2 texels b .. b + 1 in two gathers, (0,1), (1,1), (1,0), (0,0) from b (clamped
        // edges), as the blur reads its window (BENCHMARKS.md, "The occlusion by gathers").
        vec2 uv = (b + 1.0) / size;
        vec4 vis = textureGather(uOcclusion, uv, 0);
        vec4 depth = textureGather(uOcclusion, uv, 1);
        vec4 bilinear = gatherBilinearWeights(f); // common_math.glsl
        vec4 d = abs(depth - viewDepth) / (0.03 * viewDepth + 0.01);
        // The nearest in depth wins where none is alike.
        vec4 w = (bilinear + 1e-3) * exp(-d * d) + 1e-6 / (1.0 + d);
        float total = dot(w, vec4(1.0));
        result = total > 0.0 ? dot(vis, w) / total : 1.0;
    }
    return result;
}

// The occlusion at @p pixel, @p mask the shadow mask read there (frameShadowMask,
// surfaceShadowMask or groundShadowMask): where the frame has a shadow mask with a channel to
// spare (stage.counts.z = 1), the occlusion is in its fourth (render/ao_pass.h, packInto), and
// the mask's upsample, which the pixel pays for anyway, has brought it here: the occlusion's own
// upsample above (two gathers, a quarter of the stage's cost on llvmpipe: BENCHMARKS.md, "The
// occlusion rides in the shadow mask") runs no times.
// FIXED_OCCLUSION_IN_MASK 1 or 0 (render/lighting_features.h) compiles the other way out: llvmpipe
// pays for the own upsample's code even in blocks whose uniform skips it.
float stageOcclusion(vec4 mask, ivec2 pixel, float viewDepth) {
#if !WITH_OCCLUSION
    return 1.0;
#elif defined(FIXED_OCCLUSION_IN_MASK) && FIXED_OCCLUSION_IN_MASK
    return mask.a;
#elif defined(FIXED_OCCLUSION_IN_MASK)
    return screenSpaceOcclusion(pixel, viewDepth);
#else
    float own = screenSpaceOcclusion(pixel, viewDepth);
    return stage.counts.z != 0 ? mask.a : own;
#endif
}

#ifndef WITH_LOCAL_SHADOWS
#define WITH_LOCAL_SHADOWS 1
#endif

// Illuminance a shadow slot's local light gives a horizontal ground point (its shadow apart).
vec3 slotIlluminance(int s, vec3 pos, vec3 n) {
    vec4 L = stage.shadowLight[s];
    if (L.w < 0.5)
        return vec3(0.0); // directional: the frame block's loop has it
    vec3 toLight = L.xyz - pos;
    float d = max(length(toLight), 0.01);
    vec3 l = toLight / d;
    float range = stage.shadowRadiance[s].w;
    float r = d / max(range, 1e-4);
    float window = saturate(1.0 - r * r * r * r);
    float e = max(dot(n, l), 0.0) * window * window / (d * d);
    vec4 spot = stage.shadowSpot[s];
    if (spot.w > -1.5)
        e *= smoothstep(spot.w, spot.w + 0.02, dot(spot.xyz, -l));
    if (L.w > 1.5) // a rectangle emits on one side only
        e *= saturate(dot(spot.xyz, -l));
    return stage.shadowRadiance[s].rgb * e;
}

// How much of the light the ground at p receives, shadowed and occluded over unshadowed: the
// environment (SH9 irradiance x occlusion), the directional lights and the shadowed local
// lights (their shadows @p mask, the shadow mask here: frameShadowMask). Lights without shadows
// cancel out but for their share of the sum.
vec3 catcherTransmission(vec3 pos, float occlusion, vec4 mask) {
    vec3 n = vec3(0.0, 1.0, 0.0);
    vec3 env = irradianceOverPi(n) * PI;
    vec3 full = env, lit = env * occlusion;
    for (int i = 0; i < directionalLightCount(); ++i) {
        vec3 e = frame.lightRadiance[i].rgb * max(dot(n, frame.lightDirection[i].xyz), 0.0);
        full += e;
        lit += e * directionalShadow(i, mask);
    }
    // WITH_LOCAL_SHADOWS 0 (render/lighting_features.h): every slot is a directional light's,
    // which the loop above has; llvmpipe would run slotIlluminance for them all the same.
#if WITH_LOCAL_SHADOWS
    for (int s = 0; s < stage.counts.x; ++s) {
        vec3 e = slotIlluminance(s, pos, n);
        if (max3(e) <= 0.0)
            continue;
        full += e;
        lit += e * mask[clamp(s, 0, 3)];
    }
#endif
    return clamp(lit / max(full, vec3(1e-6)), 0.0, 1.0);
}

// 0 near the mesh, 1 where the plain ground has faded into the shadow catcher.
float groundFade(vec3 pos) {
    float d = length(pos.xz - stage.meshSphere.xz);
    return smoothstep(stage.ground.z, stage.ground.w, d);
}
