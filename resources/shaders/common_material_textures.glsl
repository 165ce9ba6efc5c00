// Material texture slots, sampled in the G-buffer pass (render/texture_set.h). Unit
// BINDING_MATERIAL_TEX_FIRST + slot; the material record says which slots hold a texture
// (terms2.y) and which use an atlas region (terms2.z); uTexRegion holds each region as
// xy = size / atlas size, zw = offset / atlas size (per draw, like the texture bindings).
// Slot numbers (TEX_BASE_COLOR .. TEX_SLOT_COUNT) and the uniform locations below are generated
// from core/texture_ref.h's TextureSlot into render_bindings.glsl (render/shader_program.cpp).
#include "render_bindings.glsl"

layout(binding = BINDING_MATERIAL_TEX_FIRST) uniform sampler2D uMaterialTex[TEX_SLOT_COUNT];
layout(location = 1) uniform vec4 uTexRegion[TEX_SLOT_COUNT];
// Each slot's UV transform (core/texture_ref.h UvTransform: scale, rotate, offset) as a 2x2
// matrix (columns xy, zw) and an offset; identity when unset (render/texture_set.cpp). Their
// locations follow uTexRegion's.
layout(location = TEX_UV_LINEAR_LOCATION) uniform vec4 uTexUvLinear[TEX_SLOT_COUNT];
layout(location = TEX_UV_OFFSET_LOCATION) uniform vec2 uTexUvOffset[TEX_SLOT_COUNT];

// FIXED_TEXTURE_SLOTS / FIXED_ATLAS_SLOTS (render/material_graph_program.h, GeometryFeatures):
// the G-buffer program specialised to the material's slots, the record's bits compiled in.
bool hasTexture(GpuMaterial m, int slot) {
#ifdef FIXED_TEXTURE_SLOTS
    return (FIXED_TEXTURE_SLOTS & (1 << slot)) != 0;
#else
    return (m.terms2.y & (1 << slot)) != 0;
#endif
}
bool usesAtlasRegion(GpuMaterial m, int slot) {
#ifdef FIXED_ATLAS_SLOTS
    return (FIXED_ATLAS_SLOTS & (1 << slot)) != 0;
#else
    return (m.terms2.z & (1 << slot)) != 0;
#endif
}

// The slot's texel at uv. In an atlas region the seeds added the element's offset in the vertex
// shader; here it happens per fragment so that tiling UVs wrap inside the region (fract) and the
// lookup stays half a texel inside it (no bleeding from neighbours under bilinear filtering). The
// gradients are those of the unwrapped uv, so the wrap does not pick a coarse mip at the seam.
// The slot's UV transform comes first (KHR_texture_transform's place: on the mesh's UVs, before
// the lookup), so a tiled region repeats the region.
vec4 sampleSlot(GpuMaterial m, int slot, vec2 uv) {
    vec4 l = uTexUvLinear[slot];
    uv = mat2(l.xy, l.zw) * uv + uTexUvOffset[slot];
    if (!usesAtlasRegion(m, slot))
        return texture(uMaterialTex[slot], uv);
    vec4 r = uTexRegion[slot];
    vec2 inset = 0.5 / vec2(textureSize(uMaterialTex[slot], 0));
    vec2 p = clamp(fract(uv) * r.xy + r.zw, r.zw + inset, r.zw + r.xy - inset);
    return textureGrad(uMaterialTex[slot], p, dFdx(uv) * r.xy, dFdy(uv) * r.xy);
}
