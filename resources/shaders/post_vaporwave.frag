#version 450 core
// Vaporwave (seed 004): the green channel shifted horizontally (more towards the left and right
// edges), desaturation and a purple tint, a checker floor replacing the far background below the
// horizon, then TV static and scanlines.
#include "post_common.glsl"
layout(location = 0) out vec4 outColor;

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(uInput, 0) - 1;
    vec2 uv = pixelUv(px);
    float shift = PARAM(0, VAPORWAVE_ABERRATION).x * (0.25 + 0.75 * abs(uv.x * 2.0 - 1.0));
    vec4 c = texelFetch(uInput, px, 0);
    c.g = texelFetch(uInput, clamp(px + ivec2(int(round(shift)), 0), ivec2(0), size), 0).g;
    vec3 rgb = mix(c.rgb, vec3(luminance(c.rgb)), PARAM(0, VAPORWAVE_DESATURATION).x);
    rgb = mix(rgb, rgb * PARAM(0, VAPORWAVE_TINT).rgb * 2.0, PARAM(0, VAPORWAVE_TINTAMOUNT).x);
    float checker = PARAM(0, VAPORWAVE_CHECKERSIZE).x;
    if (checker >= 1.0 && sceneDepth(px) >= 1.0 && uv.y < 0.5) {
        ivec2 k = ivec2(floor(vec2(px) / checker));
        rgb = ((k.x + k.y) & 1) == 0 ? vec3(1.0, 0.45, 0.85) : vec3(0.25, 0.9, 0.95);
    }
    float frame = floor(post.misc.x * 24.0);
    rgb += PARAM(0, VAPORWAVE_STATICAMOUNT).x * (hash13(vec3(px, frame)) - 0.5);
    rgb *= 1.0 - PARAM(0, VAPORWAVE_SCANLINES).x * float((px.y >> 1) & 1);
    outColor = vec4(max(rgb, vec3(0.0)), c.a);
}
