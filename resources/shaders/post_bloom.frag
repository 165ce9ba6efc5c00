#version 450 core
// Bloom (seeds 000 and 004) as in Jimenez 2014, "Next Generation Post Processing in Call of Duty:
// Advanced Warfare": a 13-tap downsample chain from half resolution, a 3x3 tent upsample chain
// accumulated additively (blending ONE, ONE), then an additive composite. The bright pass uses
// the soft knee of Unity's post-processing stack (quadratic curve around the threshold).
//   uPass.x 0: bright pass + downsample (uInput full resolution), 1: downsample,
//           2: tent upsample of uInput (added to the bound target), 3: composite
//           (uInput: the image, uAux: bloom level 0), uPass.y: number of levels (composite).
// Each pass is its own program (POST_PASS, post_common.glsl).
#include "post_common.glsl"
layout(location = 0) out vec4 outColor;

vec3 tap(vec2 uv, vec2 offset) { return texture(uInput, uv + offset * uTexel.xy).rgb; }

vec3 downsample13(vec2 uv) {
    vec3 a = tap(uv, vec2(-2, 2)), b = tap(uv, vec2(0, 2)), c = tap(uv, vec2(2, 2));
    vec3 d = tap(uv, vec2(-2, 0)), e = tap(uv, vec2(0, 0)), f = tap(uv, vec2(2, 0));
    vec3 g = tap(uv, vec2(-2, -2)), h = tap(uv, vec2(0, -2)), i = tap(uv, vec2(2, -2));
    vec3 j = tap(uv, vec2(-1, 1)), k = tap(uv, vec2(1, 1));
    vec3 l = tap(uv, vec2(-1, -1)), m = tap(uv, vec2(1, -1));
    return e * 0.125 + (a + c + g + i) * 0.03125 + (b + d + f + h) * 0.0625 +
           (j + k + l + m) * 0.125;
}

vec3 tent9(sampler2D s, vec2 uv, vec2 texel) {
    vec3 sum = texture(s, uv).rgb * 4.0;
    sum += (texture(s, uv + vec2(texel.x, 0)).rgb + texture(s, uv - vec2(texel.x, 0)).rgb +
            texture(s, uv + vec2(0, texel.y)).rgb + texture(s, uv - vec2(0, texel.y)).rgb) * 2.0;
    sum += texture(s, uv + texel).rgb + texture(s, uv - texel).rgb +
           texture(s, uv + vec2(texel.x, -texel.y)).rgb + texture(s, uv + vec2(-texel.x, texel.y)).rgb;
    return sum / 16.0;
}

vec3 brightPass(vec3 c) {
    float threshold = PARAM(0, BLOOM_THRESHOLD).x;
    float knee = max(threshold * PARAM(0, BLOOM_KNEE).x, 1e-5);
    float br = max3(c);
    float rq = clamp(br - threshold + knee, 0.0, 2.0 * knee);
    rq = rq * rq / (4.0 * knee);
    return c * max(rq, br - threshold) / max(br, 1e-5);
}

void main() {
    vec2 uv = gl_FragCoord.xy / uTexel.zw;
    if (POST_PASS == 0) {
        outColor = vec4(brightPass(downsample13(uv)), 1.0);
    } else if (POST_PASS == 1) {
        outColor = vec4(downsample13(uv), 1.0);
    } else if (POST_PASS == 2) {
        outColor = vec4(tent9(uInput, uv, uTexel.xy), 1.0);
    } else {
        vec4 c = texelFetch(uInput, ivec2(gl_FragCoord.xy), 0);
        // One bilinear tap: the upsample chain already tent-filtered every level.
        vec3 bloom = texture(uAux, uv).rgb / float(max(uPass.y, 1));
        outColor = vec4(c.rgb + PARAM(0, BLOOM_INTENSITY).x * PARAM(0, BLOOM_TINT).rgb * bloom, c.a);
    }
}
