#pragma once
/// @file texture_set_export.h
/// Engine texture sets (issue 12, `velvet export -f texture-set --target …`): a material's baked
/// maps (render/material_bake.h) packed, named and encoded the way each engine reads them, and a
/// small JSON manifest naming each file's role. No GL: the maps come in as images, the files go
/// out as ExportFile bytes for writeExportFiles (sanitised names, refuse-unless-force, atomic).
/// docs/interchange.md, "Engine texture sets".

#include "core/export_files.h"
#include "core/image.h"

#include <optional>
#include <string>
#include <string_view>

namespace velvet {

/// The maps an engine material reads, per texel, before any packing or encoding.
struct MaterialMaps {
    Image baseColor; ///< RGBA: scene-linear base colour, alpha (1: opaque)
    Image normal;    ///< RGB: unit tangent-space normal, OpenGL convention (+Y up), in [-1, 1]
    Image orm;       ///< RGB: occlusion (strength applied), perceptual roughness, metallic
    Image emission;  ///< RGB: scene-linear emission (colour x strength), may exceed 1
    // The lobes (core/texture_set_lobes.h); empty: not baked (the set then has no lobe maps).
    Image coat;       ///< RG: clearcoat weight, clearcoat roughness
    Image sheen;      ///< RGBA: sheen weight x colour (scene-linear), sheen roughness
    Image specular;   ///< RGBA: specular colour (scene-linear), specular weight
    Image anisotropy; ///< RGB: unit tangent-space direction (rotation applied), strength
};

enum class TextureSetTarget { Unreal, UnityHdrp, Godot, Gltf, Count };
/// "unreal", "unity-hdrp", "godot", "gltf" (the CLI's --target values) and back.
std::string_view textureSetTargetId(TextureSetTarget target);
std::string_view textureSetTargetLabel(TextureSetTarget target);
std::optional<TextureSetTarget> textureSetTargetFromId(std::string_view id);

/// Tangent-space normal maps' green channel: OpenGL (+Y up: glTF, Godot, Unity, Blender) or
/// DirectX (+Y down: Unreal). DirectX = OpenGL with G replaced by 1 - G.
enum class NormalConvention { OpenGl, DirectX };
/// The convention @p target's normal-map importer expects by default.
NormalConvention defaultNormalConvention(TextureSetTarget target);
std::string_view normalConventionId(NormalConvention convention); ///< "opengl", "directx"

enum class TextureFileType { Png, Tga, Exr, Count };
std::string_view textureFileTypeId(TextureFileType type); ///< "png", "tga", "exr"
std::optional<TextureFileType> textureFileTypeFromId(std::string_view id);

struct TextureSetOptions {
    TextureSetTarget target = TextureSetTarget::Gltf;
    int size = 1024; ///< width = height of every map, 1..8192
    /// Bits per channel: PNG 8 or 16; TGA 8; EXR 16 (half) or 32 (float). 0: the type's default
    /// (8, 8, 16).
    int bits = 0;
    TextureFileType fileType = TextureFileType::Png;
    std::optional<NormalConvention> normal; ///< nullopt: the target's default
};

/// Empty when @p options are valid, else one line saying what is wrong (the bits a type holds,
/// the size range).
std::string checkTextureSetOptions(const TextureSetOptions& options);

/// One file of a set: its name, what it holds and how, as the manifest lists it.
struct TextureSetFile {
    std::string name;        ///< "T_Silk_ORM.png"
    std::string role;        ///< "baseColor", "normal", "occlusionRoughnessMetallic", "maskMap",
                             ///< "emissive", "clearcoat", "sheen", "specular", "anisotropy"
    std::string colorSpace;  ///< "srgb" (colour, sRGB-encoded) or "linear" (data, or colour in EXR)
    std::string channels[4]; ///< what R, G, B, A hold ("" for a channel the file does not have)
};

/// The plan of @p target's set for a material called @p base (already sanitised), with or without
/// an alpha channel and an emissive map: the files in the order they are written.
std::vector<TextureSetFile> planTextureSet(const TextureSetOptions& options, std::string_view base,
                                           bool hasAlpha, bool hasEmission);

/// Packs and encodes @p maps (all of one size) for @p options.target into @p out: one file per
/// map the engine reads and, last, BASE_texture_set.json (the manifest). Colour maps (base colour,
/// emissive) are sRGB-encoded in PNG and TGA and scene-linear in EXR; data maps are linear; normals
/// are n * 0.5 + 0.5 with G flipped for DirectX; base colour carries an alpha channel only when
/// some texel's alpha is below 1 (the manifest then says alphaMode "mask", cutoff 0.5, Velvet's
/// cut-out). Emission above 1 is scaled into [0, 1] in PNG and TGA, the factor written in the
/// manifest ("scale"). An emissive map is written only when some texel emits. Then the lobe maps
/// the target reads (core/texture_set_lobes.h: clearcoat, sheen, specular, anisotropy), each
/// only when the material has that lobe. @p materialName goes
/// into the manifest. False + @p error when the maps are missing or differ in size or an image
/// cannot be encoded.
bool buildTextureSet(const MaterialMaps& maps, std::string_view base, std::string_view materialName,
                     const TextureSetOptions& options, BuiltExport& out, std::string* error);

} // namespace velvet
