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
layout(binding = BINDING_SHADOW_BOUNDS_TEX) uniform sampler2DArray uShadowBounds;

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

// What a lookup of shadow slot s at posWorld (normal n, unit l towards the light) works from:
// the receiver, offset along its normal, in the map (uv, its distance from the light), its plane
// (Isidoro 2006), the reference depth and the blocker search's radius (uv). `outside`: beyond the
// map or nearer than its near plane, where nothing can shadow it.
struct ShadowFootprint {
    vec2 uv;
    float dist, metresPerUv, ref0, searchUv;
    vec2 grad;
    bool outside;
};
ShadowFootprint shadowFootprint(int s, vec3 posWorld, vec3 n, vec3 l) {
    ShadowFootprint f;
    float NdotL = dot(n, l);
    vec4 P = stage.shadowParams[s];
    vec4 Q = stage.shadowScale[s];
    bool persp = P.x > 0.5;
    float dist = -(stage.shadowView[s] * vec4(posWorld, 1.0)).z;
    f.metresPerUv = persp ? Q.x * max(dist, 1e-3) : Q.x;
    float texel = f.metresPerUv * Q.y;
    float sinT = sqrt(saturate(1.0 - NdotL * NdotL));
    vec3 pos = posWorld + n * texel * (0.5 + 1.5 * sinT);
    f.dist = -(stage.shadowView[s] * vec4(pos, 1.0)).z;
    vec4 clip = stage.shadowViewProj[s] * vec4(pos, 1.0);
    f.uv = clip.xy / clip.w * 0.5 + 0.5;
    f.outside = any(lessThan(f.uv, vec2(0.0))) || any(greaterThan(f.uv, vec2(1.0))) ||
                f.dist <= P.y;
    vec3 nL = mat3(stage.shadowView[s]) * n;
    f.grad = clamp(nL.xy / max(nL.z, 0.2), vec2(-5.0), vec2(5.0)) * f.metresPerUv;
    f.ref0 = f.dist - 1.5 * texel;
    // The region where an occluder could hide part of the source.
    float size = P.w;
    float searchUv = persp ? 0.5 * size * (f.dist - P.y) / (f.dist * P.y * Q.x)
                           : 0.5 * size * (f.dist - P.y) / f.metresPerUv;
    f.searchUv = clamp(searchUv, 2.0 * Q.y, 0.04);
    return f;
}

// The penumbra's radius (uv) for an average blocker at distance zb from the light (PCSS).
float shadowPenumbraUv(int s, ShadowFootprint f, float zb) {
    vec4 P = stage.shadowParams[s];
    float size = P.w;
    float penumbraUv = P.x > 0.5 ? 0.5 * size * (f.dist - zb) / max(zb, 1e-3) / f.metresPerUv
                                 : 0.5 * size * (f.dist - zb) / f.metresPerUv;
    return clamp(penumbraUv, 1.5 * stage.shadowScale[s].y, 0.04);
}

// The Poisson taps reach 1.234 of the radius (SHADOW_POISSON[7]); with rounding, this bounds them.
const float SHADOW_POISSON_REACH = 1.2345;

// Least (x) and greatest (y) stored depth of slot s's map over the uv square centre +- halfSize
// (render/shadow_depth_bounds.h): four texels of the level whose texels are at least as wide as
// the square, so that it spans two of them at most each way.
vec2 shadowDepthBounds(int s, vec2 centre, float halfSize) {
    int level = clamp(int(ceil(log2(max(2.0 * halfSize * float(SHADOW_BOUNDS_SIZE), 1.0)))), 0,
                      SHADOW_BOUNDS_LEVELS - 1);
    // log2's rounding: one level up while the square is still wider than a texel.
    level += int(level < SHADOW_BOUNDS_LEVELS - 1 &&
                 2.0 * halfSize * float(SHADOW_BOUNDS_SIZE >> level) > 1.0);
    int size = SHADOW_BOUNDS_SIZE >> level;
    ivec2 lo = clamp(ivec2(floor((centre - halfSize) * float(size))), ivec2(0), ivec2(size - 1));
    ivec2 hi = clamp(ivec2(floor((centre + halfSize) * float(size))), ivec2(0), ivec2(size - 1));
    vec2 a = texelFetch(uShadowBounds, ivec3(lo, s), level).rg;
    vec2 b = texelFetch(uShadowBounds, ivec3(hi.x, lo.y, s), level).rg;
    vec2 c = texelFetch(uShadowBounds, ivec3(lo.x, hi.y, s), level).rg;
    vec2 d = texelFetch(uShadowBounds, ivec3(hi, s), level).rg;
    return vec2(min(min(a.x, b.x), min(c.x, d.x)), max(max(a.y, b.y), max(c.y, d.y)));
}

