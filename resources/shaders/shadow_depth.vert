#version 450 core
// The depth of the preview mesh seen from a shadow-casting light (render/shadow_maps.cpp).
layout(location = 0) in vec3 aPosition;
layout(location = 0) uniform mat4 uViewProj;

void main() {
    gl_Position = uViewProj * vec4(aPosition, 1.0);
}
