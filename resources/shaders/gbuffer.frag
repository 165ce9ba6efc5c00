#version 450 core
#define GBUFFER_WRITE
#include "common_frame.glsl"
#include "common_gbuffer.glsl"
#include "common_material.glsl"
#include "common_material_textures.glsl"

in vec3 vNormal;
in vec4 vTangent;
in vec2 vUv;

layout(location = 0) uniform int uMaterialId;

void main() {
    GpuMaterial m = materials[uMaterialId];
    vec3 baseColor = m.baseColorMetallic.rgb;
    float metallic = m.baseColorMetallic.a;
    float roughness = m.roughIorOcclusionNormal.x;
    vec3 n = normalize(vNormal);
    // Texture x parameter, as glTF 2.0 multiplies textures with their factors. Slots the
    // G-buffer has no room for enter the material table as means (render/texture_set.h).
    if (hasTexture(m, TEX_BASE_COLOR)) {
        vec4 t = sampleSlot(m, TEX_BASE_COLOR, vUv);
        if (t.a < 0.5) // alpha as a cut-out (glTF's MASK with the default cutoff)
            discard;
        baseColor *= t.rgb;
    }
    if (hasTexture(m, TEX_METALLIC_ROUGHNESS)) { // glTF: G roughness, B metallic
        vec4 t = sampleSlot(m, TEX_METALLIC_ROUGHNESS, vUv);
        roughness *= t.g;
        metallic *= t.b;
    }
    if (hasTexture(m, TEX_SPEC_ROUGH_METAL)) { // the seeds' atlas: R specular, G rough, B metal
        vec4 t = sampleSlot(m, TEX_SPEC_ROUGH_METAL, vUv);
        roughness *= t.g;
        metallic *= t.b;
    }
    if (hasTexture(m, TEX_NORMAL)) {
        // Tangent-space normal map (glTF: scaled normal = normalize((t * 2 - 1) * (s, s, 1))),
        // frame from the interpolated tangent re-orthogonalised against n (Gram-Schmidt).
        vec3 tn = sampleSlot(m, TEX_NORMAL, vUv).xyz * 2.0 - 1.0;
        tn.xy *= m.roughIorOcclusionNormal.w;
        vec3 t = vTangent.xyz - n * dot(n, vTangent.xyz);
        if (dot(t, t) > 1e-12) {
            t = normalize(t);
            vec3 b = cross(n, t) * (vTangent.w < 0.0 ? -1.0 : 1.0);
            n = normalize(mat3(t, b, n) * tn);
        }
    }
    if (!gl_FrontFacing)
        n = -n;
    // The occlusion channel holds 1 - strength * (1 - ao).
    float occlusion = 1.0;
    if (hasTexture(m, TEX_OCCLUSION))
        occlusion = 1.0 + m.roughIorOcclusionNormal.z * (sampleSlot(m, TEX_OCCLUSION, vUv).r - 1.0);
    gBaseColorOcclusion = vec4(encodeBaseColor(baseColor), occlusion);
    gNormal = octEncodeUnorm16(n);
    gMaterial = vec4(metallic, clamp(roughness, 0.0, 1.0), float(uMaterialId) / 255.0, 0.0);
}
