#version 450 core
// Depth of field: a circle of confusion from the focal distance and range (0 inside the focal
// range, 1 at maxBlur) blends the sharp image with a blurred copy (uAux, half resolution,
// bilinear), as in Hammon 2007, "Practical Post-Process Depth of Field" (GPU Gems 3 ch. 28),
// replacing seed 004's fake DoF. Background pixels count as infinitely far.
#include "post_common.glsl"
layout(location = 0) out vec4 outColor;

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    float z = sceneDepth(px) >= 1.0 ? 1e6 : viewDistance(px);
    float halfRange = 0.5 * PARAM(0, DEPTH_OF_FIELD_FOCALRANGE).x;
    float d = abs(z - PARAM(0, DEPTH_OF_FIELD_FOCALDISTANCE).x) - halfRange;
    float coc = clamp(d / max(halfRange, 0.05), 0.0, 1.0);
    vec4 sharp = texelFetch(uInput, px, 0);
    vec4 blurred = texture(uAux, pixelUv(px));
    outColor = coc > 0.0 ? mix(sharp, blurred, coc) : sharp;
}
