#version 450 core
#include "common_frame.glsl"

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec4 aTangent;
layout(location = 3) in vec2 aUv;
// The mesh's visibility from itself (render/gpu_mesh.h kVisibilityLocation): bent normal and
// unoccluded fraction; (0, 0, 0, 1), the generic value, where the mesh has none.
layout(location = 4) in vec4 aVisibility;

out vec3 vNormal;
out vec4 vTangent;
out vec2 vUv;
out vec3 vWorldPosition;
out vec4 vVisibility;

void main() {
    // The preview mesh sits at the origin (model matrix = identity for now).
    vNormal = aNormal;
    vTangent = aTangent;
    vUv = aUv;
    vWorldPosition = aPosition;
    vVisibility = aVisibility;
    gl_Position = frame.viewProjMatrix * vec4(aPosition, 1.0);
}
