#pragma once
/// @file material_table.h
/// Render-private: the GPU material table (an SSBO indexed by the material id in the G-buffer).
/// A value edit rewrites the table; it never touches a shader.

#include "core/material.h"
#include "render/lobe_channels.h"

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <string>
#include <vector>

namespace velvet::render {

/// One material as the shaders read it; generated into GLSL by render/render_interface.cpp (std430,
/// vec4 members only, so C++ and GLSL agree on every offset).
struct GpuMaterial {
    glm::vec4 baseColorMetallic;
    glm::vec4 specularColorWeight;
    glm::vec4 roughIorOcclusionNormal;
    glm::vec4 emissive;
    glm::vec4 sheenColorRoughness;
    glm::vec4 clearcoat;
    /// Sheen weight, anisotropy strength and rotation (radians), and 1 when the shading normal
    /// varies per pixel (perturbsNormal(), render/lobe_channels.h; packMaterialRecord), else 0.
    glm::vec4 sheenWeightAnisotropy;
    glm::ivec4 terms;
    glm::ivec4 terms2;
    /// The base colour as the G-buffer holds it and the lighting reads it back: 8-bit sRGB,
    /// decoded (storedBaseColor()); w unused. A record of kRecordValuesPerMaterial is read from
    /// here in place of the G-buffer, without the sRGB curves' powers per pixel.
    glm::vec4 storedBaseColor;
};
static_assert(sizeof(GpuMaterial) == 160, "GpuMaterial must match the std430 layout");

/// @p linear as the G-buffer stores a base colour (gbuffer.frag's encodeBaseColor into an 8-bit
/// unorm target, OpenGL 4.5 section 2.3.5.1's round(clamp(v) x 255)) and gbuffer_read.glsl
/// decodes it: the CPU twin of decodeBaseColor(unorm8(encodeBaseColor(linear))).
glm::vec3 storedBaseColor(glm::vec3 linear);

/// A bit of GpuMaterial::terms2.y (beside the texture presence bits, one per slot): the record's
/// base colour, metallic and roughness are the same at every pixel (no texture at all, no graph
/// writes them), so the lighting passes read them from the table, quantised as the G-buffer
/// holds them (gbuffer_read.glsl), and a value edit need not draw the G-buffer again
/// (Renderer::Impl::keepsGBuffer, render/frame_reuse.h).
inline constexpr int kRecordValuesPerMaterial = 1 << 30;

/// The IOR's lobe-channel entry of @p g (LobeChannelMap::iorEntry(), kept in clearcoat.w): its
/// channel, or kLobePerMaterial.
inline int iorLobeEntry(const GpuMaterial& g) {
    return int(g.clearcoat.w);
}

/// Whether @p g varies some lobe value per pixel (its lobe-channel map, terms2.w and the IOR's
/// entry, is not all "per material"): the geometry pass then writes the lobe targets and the
/// lighting passes read them.
inline bool hasLobeMap(const GpuMaterial& g) {
    return g.terms2.w != -1 || iorLobeEntry(g) != kLobePerMaterial;
}

/// The parameters alone (no texture presence, every lobe per material).
GpuMaterial packMaterial(const Material& m);

class TextureSet;

/// The record a frame draws with: packMaterial(), the lobe-channel map (terms2.w) of the values
/// @p m varies per pixel given the slots @p textures holds and the MaterialInputs fields
/// @p graphFields the drawn graph writes, and the texture presence bits with the means of the
/// slots that stay per material (TextureSet::applyTo). @p compactGBuffer: the 16-byte layout,
/// every lobe per material. @p overflow (optional) receives the values that varied but found no
/// channel (render/lobe_channels.h).
GpuMaterial packMaterialRecord(const Material& m, const TextureSet& textures,
                               const std::vector<std::string>& graphFields, bool compactGBuffer,
                               std::uint32_t* overflow = nullptr);

class MaterialTable {
public:
    MaterialTable() = default;
    ~MaterialTable();
    MaterialTable(const MaterialTable&) = delete;
    MaterialTable& operator=(const MaterialTable&) = delete;

    /// Uploads @p materials (id = index); grows the buffer when needed.
    void upload(const std::vector<GpuMaterial>& materials);
    /// Binds the table to BINDING_MATERIAL_SSBO.
    void bind() const;

private:
    unsigned m_buffer = 0;
    size_t m_capacity = 0;
};

} // namespace velvet::render
