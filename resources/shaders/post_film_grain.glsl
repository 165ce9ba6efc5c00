// Film grain: white noise per grain cell, changing 24 times a second, strongest in midtones.
// Pointwise; included by a generated main.
#include "post_common.glsl"

vec4 post_film_grain(vec4 color, ivec2 px, int b) {
    vec2 cell = floor(vec2(px) / max(PARAM(b, FILM_GRAIN_SIZE).x, 1.0));
    float n = hash13(vec3(cell, floor(post.misc.x * 24.0))) - 0.5;
    float l = luminance(color.rgb);
    float response = 4.0 * l * (1.0 - clamp(l, 0.0, 1.0)) + 0.1;
    return vec4(max(color.rgb + PARAM(b, FILM_GRAIN_INTENSITY).x * n * response, 0.0), color.a);
}
