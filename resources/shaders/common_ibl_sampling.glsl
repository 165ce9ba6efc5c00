// Sampling helpers of the IBL bake (Karis 2013, "Real Shading in Unreal Engine 4"); mirrored by
// core/ibl.cpp line for line.
#include "common_math.glsl"

// Hammersley point i of n (radical inverse in base 2).
vec2 hammersley(uint i, uint n) {
    return vec2(float(i) / float(n), float(bitfieldReverse(i)) * 2.3283064365386963e-10);
}

// Karis 2013, ImportanceSampleGGX: a GGX half vector in tangent space (z = normal).
vec3 importanceSampleGgx(vec2 xi, float alpha) {
    float phi = 2.0 * PI * xi.y;
    float cosTheta = sqrt((1.0 - xi.x) / (1.0 + (alpha * alpha - 1.0) * xi.x));
    float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
    return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

// Direction of texel (x, y) of cube face `face` (OpenGL 4.5 spec, table 8.19: the inverse of the
// hardware's face selection, so that a lookup along the direction returns this texel).
vec3 cubeTexelDirection(ivec2 texel, int face, int size) {
    vec2 st = (vec2(texel) + 0.5) / float(size) * 2.0 - 1.0;
    vec3 d;
    if (face == 0)
        d = vec3(1.0, -st.y, -st.x);
    else if (face == 1)
        d = vec3(-1.0, -st.y, st.x);
    else if (face == 2)
        d = vec3(st.x, 1.0, st.y);
    else if (face == 3)
        d = vec3(st.x, -1.0, -st.y);
    else if (face == 4)
        d = vec3(st.x, -st.y, 1.0);
    else
        d = vec3(-st.x, -st.y, -1.0);
    return normalize(d);
}
