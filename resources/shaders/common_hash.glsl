// The GPU hashes, one copy each for every shader and for the material graph's generated code
// (core/graph/graph_compiler.cpp emits #include "common_hash.glsl"). Both give the same bits on
// every GPU, so a fixed input (a time, a seed) gives a fixed image.

// Jarzynski & Olano 2020, "Hash Functions for GPU Rendering", JCGT 9(3), 21-38 (pcg2d): an
// integer hash of two 32-bit words to two.
uvec2 pcg2d(uvec2 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v = v ^ (v >> 16u);
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v = v ^ (v >> 16u);
    return v;
}

// Hoskins 2014, "Hash without Sine" (hash13): stable white noise in [0, 1) from a float triple.
float hash13(vec3 p3) {
    p3 = fract(p3 * 0.1031);
    p3 += dot(p3, p3.zyx + 31.32);
    return fract((p3.x + p3.y) * p3.z);
}

// Jimenez 2014, "Next Generation Post Processing in Call of Duty: Advanced Warfare": a per-pixel
// value in [0, 1) whose neighbours differ evenly (the shadow taps' rotation, shadow_sampling.glsl).
float interleavedGradientNoise(vec2 pixel) {
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}
