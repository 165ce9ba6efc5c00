#pragma once
/// @file texture_ref.h
/// Texture slots of a material and what fills them: an image file, or a rectangular region of an
/// atlas image (the seed documents store each element's offset in a shared atlas; their material
/// atlas packs RGB = specular, roughness, metallic).

#include <span>
#include <string>
#include <string_view>

namespace velvet {

enum class TextureSlot : int {
    BaseColor,          ///< RGB colour, A alpha (sRGB texture)
    MetallicRoughness,  ///< glTF packing: G roughness, B metallic (raw)
    SpecRoughMetal,     ///< seed-document material atlas: R specular, G roughness, B metallic (raw)
    Normal,             ///< tangent-space normal map (raw)
    Occlusion,          ///< R ambient occlusion (raw)
    Emissive,           ///< RGB emission (sRGB texture)
    Clearcoat,          ///< R clearcoat weight (raw)
    ClearcoatRoughness, ///< G clearcoat roughness (raw)
    ClearcoatNormal,    ///< clearcoat normal map (raw)
    SheenColor,         ///< RGB sheen colour (sRGB texture)
    SheenRoughness,     ///< A sheen roughness (raw)
    Specular,           ///< A specular weight (raw)
    SpecularColor,      ///< RGB specular colour (sRGB texture)
    Count
};
inline constexpr int kTextureSlotCount = static_cast<int>(TextureSlot::Count);

/// Metadata of a texture slot.
struct TextureSlotMeta {
    std::string_view id;    ///< JSON key under "textures", e.g. "baseColor"
    std::string_view label; ///< e.g. "Base colour"
    bool isColor;           ///< colour data (defaults to the sRGB texture space) or raw data
    std::string_view tooltip;
};
std::span<const TextureSlotMeta> textureSlotMetas();
const TextureSlotMeta& textureSlotMeta(TextureSlot slot);

/// A rectangle in pixels inside an atlas image.
struct AtlasRegion {
    int x = 0, y = 0, width = 0, height = 0;
    bool operator==(const AtlasRegion&) const = default;
};

/// What fills a texture slot. Empty file: the slot is unused and the parameter value applies.
struct TextureRef {
    std::string file;       ///< image path (absolute, or relative to the document that names it)
    bool useRegion = false; ///< true: only `region` of `file` (an atlas) is used
    AtlasRegion region;
    std::string colorSpace; ///< input colour space name; empty: the slot's default
    bool empty() const { return file.empty(); }
    bool operator==(const TextureRef&) const = default;
};

} // namespace velvet
