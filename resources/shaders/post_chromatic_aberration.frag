#version 450 core
// Radial chromatic aberration: red sampled outwards and blue inwards along the direction from
// the centre, `amount` pixels at the corners.
#include "post_common.glsl"
layout(location = 0) out vec4 outColor;

void main() {
    vec2 uv = gl_FragCoord.xy / uTexel.zw;
    vec2 offset = (uv - 0.5) * 2.0 * 0.70710678 * PARAM(0, CHROMATIC_ABERRATION_AMOUNT).x *
                  uTexel.xy;
    vec4 c = texture(uInput, uv);
    c.r = texture(uInput, uv + offset).r;
    c.b = texture(uInput, uv - offset).b;
    outColor = c;
}
