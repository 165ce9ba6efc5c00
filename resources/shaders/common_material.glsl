// The material table, indexed by the material id stored in the G-buffer; mirrors struct
// GpuMaterial in render/material_table.h (std430, vec4 only).
#include "render_bindings.glsl"

struct GpuMaterial {
    vec4 baseColorMetallic;      // rgb base colour (linear), a metallic
    vec4 specularColorWeight;    // rgb specular colour, a specular weight
    vec4 roughIorOcclusionNormal;// roughness, IOR, occlusion strength, normal scale
    vec4 emissive;               // rgb colour, a strength (nits); drawn per pixel by gbuffer.frag
    vec4 sheenColorRoughness;    // rgb sheen weight x colour, a sheen roughness
    vec4 clearcoat;              // weight, roughness, normal scale, unused
    ivec4 terms;                 // distribution, visibility, fresnel, diffuse
    ivec4 terms2;                // sheen model, texture-slot presence bits, atlas-region bits
                                 // (render/texture_set.h), unused
};

layout(std430, binding = BINDING_MATERIAL_SSBO) readonly buffer MaterialTable {
    GpuMaterial materials[];
};
