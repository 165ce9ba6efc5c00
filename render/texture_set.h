#pragma once
/// @file texture_set.h
/// Render-private: the GL textures of a material's slots, loaded through core's TextureCache
/// (once per file and input colour space, to scene-linear float) and re-uploaded when the cache
/// reloads a file changed on disk. No shader ever changes: the G-buffer program samples unit
/// binding::kMaterialTexFirst + slot when the material record's presence bit says so
/// (GpuMaterial::terms2.y; atlas-region bits in terms2.z; regions in a per-draw uniform).
///
/// What reaches the pixels: base colour (and alpha, a 0.5 cut-out), metallic-roughness, the
/// seeds' spec/rough/metal atlas (roughness and metallic), normal map and occlusion go through the
/// 16-byte G-buffer per pixel. The slots the G-buffer has no room for (emissive, clearcoat,
/// clearcoat roughness, sheen colour / roughness, specular, specular colour and the spec channel
/// of the atlas) enter the material table as their texture's mean, multiplied with the parameter:
/// DESIGN.md's G-buffer contract puts per-material data that does not fit there. The clearcoat
/// normal map (mean: flat) is not applied.

#include "core/diagnostics.h"
#include "core/image.h"
#include "core/material.h"
#include "core/texture_ref.h"

#include <array>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <memory>

namespace velvet {
class ColorManagement;
class TextureCache;
} // namespace velvet

namespace velvet::render {

struct GpuMaterial;

/// Uploads @p image (1 to 4 channels, RRR for grey, alpha 1 when absent) into every level of
/// @p texture, an RGBA16F 2D texture with the full mip chain allocated
/// (mipLevelCount(width, height) levels): the levels of core::mipChain, filtered on the CPU
/// through OpenImageIO (Blackman-Harris, the same filter for every platform and driver) rather
/// than glGenerateTextureMipmap's unspecified box filter. Row 0 goes to t = 0. Material slot and
/// graph textures use it; needs a current context.
void uploadMipChain(unsigned texture, const Image& image);

/// True when the geometry pass reads slot @p slot per pixel (base colour, metallic / roughness,
/// the material atlas's roughness and metallic, normal, occlusion, and emissive, which it writes
/// straight into the HDR target). The other slots (clearcoat, sheen, specular) have no room in
/// the 16-byte G-buffer: their image's mean, times the parameter, goes to the material table
/// (docs/architecture.md, "G-buffer").
bool slotIsPerPixel(TextureSlot slot);

/// A slot's UV transform (core/texture_ref.h) as the shader applies it: uv' = mat2(linear.xy,
/// linear.zw) * uv + offset (columns), uniforms uTexUvLinear and uTexUvOffset of
/// common_material_textures.glsl.
struct UvTransformMatrix {
    glm::vec4 linear{1.0f, 0.0f, 0.0f, 1.0f};
    glm::vec2 offset{0.0f};
};
UvTransformMatrix uvTransformMatrix(const UvTransform& uv);

class TextureSet {
public:
    TextureSet();
    /// Needs the renderer's context current (frees GL textures).
    ~TextureSet();
    TextureSet(const TextureSet&) = delete;
    TextureSet& operator=(const TextureSet&) = delete;

    /// The OCIO config input colour spaces come from (null: ColorManagement's default config,
    /// loaded when a first texture needs it). Drops the cache: names may mean other spaces.
    void setColorManagement(std::shared_ptr<const ColorManagement> colorManagement);

    /// Takes @p material's texture slots: loads (cached) and uploads what changed, releases
    /// emptied slots. A missing or broken file is reported to @p problems and its slot falls back
    /// to the parameter value. Needs a current context.
    void setMaterial(const Material& material, Problems* problems);

    /// Stats the files in use (TextureCache::poll, one stat per file) and re-uploads the slots
    /// whose file changed. True when anything changed (re-pack the material then). Every frame.
    bool poll();

    /// Writes presence and region bits and the texture means into @p g (packMaterial's output).
    void applyTo(GpuMaterial& g) const;
    /// Binds the slot textures and sets @p program's region and UV-transform uniforms (location 1
    /// onwards: uTexRegion, uTexUvLinear, uTexUvOffset, kTextureSlotCount each).
    void bind(unsigned program) const;
    /// Unbinds the slot units.
    void unbind() const;

    /// GL texture (re)allocations since construction (tests: a changed file of the same size
    /// re-uploads without reallocating).
    int allocationCount() const { return m_allocations; }
    /// The GL texture name of @p slot (0 when the slot is empty or its file failed; tests read
    /// its levels back).
    unsigned texture(TextureSlot slot) const;
    /// The texture cache behind the slots (created on first use; needs a current context), shared
    /// with the material graph's texture nodes so a file is decoded once for both.
    TextureCache& sharedCache() { return cache(); }

private:
    struct Slot;
    void refresh(int slot, Problems* problems);
    TextureCache& cache();

    std::shared_ptr<const ColorManagement> m_colorManagement;
    std::unique_ptr<TextureCache> m_cache;
    std::unique_ptr<std::array<Slot, kTextureSlotCount>> m_slots;
    int m_allocations = 0;
};

} // namespace velvet::render
