#version 450 core
// The ground (render/ground_pass.h): a square at the mesh's lowest point, centred under it, from
// gl_VertexID alone (a triangle strip of four vertices, counter-clockwise seen from above).
#include "common_frame.glsl"

layout(location = 1) uniform vec4 uGround; // centre x, height, centre z, half size (m)

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
    vec3 pos = vec3(uGround.x + corner.x * uGround.w, uGround.y, uGround.z - corner.y * uGround.w);
    gl_Position = frame.viewProjMatrix * vec4(pos, 1.0);
}
