#version 450 core
// Depth of field: a circle of confusion from the focal distance and range (0 inside the focal
// range, 1 at maxBlur) picks the blur radius, as in Hammon 2007, "Practical Post-Process Depth of
// Field" (GPU Gems 3 ch. 28), replacing seed 004's fake DoF. Two half-resolution blurs stand for
// the radii maxBlur / 2 (uAux) and maxBlur (uAux2); the pixel interpolates sharp -> narrow for a
// CoC in [0, 0.5] and narrow -> wide in [0.5, 1], so the blur radius grows about linearly with
// the CoC instead of a sharp image fading into one fixed blur. Near and far sides use the same
// |distance - focus| (pixels in front of the focal range blur as much as those behind it); the
// background counts as infinitely far.
#include "post_common.glsl"
layout(binding = POST_AUX2_UNIT) uniform sampler2D uWide;
layout(location = 0) out vec4 outColor;

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    float z = sceneDepth(px) >= 1.0 ? 1e6 : viewDistance(px);
    float halfRange = 0.5 * PARAM(0, DEPTH_OF_FIELD_FOCALRANGE).x;
    float d = abs(z - PARAM(0, DEPTH_OF_FIELD_FOCALDISTANCE).x) - halfRange;
    float coc = clamp(d / max(halfRange, 0.05), 0.0, 1.0);
    vec4 sharp = texelFetch(uInput, px, 0);
    if (coc <= 0.0) {
        outColor = sharp;
        return;
    }
    vec2 uv = pixelUv(px);
    vec4 narrow = texture(uAux, uv);
    outColor = coc < 0.5 ? mix(sharp, narrow, coc * 2.0)
                         : mix(narrow, texture(uWide, uv), coc * 2.0 - 1.0);
}
