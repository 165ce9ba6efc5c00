#version 450 core
// The ground into the G-buffer: facing up, the plain ground's record of the material table
// (colour, roughness; render/ground_pass.cpp), no emission. The shadow catcher writes the same
// with its own id, which lighting.frag shows as the darkened background.
#define GBUFFER_WRITE
#include "common_frame.glsl"
#include "common_gbuffer.glsl"
#include "common_material.glsl"

layout(location = 0) uniform int uMaterialId;

void main() {
    GpuMaterial m = materials[uMaterialId];
    gBaseColorOcclusion = vec4(encodeBaseColor(m.baseColorMetallic.rgb), 1.0);
    gNormal = octEncodeUnorm16(vec3(0.0, 1.0, 0.0));
    gMaterial = vec4(0.0, clamp(m.roughIorOcclusionNormal.x, 0.0, 1.0), float(uMaterialId) / 255.0,
                     1.0); // a: specular occlusion (none)
    gLobes0 = gLobes1 = vec4(0.0); // its lobe-channel map keeps every lobe per material
    gEmission = vec4(0.0, 0.0, 0.0, 1.0);
}
