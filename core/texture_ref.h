#pragma once
/// @file texture_ref.h
/// Texture slots of a material and what fills them: an image file, or a rectangular region of an
/// atlas image (the seed documents store each element's offset in a shared atlas; their material
/// atlas packs RGB = specular, roughness, metallic).

#include <glm/vec2.hpp>
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
    Anisotropy, ///< KHR_materials_anisotropy: RG direction in tangent space ([0, 1] -> [-1, 1]),
                ///< B strength multiplier (raw)
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

/// How a slot's texture coordinates are transformed before sampling: uv' = R(rotation) (scale *
/// uv) + offset, R rotating counter-clockwise in UV space (u right, v down the image), the order
/// and sense of the Image texture node (Blender's Mapping node, type Point). It maps exactly to
/// KHR_texture_transform (same scale and offset; rotation = -radians(rotation), since glTF's
/// rotation matrix is the transpose): docs/interchange.md.
struct UvTransform {
    glm::vec2 scale{1.0f};  ///< tiling: 2 repeats the texture twice across the UV square
    glm::vec2 offset{0.0f}; ///< added after scale and rotation, in UV units
    float rotation = 0.0f;  ///< degrees
    bool isIdentity() const {
        return scale == glm::vec2(1.0f) && offset == glm::vec2(0.0f) && rotation == 0.0f;
    }
    bool operator==(const UvTransform&) const = default;
};

/// The UV transform's limits (hard ranges of the JSON reader and the Properties editors).
inline constexpr float kUvScaleLimit = 1000.0f;  ///< |scale| at most this, and not 0
inline constexpr float kUvOffsetLimit = 1000.0f; ///< |offset| at most this
inline constexpr float kUvRotationLimit = 360.0f;

/// What fills a texture slot. Empty file: the slot is unused and the parameter value applies.
struct TextureRef {
    std::string file;       ///< image path (absolute, or relative to the document that names it)
    bool useRegion = false; ///< true: only `region` of `file` (an atlas) is used
    AtlasRegion region;
    std::string colorSpace; ///< input colour space name; empty: the slot's default
    UvTransform uv;         ///< applied to the mesh's UVs before the region (if any) is looked up
    bool empty() const { return file.empty(); }
    bool operator==(const TextureRef&) const = default;
};

} // namespace velvet
