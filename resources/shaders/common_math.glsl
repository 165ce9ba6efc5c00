// Small helpers shared by every pass.
#define PI 3.14159265358979

float saturate(float x) { return clamp(x, 0.0, 1.0); }
float max3(vec3 v) { return max(v.x, max(v.y, v.z)); }

// The bilinear weights of the four texels textureGather returns, in its order (0,1), (1,1),
// (1,0), (0,0) from the block's first texel, for the fraction @p f of the way to the last
// (the shadow mask's and the occlusion's depth-aware upsamples).
vec4 gatherBilinearWeights(vec2 f) {
    return vec4((1.0 - f.x) * f.y, f.x * f.y, f.x * (1.0 - f.y), (1.0 - f.x) * (1.0 - f.y));
}

// IEC 61966-2-1 sRGB transfer functions (the OETF and its inverse).
vec3 srgbEncode(vec3 c) {
    c = max(c, vec3(0.0));
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
vec3 srgbDecode(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}
