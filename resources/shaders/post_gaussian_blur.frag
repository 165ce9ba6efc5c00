#version 450 core
// Separable gaussian blur (seed 001): weights G(x) = e^(-x^2 / 2 sigma^2) / sqrt(2 pi sigma^2),
// normalised on the CPU (render/post_effect.cpp gaussianWeights). Wide kernels run at half
// resolution: a 2x2 box downsample (one bilinear tap), the blur, a bilinear upsample.
//   uPass.x 0: horizontal, 1: vertical (uPass.y taps each side), 2: downsample, 3: upsample.
#include "post_common.glsl"
layout(location = 0) out vec4 outColor;
layout(location = POST_WEIGHTS_LOCATION) uniform float uWeights[POST_MAX_TAPS];

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    if (POST_PASS >= 2) {
        outColor = texture(uInput, gl_FragCoord.xy / uTexel.zw);
        return;
    }
    ivec2 size = textureSize(uInput, 0) - 1;
    ivec2 dir = POST_PASS == 0 ? ivec2(1, 0) : ivec2(0, 1);
    vec4 sum = texelFetch(uInput, px, 0) * uWeights[0];
    for (int i = 1; i <= uPass.y; ++i)
        sum += (texelFetch(uInput, clamp(px + dir * i, ivec2(0), size), 0) +
                texelFetch(uInput, clamp(px - dir * i, ivec2(0), size), 0)) * uWeights[i];
    outColor = sum;
}
