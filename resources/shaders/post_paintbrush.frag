#version 450 core
// Paintbrush (seed 004). Pass 0 (the pre-pass, half resolution): curl noise (Bridson et al. 2007,
// "Curl-Noise for Procedural Fluid Flow") of a gradient-noise potential gives each pixel a stroke
// direction; the noise's third coordinate follows a smoothed step of time, so strokes hold still
// and then change smoothly every `period` seconds. Pass 1: an imaginary grid of brushScale
// cells; each cell paints a rotated ellipse in its centre's colour along the curl direction, and
// a pixel accumulates the strokes of the 5x5 cells around it (weighted by distance), with noise
// roughening the stroke edges. uAux: the curl pre-pass.
#include "post_common.glsl"
layout(location = 0) out vec4 outColor;

vec3 grad3(vec3 c) {
    return normalize(vec3(hash13(c), hash13(c + 17.0), hash13(c + 43.0)) - 0.5 + 1e-4);
}
// Perlin 2002, "Improving Noise" (gradient noise, quintic fade)
float gradientNoise(vec3 p) {
    vec3 i = floor(p), f = fract(p);
    vec3 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    float n = 0.0;
    for (int k = 0; k < 8; ++k) {
        vec3 o = vec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
        vec3 w = mix(1.0 - u, u, o);
        n += w.x * w.y * w.z * dot(grad3(i + o), f - o);
    }
    return n;
}

float timePhase() {
    float t = post.misc.x / PARAM(0, PAINTBRUSH_PERIOD).x;
    return floor(t) + smoothstep(0.8, 1.0, fract(t)); // seed 004's "smoothStep"
}

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    if (POST_PASS == 0) {
        vec2 uv = gl_FragCoord.xy / uTexel.zw;
        vec3 q = vec3(uv * PARAM(0, PAINTBRUSH_NOISEFREQUENCY).x * vec2(post.viewport.x *
                      post.viewport.w, 1.0), timePhase());
        const float e = 0.01;
        float dx = gradientNoise(q + vec3(e, 0, 0)) - gradientNoise(q - vec3(e, 0, 0));
        float dy = gradientNoise(q + vec3(0, e, 0)) - gradientNoise(q - vec3(0, e, 0));
        vec2 curl = vec2(dy, -dx);
        outColor = vec4(normalize(curl + vec2(1e-6, 0.0)), 0.0, 1.0);
        return;
    }
    float cell = PARAM(0, PAINTBRUSH_BRUSHSCALE).x;
    vec2 p = gl_FragCoord.xy;
    ivec2 home = ivec2(floor(p / cell));
    ivec2 size = textureSize(uInput, 0) - 1;
    float roughness = PARAM(0, PAINTBRUSH_NOISEAMOUNT).x;
    float edgeNoise = hash13(vec3(floor(p / 2.0), 7.0)) - 0.5;
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i) {
            ivec2 c = home + ivec2(i, j);
            vec2 jitter = vec2(hash13(vec3(c, 3.0)), hash13(vec3(c, 5.0))) - 0.5;
            vec2 centre = (vec2(c) + 0.5 + jitter) * cell;
            vec2 dir = texture(uAux, centre * post.viewport.zw).xy;
            vec2 d = p - centre;
            vec2 local = vec2(dot(d, dir), dot(d, vec2(-dir.y, dir.x))) / (cell * vec2(1.4, 0.5));
            float dist = length(local) + roughness * edgeNoise;
            float w = smoothstep(1.0, 0.6, dist) * (1.0 + hash13(vec3(c, 11.0)));
            if (w > 0.0) {
                sum += w * texelFetch(uInput, clamp(ivec2(centre), ivec2(0), size), 0).rgb;
                weights += w;
            }
        }
    outColor = weights > 1e-4 ? vec4(sum / weights, 1.0) : texelFetch(uInput, px, 0);
}
