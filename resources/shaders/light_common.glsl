// Point, spot and area lights shared by the three many-light paths (light_volume.*,
// light_tiled.comp, light_brute.frag): the light buffer, the G-buffer read of one pixel, and one
// light's contribution. CPU twins of the light functions: core/lights.cpp. Units: docs/units.md.
#include "gbuffer_read.glsl"
#include "light_lobes.glsl"
#include "light_bindings.glsl"
#include "shadow_mask.glsl"

#define LIGHT_POINT 1
#define LIGHT_SPOT 2
#define LIGHT_AREA_SPHERE 3
#define LIGHT_AREA_RECTANGLE 4
#define MIN_LIGHT_DISTANCE 0.01

// Mirrors struct GpuLight in render/light_passes.cpp (std430, vec4 only).
struct GpuLight {
    vec4 positionRange;  // xyz world position, w influence radius (m)
    vec4 colorIntensity; // rgb colour x intensity (candela; nits for area lights)
    vec4 directionType;  // xyz unit direction the light travels, w type (LIGHT_*)
    vec4 params;         // spot: cos outer, cos inner; area: radius or half width, half height;
                         // z: shadow slot + 1 (0: no shadow; shadow_mask.glsl)
};

layout(std430, binding = BINDING_LIGHT_SSBO) readonly buffer LightBuffer {
    GpuLight lights[];
};
layout(location = LOCATION_LIGHT_COUNT) uniform int uLightCount;

