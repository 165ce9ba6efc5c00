#version 450 core
// Light volumes (the seeds' deferred light volumes): one instance of a proxy sphere per light,
// scaled to the light's radius. The proxy circumscribes the sphere (render/light_passes.cpp),
// back faces only, depth-tested against the G-buffer so only pixels in front of its far side pay.
#include "light_common.glsl"

layout(location = 0) in vec3 aPosition;
layout(location = 0) flat out int vLight;

void main() {
    vLight = gl_InstanceID;
    GpuLight L = lights[gl_InstanceID];
    vec3 world = L.positionRange.xyz + aPosition * L.positionRange.w;
    gl_Position = frame.viewProjMatrix * vec4(world, 1.0);
}
