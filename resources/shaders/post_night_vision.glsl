// Night vision (seed 000): luminance times green-weighted channels, animated grain, vignetting.
// Pointwise; included by a generated main.
#include "post_common.glsl"

vec4 post_night_vision(vec4 color, ivec2 px, int b) {
    vec3 c = luminance(color.rgb) * PARAM(b, NIGHT_VISION_WEIGHTS).rgb;
    float n = hash13(vec3(px, floor(post.misc.x * 24.0))) - 0.5;
    c *= 1.0 + 2.0 * PARAM(b, NIGHT_VISION_GRAIN).x * n;
    float r = length(pixelUv(px) - 0.5) * 1.41421356;
    c *= 1.0 - PARAM(b, NIGHT_VISION_VIGNETTING).x * smoothstep(0.4, 1.0, r);
    return vec4(max(c, vec3(0.0)), color.a);
}
