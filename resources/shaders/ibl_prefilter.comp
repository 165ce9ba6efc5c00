#version 450 core
// Karis 2013, "Real Shading in Unreal Engine 4": radiance convolved with the GGX lobe of one
// roughness (n = v = r), importance sampled, weighted by n.l; the source mip of each sample is
// chosen from its PDF (Colbert & Krivanek 2007, "GPU-Based Importance Sampling", GPU Gems 3
// ch. 20) so that few samples give no fireflies. Writes rows uRowOffset.. of one face of one
// level. Mirrored by core/ibl.cpp (sourceLod).
#include "common_ibl_sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform samplerCube uRadiance;
layout(binding = 0, rgba16f) uniform writeonly imageCube uTarget;
layout(location = 0) uniform int uFace;
layout(location = 1) uniform int uSize;       // target level size
layout(location = 2) uniform int uRowOffset;
layout(location = 3) uniform float uRoughness; // perceptual
layout(location = 4) uniform int uSamples;
layout(location = 5) uniform int uSourceSize; // radiance level 0 size

float distributionGgx(float NdotH, float alpha) {
    float a2 = alpha * alpha;
    float f = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return a2 / (PI * f * f);
}

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, uRowOffset);
    if (texel.x >= uSize || texel.y >= uSize)
        return;
    vec3 n = cubeTexelDirection(texel, uFace, uSize);
    vec3 up = abs(n.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 tx = normalize(cross(up, n));
    vec3 ty = cross(n, tx);
    float alpha = max(uRoughness * uRoughness, 1e-4);
    float omegaP = 4.0 * PI / (6.0 * float(uSourceSize * uSourceSize));
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int i = 0; i < uSamples; ++i) {
        vec3 hT = importanceSampleGgx(hammersley(uint(i), uint(uSamples)), alpha);
        vec3 h = tx * hT.x + ty * hT.y + n * hT.z;
        vec3 l = 2.0 * dot(n, h) * h - n;
        float NdotL = dot(n, l);
        if (NdotL <= 0.0)
            continue;
        // pdf(l) = D (n.h) / (4 v.h) = D / 4 with n = v.
        float pdf = distributionGgx(hT.z, alpha) * 0.25;
        float omegaS = 1.0 / (float(uSamples) * pdf + 1e-8);
        float lod = max(0.5 * log2(omegaS / omegaP) + 1.0, 0.0);
        sum += textureLod(uRadiance, l, lod).rgb * NdotL;
        weight += NdotL;
    }
    imageStore(uTarget, ivec3(texel, uFace), vec4(sum / max(weight, 1e-6), 1.0));
}
