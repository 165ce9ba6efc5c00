#version 450 core
// The inline frame's background from its picture uFactor times smaller each way
// (render/background_downsample.h): one bilinear fetch. Texel t of the small target stands for
// the full-resolution point uFactor (t + 0.5) (lighting.frag's BACKGROUND_DOWNSAMPLE), so pixel
// p's centre p + 0.5 sits at (p + 0.5) / uFactor in its texel units: uv = gl_FragCoord / (uFactor
// x its size).
#include "render_bindings.glsl"

layout(binding = BINDING_HDR_TEX) uniform sampler2D uSmallBackground;
layout(location = 0) uniform float uFactor;
layout(location = 0) out vec4 outColor;

void main() {
    vec2 size = vec2(textureSize(uSmallBackground, 0)) * uFactor;
    outColor = textureLod(uSmallBackground, gl_FragCoord.xy / size, 0.0);
}
