#version 450 core
// The background's dome (render/background_dome.h): a latitude-longitude sphere around the
// camera in the environment's frame, turned by the environment's rotation into the world and by
// the view's rotation alone into the camera (a background is at infinity: the camera's position
// does not move it). Its clip depth is 0, inside any depth range: the pass draws every pixel
// without a depth test and the surfaces' pass draws the mesh over it.
#include "common_frame.glsl"

// GpuMesh's attributes: the position is the direction, the uv its equirect coordinates.
layout(location = 0) in vec3 aEnvironmentDirection;
layout(location = 3) in vec2 aUv;
layout(location = 0) out vec2 vUv;

void main() {
    // The inverse of common_environment.glsl's toEnvironment: a rotation about +Y.
    float c = frame.envParams.x, s = frame.envParams.y;
    vec3 e = aEnvironmentDirection;
    vec3 world = vec3(c * e.x + s * e.z, e.y, -s * e.x + c * e.z);
    vec4 clip = frame.projMatrix * vec4(mat3(frame.viewMatrix) * world, 0.0);
    gl_Position = vec4(clip.xy, 0.0, clip.w);
    vUv = aUv;
}
