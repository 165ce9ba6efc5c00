#version 450 core
// One frame of a progressive mean (render/progressive_accumulation.h): the frame's pixel as it
// is; the fixed-function blend (constant alpha 1 / (n + 1)) folds it into the mean.
#include "render_bindings.glsl"

layout(binding = BINDING_HDR_TEX) uniform sampler2D uFrame;
layout(location = 0) out vec4 outColor;

void main() {
    outColor = texelFetch(uFrame, ivec2(gl_FragCoord.xy), 0);
}
