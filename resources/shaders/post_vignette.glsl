// Vignette with seed 001's controls: centre, roundness, intensity, smoothness, blend, colour.
// Pointwise; included by a generated main. Corners are darkened by exactly `intensity`.
#include "post_common.glsl"

vec4 post_vignette(vec4 color, ivec2 px, int b) {
    vec2 center = vec2(PARAM(b, VIGNETTE_CENTERX).x, PARAM(b, VIGNETTE_CENTERY).x);
    vec2 d = abs(pixelUv(px) - center) * 2.0; // 1 on the border of a centred vignette
    // A superellipse: p = 2 round, p = 8 nearly square; normalised so a corner is at r = 1.
    float p = mix(8.0, 2.0, PARAM(b, VIGNETTE_ROUNDNESS).x);
    float r = pow(pow(d.x, p) + pow(d.y, p), 1.0 / p) / pow(2.0, 1.0 / p);
    float mask = smoothstep(1.0 - PARAM(b, VIGNETTE_SMOOTHNESS).x, 1.0, r);
    float k = PARAM(b, VIGNETTE_INTENSITY).x * mask;
    vec3 darkened = color.rgb * (1.0 - k);
    vec3 tinted = mix(color.rgb, PARAM(b, VIGNETTE_COLOR).rgb, k);
    return vec4(mix(darkened, tinted, PARAM(b, VIGNETTE_BLEND).x), color.a);
}
