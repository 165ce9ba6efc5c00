#version 450 core
// Pixelation (seed 000): every cellSize x cellSize cell takes the colour at its centre, so each
// cell is exactly constant.
#include "post_common.glsl"
layout(location = 0) out vec4 outColor;

void main() {
    int cell = max(int(PARAM(0, PIXELATE_CELLSIZE).x + 0.5), 1);
    ivec2 px = ivec2(gl_FragCoord.xy);
    ivec2 centre = min((px / cell) * cell + cell / 2, textureSize(uInput, 0) - 1);
    outColor = texelFetch(uInput, centre, 0);
}
