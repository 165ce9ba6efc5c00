// Colour grading in scene-linear: exposure, white balance, contrast around 18 % grey (in log2,
// as ACEScct-style grading does), saturation, then ASC-CDL-like lift / gamma / gain.
// Pointwise; included by a generated main.
#include "post_common.glsl"

vec4 post_color_grading(vec4 color, ivec2 px, int b) {
    vec3 c = max(color.rgb, vec3(0.0)) * exp2(PARAM(b, COLOR_GRADING_EXPOSURE).x);
    float t = PARAM(b, COLOR_GRADING_TEMPERATURE).x, g = PARAM(b, COLOR_GRADING_TINT).x;
    vec3 balance = vec3(1.0 + 0.3 * t, 1.0 - 0.3 * g, 1.0 - 0.3 * t) * vec3(1.0, 1.0, 1.0);
    c *= balance / luminance(balance);
    const float grey = 0.18;
    c = grey * pow(c / grey + 1e-6, vec3(PARAM(b, COLOR_GRADING_CONTRAST).x));
    c = mix(vec3(luminance(c)), c, PARAM(b, COLOR_GRADING_SATURATION).x);
    vec3 lift = PARAM(b, COLOR_GRADING_LIFT).rgb;
    c = PARAM(b, COLOR_GRADING_GAIN).rgb * (c + lift * (1.0 - clamp(c, 0.0, 1.0)));
    c = pow(max(c, vec3(0.0)), 1.0 / max(PARAM(b, COLOR_GRADING_GAMMA).rgb, vec3(0.01)));
    return vec4(c, color.a);
}
