#version 450 core
// Camera motion blur from depth and the previous view-projection (seed 002; Rosado 2007,
// "Motion Blur as a Post-Processing Effect", GPU Gems 3 ch. 27): the pixel's world position is
// reconstructed with the inverse view-projection, projected with last frame's matrix, and the
// image is averaged along the screen-space difference (centred on the pixel, unlike the seed).
// Frame blending (Unity post-processing stack v1, after Kino Motion): with uPass.y = 1, last
// frame's input to this effect is on uAux and blended in with weight frameBlend.
#include "post_common.glsl"
layout(location = 0) out vec4 outColor;

vec4 blur(ivec2 px) {
    vec2 uv = pixelUv(px);
    vec4 ndc = vec4(uv * 2.0 - 1.0, sceneDepth(px) * 2.0 - 1.0, 1.0);
    vec4 world = post.invViewProj * ndc;
    world /= world.w;
    vec4 previous = post.prevViewProj * world;
    previous /= previous.w;
    vec2 velocity = (ndc.xy - previous.xy) * 0.5 * PARAM(0, MOTION_BLUR_STRENGTH).x; // in uv
    vec4 centre = texelFetch(uInput, px, 0);
    if (length(velocity * post.viewport.xy) < 0.05) // a still camera changes nothing
        return centre;
    int n = max(int(PARAM(0, MOTION_BLUR_SAMPLES).x + 0.5), 2);
    vec4 sum = vec4(0.0);
    for (int i = 0; i < n; ++i)
        sum += texture(uInput, uv + velocity * (float(i) / float(n - 1) - 0.5));
    return sum / float(n);
}

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 c = blur(px);
    if (uPass.y == 1)
        c = mix(c, texelFetch(uAux, px, 0), PARAM(0, MOTION_BLUR_FRAMEBLEND).x);
    outColor = c;
}