// What shadowVisibility(s, posWorld, n, l, any noise) returns where the map's depth bounds settle
// it without filtering, else -1: 1 where no texel the blocker search can read is nearer than its
// reference (no blocker: the lookup returns 1 before filtering), 0 where the ground blocks the
// light or every texel the search and the filter can read is a blocker (all 16 compares fail).
// One square bounds both: the filter's radius, the penumbra of a blocker farther than the near
// plane, never exceeds the search's (shadowFootprint, shadowPenumbraUv). Each tap's offset is
// bounded by SHADOW_POISSON_REACH x its radius and its texels by two more (the nearest texel of
// the search, the 2x2 of a compare), and eps leaves room for the lookup's rounding, so a
// settled value is exactly the lookup's, whatever the noise.
float shadowVisibilityBound(int s, vec3 posWorld, vec3 n, vec3 l) {
    if (groundBlocksLight(s, posWorld))
        return 0.0;
    ShadowFootprint f = shadowFootprint(s, posWorld, n, l);
    if (f.outside)
        return 1.0;
    // 1 % more: the filter's radius can pass the search's by the normal offset's share of the
    // distance (perspective maps) and the blockers' mean by its rounding.
    float reach = 1.01 * SHADOW_POISSON_REACH * f.searchUv;
    float tilt = length(f.grad) * reach + 1e-5 * max(abs(f.ref0), 1.0);
    vec2 bounds = shadowDepthBounds(s, f.uv, reach + 2.0 * stage.shadowScale[s].y);
    if (shadowLinearDepth(s, bounds.x) >= f.ref0 + tilt)
        return 1.0;
    if (shadowLinearDepth(s, bounds.y) < f.ref0 - tilt &&
        bounds.y < shadowStoredDepth(s, f.ref0 - tilt))
        return 0.0;
    return -1.0;
}

// Fraction of shadow slot s's light that reaches posWorld (normal n, unit l towards the light);
// 0 with the ground in between, 1 outside the map (no caster there). noise in [0, 1) rotates the
// taps. A surface facing away from the light is looked up like any other (the shading's N.L
// already darkens it): the half-resolution mask is upsampled across the terminator, where a
// hard 0 on the far side would bleed into the lit side's last pixels.
float shadowVisibility(int s, vec3 posWorld, vec3 n, vec3 l, float noise) {
    if (groundBlocksLight(s, posWorld))
        return 0.0;
    ShadowFootprint f = shadowFootprint(s, posWorld, n, l);
    if (f.outside)
        return 1.0;
    float angle = noise * 6.2831853;
    mat2 rot = mat2(cos(angle), sin(angle), -sin(angle), cos(angle));

    // Blocker search over the region where an occluder could hide part of the source.
    float blockers = 0.0, blockerSum = 0.0;
    for (int i = 0; i < 8; ++i) {
        vec2 o = rot * SHADOW_POISSON[2 * i + 1] * f.searchUv;
        float zb =
            shadowLinearDepth(s, textureLod(uShadowDepth, vec3(f.uv + o, float(s)), 0.0).r);
        if (zb < f.ref0 + dot(f.grad, o)) {
            blockers += 1.0;
            blockerSum += zb;
        }
    }
    if (blockers == 0.0)
        return 1.0;
    float radius = shadowPenumbraUv(s, f, blockerSum / blockers);
    float lit = 0.0;
    for (int i = 0; i < 16; ++i) {
        vec2 o = rot * SHADOW_POISSON[i] * radius;
        lit += texture(uShadowCompare,
                       vec4(f.uv + o, float(s), shadowStoredDepth(s, f.ref0 + dot(f.grad, o))));
    }
    return lit / 16.0;
}
