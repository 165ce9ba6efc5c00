#version 450 core
// Sharpen: unsharp mask against the mean of the four direct neighbours.
#include "post_common.glsl"
layout(location = 0) out vec4 outColor;

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(uInput, 0) - 1;
    vec4 c = texelFetch(uInput, px, 0);
    vec4 n = texelFetch(uInput, clamp(px + ivec2(1, 0), ivec2(0), size), 0) +
             texelFetch(uInput, clamp(px - ivec2(1, 0), ivec2(0), size), 0) +
             texelFetch(uInput, clamp(px + ivec2(0, 1), ivec2(0), size), 0) +
             texelFetch(uInput, clamp(px - ivec2(0, 1), ivec2(0), size), 0);
    outColor = vec4(max(c.rgb + PARAM(0, SHARPEN_AMOUNT).x * (c.rgb - 0.25 * n.rgb), 0.0), c.a);
}
