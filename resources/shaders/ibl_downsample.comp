#version 450 core
// One level of the radiance cube's mip chain from the level above: a 2x2 box filter per face
// (what glGenerateMipmap does, but in rows, so the bake's slices stay short on llvmpipe).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba16f) uniform readonly imageCube uSource;
layout(binding = 1, rgba16f) uniform writeonly imageCube uTarget;
layout(location = 0) uniform int uFace;
layout(location = 1) uniform int uSize; // target level size
layout(location = 2) uniform int uRowOffset;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, uRowOffset);
    if (texel.x >= uSize || texel.y >= uSize)
        return;
    ivec2 s = texel * 2;
    vec4 c = imageLoad(uSource, ivec3(s, uFace)) + imageLoad(uSource, ivec3(s + ivec2(1, 0), uFace)) +
             imageLoad(uSource, ivec3(s + ivec2(0, 1), uFace)) +
             imageLoad(uSource, ivec3(s + ivec2(1, 1), uFace));
    imageStore(uTarget, ivec3(texel, uFace), c * 0.25);
}
