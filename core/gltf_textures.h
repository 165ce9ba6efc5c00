#pragma once
/// @file gltf_textures.h
/// Which images a glTF export of a material holds and which texture slot reads which image
/// (internal to core/gltf_export.cpp; its own header so tests can check the plan channel by
/// channel without parsing a file). docs/interchange.md, "Textures".

#include "core/image.h"
#include "core/material.h"

#include <array>
#include <glm/vec2.hpp>
#include <optional>
#include <string>
#include <vector>

namespace velvet {

class TextureCache;

/// One image of the export, already encoded the way glTF reads it: colour images sRGB-encoded
/// (glTF 2.0 section 3.9.2: baseColorTexture, emissiveTexture and the KHR colour textures hold
/// sRGB-encoded values), data images as stored.
struct GltfImage {
    std::string label; ///< file-name suffix and glTF image name: "baseColor", "orm", …
    Image pixels;      ///< values in [0, 1] as they go into the 8-bit PNG
};

/// How one glTF texture slot reads an image: which image, and the KHR_texture_transform that
/// maps the mesh's UVs: the slot's UV transform (texture_ref.h) or, for an atlas region with no
/// UV transform, the one that maps [0, 1] onto the region (a region with a UV transform is cut
/// out: glTF's sampler would tile the whole atlas where Velvet tiles the region).
struct GltfTextureUse {
    int image = -1;
    bool transformed = false;
    glm::vec2 offset{0.0f}; ///< region origin / atlas size (UV space: v = 0 at the top row)
    glm::vec2 scale{1.0f};  ///< region size / atlas size
    float rotation = 0.0f;  ///< radians, KHR_texture_transform's sense (the slot's UV transform)
};

/// The textures of an export, indexed by TextureSlot. SpecRoughMetal never has a use of its
/// own: its G and B go into the metallic-roughness image and its R into the specular one.
struct GltfTexturePlan {
    std::vector<GltfImage> images;
    std::array<std::optional<GltfTextureUse>, kTextureSlotCount> uses{};
    /// Base colour alpha below 1 somewhere: Velvet cuts out below 0.5, glTF's alphaMode MASK
    /// with its default alphaCutoff 0.5.
    bool alphaCutout = false;
    std::vector<std::string> warnings; ///< lossy steps (resampling, clamping), one line each
};

/// Loads every texture slot of @p material through @p textures and plans the images:
/// - slots glTF reads as they are (base colour, normal, emissive, clearcoat, clearcoat
///   roughness and normal, sheen colour and roughness, specular, specular colour, anisotropy, and
///   metallic-roughness or occlusion alone) keep their image, one image per distinct file and
///   colour handling, an atlas region becoming a KHR_texture_transform;
/// - occlusion together with metallic-roughness, or any SpecRoughMetal texture, are packed
///   (core/channel_packing.h, PackLayout::GltfMetallicRoughness) into one "orm" image: R
///   occlusion, G roughness, B metallic (the products where two slots feed one value, as the
///   renderer multiplies them), plus A = specular (SpecRoughMetal's R times the specular slot's
///   A) read by KHR_materials_specular's specularTexture. Regions are cut out first; maps of
///   different sizes are resampled to the largest (a warning says so).
/// With @p cutOutRegions every region is cut out into an image of its own instead (MaterialX:
/// its image node's UV offset counts from the bottom row, Velvet's regions from the top).
/// False + @p error (naming the slot and file) when a texture cannot be read or a region lies
/// outside its image.
bool planGltfTextures(const Material& material, TextureCache& textures, GltfTexturePlan& plan,
                      std::string* error, bool cutOutRegions = false);

} // namespace velvet
