// Shadow-map lookups of the screen-space shadow mask pass (shadow_mask.frag, render/shadow_mask.h;
// the lighting passes read its result through shadow_mask.glsl; docs/shadows.md): PCSS
// (Fernando 2005, "Percentage-Closer Soft Shadows"): a blocker search whose average depth sizes
// the penumbra from the light's source size, then percentage-closer filtering over it with the
// hardware's 2x2 compare (Poisson taps rotated per pixel by interleaved gradient noise, Jimenez
// 2014). Acne is kept off by three biases: the depth maps' slope-scaled polygon offset, a normal
// offset of the receiver that grows with the slope (Holbert 2011, "Normal Offset Shadows") and a
// receiver-plane depth per tap from the surface normal in light space (Isidoro 2006), plus one
// texel of constant bias.
#include "render_bindings.glsl"
#include "stage_interface.glsl"
#include "common_frame.glsl"
#include "common_hash.glsl"

layout(binding = BINDING_SHADOW_COMPARE_TEX) uniform sampler2DArrayShadow uShadowCompare;
layout(binding = BINDING_SHADOW_DEPTH_TEX) uniform sampler2DArray uShadowDepth;

const vec2 SHADOW_POISSON[16] = vec2[](
    vec2(-0.94201624, -0.39906216), vec2(0.94558609, -0.76890725), vec2(-0.09418410, -0.92938870),
    vec2(0.34495938, 0.29387760), vec2(-0.91588581, 0.45771432), vec2(-0.81544232, -0.87912464),
    vec2(-0.38277543, 0.27676845), vec2(0.97484398, 0.75648379), vec2(0.44323325, -0.97511554),
    vec2(0.53742981, -0.47373420), vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
    vec2(-0.24188840, 0.99706507), vec2(-0.81409955, 0.91437590), vec2(0.19984126, 0.78641367),
    vec2(0.14383161, -0.14100790));

// Distance from the light (m) of a stored depth, and back.
float shadowLinearDepth(int s, float d) {
    vec4 P = stage.shadowParams[s];
    return P.x > 0.5 ? P.y * P.z / (P.z - d * (P.z - P.y)) : P.y + d * (P.z - P.y);
}
float shadowStoredDepth(int s, float dist) {
    vec4 P = stage.shadowParams[s];
    float d = P.x > 0.5 ? P.z / (P.z - P.y) * (1.0 - P.y / max(dist, 1e-6))
                        : (dist - P.y) / (P.z - P.y);
    return clamp(d, 0.0, 1.0);
}

// Whether the ground (stage.ground, a square stage.groundSquare) stands between posWorld and shadow
// slot s's light: a light under the floor does not light what stands on it (docs/shadows.md, "The
// ground as a caster"). Analytic, so the ground needs no room in the maps: where the segment
// towards the light crosses the ground's plane, inside the square. Off with the ground.
bool groundBlocksLight(int s, vec3 posWorld) {
    float h = stage.ground.x;
    vec4 L = stage.shadowLight[s];
    if (stage.ground.y < 0.5)
        return false;
    // Directional: L.xyz is the way towards the light, crossing where y falls by posWorld.y - h.
    // Local: the fraction of the way to the light's centre at which y reaches h.
    vec3 toLight = L.w < 0.5 ? L.xyz : L.xyz - posWorld;
    bool below = L.w < 0.5 ? L.y < 0.0 : L.y < h;
    if (!below)
        return false;
    // The ground itself faces away from a light under it (the lookup does not test facing: the
    // half-resolution mask is upsampled across terminators, shadow_mask.glsl).
    if (posWorld.y <= h + 1e-4 * max(abs(h), 1.0))
        return true;
    vec2 crossing = posWorld.xz + toLight.xz * ((posWorld.y - h) / max(-toLight.y, 1e-6));
    return all(lessThanEqual(abs(crossing - stage.groundSquare.xz), vec2(stage.groundSquare.w)));
}

// Fraction of shadow slot s's light that reaches posWorld (normal n, unit l towards the light);
// 0 with the ground in between, 1 outside the map (no caster there). noise in [0, 1) rotates the
// taps. A surface facing away from the light is looked up like any other (the shading's N.L
// already darkens it): the half-resolution mask is upsampled across the terminator, where a
// hard 0 on the far side would bleed into the lit side's last pixels.
float shadowVisibility(int s, vec3 posWorld, vec3 n, vec3 l, float noise) {
    float NdotL = dot(n, l);
    if (groundBlocksLight(s, posWorld))
        return 0.0;
    vec4 P = stage.shadowParams[s];
    vec4 Q = stage.shadowScale[s];
    bool persp = P.x > 0.5;
    float dist = -(stage.shadowView[s] * vec4(posWorld, 1.0)).z;
    float metresPerUv = persp ? Q.x * max(dist, 1e-3) : Q.x;
    float texel = metresPerUv * Q.y;
    float sinT = sqrt(saturate(1.0 - NdotL * NdotL));
    vec3 pos = posWorld + n * texel * (0.5 + 1.5 * sinT);
    dist = -(stage.shadowView[s] * vec4(pos, 1.0)).z;
    vec4 clip = stage.shadowViewProj[s] * vec4(pos, 1.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || dist <= P.y)
        return 1.0;
    // The receiver's plane: distance from the light per unit of uv (Isidoro 2006).
    vec3 nL = mat3(stage.shadowView[s]) * n;
    vec2 grad = clamp(nL.xy / max(nL.z, 0.2), vec2(-5.0), vec2(5.0)) * metresPerUv;
    float ref0 = dist - 1.5 * texel;
    float angle = noise * 6.2831853;
    mat2 rot = mat2(cos(angle), sin(angle), -sin(angle), cos(angle));

    // Blocker search over the region where an occluder could hide part of the source.
    float size = P.w;
    float searchUv = persp ? 0.5 * size * (dist - P.y) / (dist * P.y * Q.x)
                           : 0.5 * size * (dist - P.y) / metresPerUv;
    searchUv = clamp(searchUv, 2.0 * Q.y, 0.04);
    float blockers = 0.0, blockerSum = 0.0;
    for (int i = 0; i < 8; ++i) {
        vec2 o = rot * SHADOW_POISSON[2 * i + 1] * searchUv;
        float zb = shadowLinearDepth(s, textureLod(uShadowDepth, vec3(uv + o, float(s)), 0.0).r);
        if (zb < ref0 + dot(grad, o)) {
            blockers += 1.0;
            blockerSum += zb;
        }
    }
    if (blockers == 0.0)
        return 1.0;
    float zb = blockerSum / blockers;
    float penumbraUv = persp ? 0.5 * size * (dist - zb) / max(zb, 1e-3) / metresPerUv
                             : 0.5 * size * (dist - zb) / metresPerUv;
    float radius = clamp(penumbraUv, 1.5 * Q.y, 0.04);
    float lit = 0.0;
    for (int i = 0; i < 16; ++i) {
        vec2 o = rot * SHADOW_POISSON[i] * radius;
        lit += texture(uShadowCompare,
                       vec4(uv + o, float(s), shadowStoredDepth(s, ref0 + dot(grad, o))));
    }
    return lit / 16.0;
}
