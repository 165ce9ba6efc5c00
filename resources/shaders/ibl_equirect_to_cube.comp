#version 450 core
// Equirectangular radiance -> one face (rows uRowOffset..) of cube level 0. The source is
// mip-mapped; the lod matches the cube texel's footprint so a large HDRI does not alias.
#include "common_ibl_sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uSource;
layout(binding = 0, rgba16f) uniform writeonly imageCube uTarget;
layout(location = 0) uniform int uFace;
layout(location = 1) uniform int uSize;
layout(location = 2) uniform int uRowOffset;
layout(location = 3) uniform float uSourceLod;

// Must match equirectUv() in common_environment.glsl.
vec2 equirectUvOf(vec3 d) {
    return vec2(0.5 + atan(d.x, -d.z) / (2.0 * PI), acos(clamp(d.y, -1.0, 1.0)) / PI);
}

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, uRowOffset);
    if (texel.x >= uSize || texel.y >= uSize)
        return;
    vec3 d = cubeTexelDirection(texel, uFace, uSize);
    vec3 c = textureLod(uSource, equirectUvOf(d), uSourceLod).rgb;
    imageStore(uTarget, ivec3(texel, uFace), vec4(c, 1.0));
}
