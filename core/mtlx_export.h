#pragma once
/// @file mtlx_export.h
/// A material as a MaterialX 1.39 document: one shader node (Autodesk standard_surface,
/// open_pbr_surface or gltf_pbr) in a surfacematerial, its textures as `image` nodes reading PNG
/// files beside the .mtlx (relative paths, colour images tagged srgb_texture), packed channels
/// picked with `extract`, texture x factor with `multiply` (as glTF and Velvet combine them),
/// normal maps through `normalmap`. Every mapping is tabled in docs/interchange.md.

#include "core/baked_maps.h"
#include "core/export_files.h"
#include "core/material.h"

#include <optional>
#include <string_view>

namespace velvet {

class TextureCache;

enum class MtlxShader { StandardSurface, OpenPbrSurface, GltfPbr, Count };

/// The MaterialX node names, which are also the CLI's --shader values: "standard_surface",
/// "open_pbr_surface", "gltf_pbr".
std::string_view mtlxShaderId(MtlxShader shader);
std::optional<MtlxShader> mtlxShaderFromId(std::string_view id);

/// Builds BASE.mtlx (last) and its BASE_<map>.png images for @p material with @p shader.
/// Atlas regions are cut out into images of their own. False + one-line @p error when a
/// texture cannot be read. Graph-driven inputs whose nodes all have standard-library
/// counterparts are a <nodegraph> (core/mtlx_graph_export.h); with @p baked, the other
/// graph-driven inputs read its maps as image nodes (core/baked_maps.h).
bool buildMtlx(const Material& material, std::string_view baseName, MtlxShader shader,
               TextureCache& textures, BuiltExport& out, std::string* error,
               const BakedMaterialMaps* baked = nullptr);

} // namespace velvet
