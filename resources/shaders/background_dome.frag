#version 450 core
// The background's display value from its equirect cache (render/background_dome.h) at the
// dome's interpolated coordinates: one bilinear fetch.
#include "render_bindings.glsl"

layout(binding = BINDING_HDR_TEX) uniform sampler2D uBackgroundCache;
layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outColor;

void main() { outColor = textureLod(uBackgroundCache, vUv, 0.0); }