// Karis 2013, "Real Shading in Unreal Engine 4" (windowed inverse-square falloff)
float windowFalloff(float distance, float range) {
    if (range <= 0.0)
        return 0.0;
    float r = distance / range;
    float w = saturate(1.0 - r * r * r * r);
    return w * w;
}
float distanceAttenuation(float distance, float range) {
    return windowFalloff(distance, range) /
           max(distance * distance, MIN_LIGHT_DISTANCE * MIN_LIGHT_DISTANCE);
}
// Spot cone: smoothstep from the outer cone (0) to the inner cone (1) over cos(angle).
float spotConeAttenuation(float cosAngle, float cosOuter, float cosInner) {
    return smoothstep(cosOuter, max(cosInner, cosOuter + 1e-4), cosAngle);
}
// Karis 2013 eq. 11: the point of a sphere light closest to the reflection ray.
vec3 sphereRepresentativePoint(vec3 toCenter, vec3 r, float radius) {
    vec3 centerToRay = dot(toCenter, r) * r - toCenter;
    return toCenter + centerToRay * saturate(radius / max(length(centerToRay), 1e-6));
}
// Karis 2013's representative point carried to a one-sided rectangle: where the reflection ray
// meets the plane, clamped to the rectangle (else the clamped projection of the shaded point).
vec3 rectangleRepresentativePoint(vec3 toCenter, vec3 ax, vec3 ay, float hx, float hy, vec3 r) {
    vec3 normal = cross(ax, ay);
    float denom = dot(r, normal);
    vec3 onPlane = toCenter - dot(toCenter, normal) * normal;
    if (abs(denom) > 1e-4) {
        float t = dot(toCenter, normal) / denom;
        if (t > 0.0)
            onPlane = r * t;
    }
    vec3 local = onPlane - toCenter;
    return toCenter + ax * clamp(dot(local, ax), -hx, hx) + ay * clamp(dot(local, ay), -hy, hy);
}
// Rectangle axes from the light's direction (its normal): x horizontal, y completes the frame.
void rectangleAxes(vec3 normal, out vec3 ax, out vec3 ay) {
    vec3 up = abs(normal.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    ax = normalize(cross(up, normal));
    ay = cross(normal, ax);
}

// One pixel of the G-buffer, ready to shade (gbuffer_read.glsl), with every shadow slot's
// visibility there (shadowMaskAll, upsampled once per pixel for all its lights); false at the far
// plane.
bool loadShadingPoint(ivec2 pixel, out ShadingPoint p, out vec4 shadows) {
    float depth = texelFetch(gDepthTex, pixel, 0).r;
    shadows = vec4(1.0);
    if (depth >= 1.0)
        return false;
    p = readShadingPoint(pixel, depth);
    shadows = shadowMaskAll(pixel, -p.posView.z, p.materialId);
    return true;
}

// Whether the light reaches the point (what every path culls by, and what the lights-per-pixel
// view counts): inside its influence sphere and, for a spot light, inside its outer cone (where
// spotConeAttenuation() is non-zero; the volumes path's cone proxy covers exactly that region).
bool lightReaches(GpuLight L, vec3 posWorld) {
    vec3 d = L.positionRange.xyz - posWorld;
    float d2 = dot(d, d);
    if (d2 >= L.positionRange.w * L.positionRange.w)
        return false;
    if (int(L.directionType.w) == LIGHT_SPOT)
        return dot(L.directionType.xyz, -d) > L.params.x * sqrt(d2);
    return true;
}

// One light's contribution to the pixel for debug view `view`: radiance for the final image and
// the lobe views, 1 for the lights-per-pixel view, 0 where the light does not reach. @p shadows:
// the pixel's shadow slots (loadShadingPoint).
vec3 shadeLocalLight(GpuLight L, ShadingPoint p, vec4 shadows, int view) {
    // The shadow catcher only darkens the background (lighting.frag): no light is added to it.
    if (!lightReaches(L, p.posWorld) || p.materialId == GROUND_CATCHER_MATERIAL_ID)
        return vec3(0.0);
    if (view == DEBUG_LIGHTS_PER_PIXEL)
        return vec3(1.0);
    int type = int(L.directionType.w);
    vec3 toLight = L.positionRange.xyz - p.posWorld;
    float dist = length(toLight);
    vec3 l = toLight / max(dist, 1e-6);
    float range = L.positionRange.w;
    vec3 lSpecular = l;
    float widen = 0.0;
    float illuminance; // per unit colour x intensity
    if (type == LIGHT_POINT || type == LIGHT_SPOT) {
        illuminance = distanceAttenuation(dist, range);
        if (type == LIGHT_SPOT)
            illuminance *= spotConeAttenuation(dot(L.directionType.xyz, -l), L.params.x, L.params.y);
    } else if (type == LIGHT_AREA_SPHERE) {
        float radius = L.params.x;
        float d = max(dist, max(radius, MIN_LIGHT_DISTANCE));
        illuminance = PI * radius * radius / (d * d) * windowFalloff(dist, range);
        vec3 r = reflect(-p.v, p.n);
        lSpecular = normalize(sphereRepresentativePoint(toLight, r, radius));
        widen = radius / (2.0 * d);
    } else {
        vec3 ax, ay;
        rectangleAxes(L.directionType.xyz, ax, ay);
        float hx = L.params.x, hy = L.params.y;
        // Small-source form factor of the rectangle, A cos(theta_light) / d^2, one-sided.
        float cosLight = saturate(dot(L.directionType.xyz, -l));
        float d = max(dist, MIN_LIGHT_DISTANCE);
        illuminance = 4.0 * hx * hy * cosLight / (d * d) * windowFalloff(dist, range);
        vec3 r = reflect(-p.v, p.n);
        lSpecular = normalize(rectangleRepresentativePoint(toLight, ax, ay, hx, hy, r));
        widen = sqrt(4.0 * hx * hy / PI) / (2.0 * d); // the disc of the same area
    }
    // Below the geometric horizon of a bent shading normal (gbuffer_read.glsl); an area light by
    // the share of its disc above it (its angular radius about 2 widen).
    illuminance *= geometricHorizon(p, l, 2.0 * widen);
    if (illuminance <= 0.0)
        return vec3(0.0);
    int shadowSlot = int(L.params.z) - 1;
    if (shadowSlot >= 0)
        illuminance *= shadows[clamp(shadowSlot, 0, 3)];
    Lobes o = shadeLobes(p.s, p.n, p.v, l, lSpecular, widen);
    return selectLobes(o, view) * L.colorIntensity.rgb * illuminance;
}
