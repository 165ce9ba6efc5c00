#version 450 core
#define GBUFFER_WRITE
#include "common_frame.glsl"
#include "common_gbuffer.glsl"
#include "common_material.glsl"

in vec3 vNormal;
in vec4 vTangent;
in vec2 vUv;

layout(location = 0) uniform int uMaterialId;

void main() {
    GpuMaterial m = materials[uMaterialId];
    vec3 n = normalize(vNormal);
    if (!gl_FrontFacing)
        n = -n;
    // Textures (base colour, normal, occlusion, ...) arrive with the renderer issue; the
    // occlusion channel already holds 1 - strength * (1 - ao).
    float occlusion = 1.0;
    gBaseColorOcclusion = vec4(encodeBaseColor(m.baseColorMetallic.rgb), occlusion);
    gNormal = octEncodeUnorm16(n);
    gMaterial = vec4(m.baseColorMetallic.a, m.roughIorOcclusionNormal.x,
                     float(uMaterialId) / 255.0, 0.0);
}
