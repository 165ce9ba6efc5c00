#version 450 core
// The environment's irradiance over pi, E(n) / pi, into one face of a small cube
// (render/irradiance_map.h): the cosine-weighted sum over a uGrid of directions of the equirect's
// mip uSourceLevel, read at their texels' centres (each texel's mean radiance over its solid angle
// (2 pi / W)(pi / H) sin(theta), so a lamp keeps its energy), divided by the same sum of the
// weights alone, so a uniform environment gives its radiance exactly. The grid is the mip's own
// texels, or 64 x 32 bilinear samples of a smaller source (a uniform environment's one texel).
// In the environment's own frame (before its rotation and intensity, which the lookup applies).
#include "common_ibl_sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uSource;
layout(binding = 0, rgba16f) uniform writeonly imageCube uTarget;
layout(location = 0) uniform int uFace;
layout(location = 1) uniform int uSize;
layout(location = 2) uniform int uSourceLevel;
layout(location = 3) uniform ivec2 uGrid;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (texel.x >= uSize || texel.y >= uSize)
        return;
    vec3 n = normalize(cubeTexelDirection(texel, uFace, uSize));
    ivec2 size = uGrid;
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int y = 0; y < size.y; ++y) {
        float theta = PI * (float(y) + 0.5) / float(size.y);
        float sinTheta = sin(theta), cosTheta = cos(theta);
        for (int x = 0; x < size.x; ++x) {
            // The inverse of equirectUv (common_environment.glsl): u = 0.5 at -Z.
            float phi = 2.0 * PI * ((float(x) + 0.5) / float(size.x) - 0.5);
            vec3 l = vec3(sin(phi) * sinTheta, cosTheta, -cos(phi) * sinTheta);
            float w = max(dot(n, l), 0.0) * sinTheta;
            vec2 uv = (vec2(x, y) + 0.5) / vec2(size);
            sum += w * textureLod(uSource, uv, float(uSourceLevel)).rgb;
            weights += w;
        }
    }
    imageStore(uTarget, ivec3(texel, uFace), vec4(sum / max(weights, 1e-8), 1.0));
}
