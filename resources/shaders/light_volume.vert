#version 450 core
// Light volumes (the seeds' deferred light volumes): one instance of a proxy per light, scaled to
// the light's radius, back faces only, depth-tested against the G-buffer so only pixels in front
// of its far side pay. Point and area lights (and wide spots) use a sphere that circumscribes the
// light's range; spot lights a cone (apex at the light, axis along its direction, height = range,
// base radius = range tan(outer)) that encloses the part of the range sphere inside the outer
// cone: a point there at axial distance t <= range lies within t tan(outer). Both meshes are built
// in render/light_passes.cpp.
#include "light_common.glsl"

layout(location = 0) in vec3 aPosition;
layout(location = 0) flat out int vLight;
layout(location = LOCATION_PROXY_CONE) uniform int uProxyCone;
layout(location = LOCATION_INSTANCE_BASE) uniform int uInstanceBase;

void main() {
    vLight = uInstanceBase + gl_InstanceID;
    GpuLight L = lights[vLight];
    float range = L.positionRange.w;
    vec3 world;
    if (uProxyCone != 0) {
        vec3 axis = L.directionType.xyz;
        vec3 up = abs(axis.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
        vec3 ax = normalize(cross(up, axis));
        vec3 ay = cross(axis, ax);
        float cosOuter = L.params.x;
        float tanOuter = sqrt(max(1.0 - cosOuter * cosOuter, 0.0)) / max(cosOuter, 1e-4);
        float radial = range * tanOuter;
        world = L.positionRange.xyz + (ax * aPosition.x + ay * aPosition.y) * radial +
                axis * (aPosition.z * range);
    } else {
        world = L.positionRange.xyz + aPosition * range;
    }
    gl_Position = frame.viewProjMatrix * vec4(world, 1.0);
}
