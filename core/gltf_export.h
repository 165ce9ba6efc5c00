#pragma once
/// @file gltf_export.h
/// A material on a mesh as a glTF 2.0 asset: the metallic-roughness core with
/// KHR_materials_clearcoat, _sheen, _specular, _ior, _emissive_strength and _anisotropy, textures
/// as PNG images (atlas regions through KHR_texture_transform), in a .glb (one file, buffers and
/// images embedded) or a .gltf (JSON, a .bin and the images beside it). Every mapping, and what
/// cannot be mapped, is in docs/interchange.md. Built in memory; writing is export_files.h's job.

#include "core/baked_maps.h"
#include "core/export_files.h"
#include "core/material.h"
#include "core/mesh.h"

#include <string>
#include <string_view>
#include <vector>

namespace velvet {

class TextureCache;

enum class GltfContainer { Glb, Gltf };

/// .glb: one file. .gltf: the images, the .bin, then the .gltf (written in that order).
using GltfExportResult = BuiltExport;

/// Builds the asset of @p material on @p mesh. @p baseName (already a safe stem, see
/// sanitizeFileStem) names the files: BASE.glb, or BASE.gltf + BASE.bin + BASE_<map>.png.
/// Textures are read through @p textures. False + one-line @p error when a texture cannot be
/// read or the mesh is empty. With @p baked, the graph-driven inputs read its maps
/// (core/baked_maps.h); without, a graph is a warning and its inputs' parameters are exported.
bool buildGltf(const Material& material, const MeshData& mesh, std::string_view baseName,
               GltfContainer container, TextureCache& textures, GltfExportResult& out,
               std::string* error, const BakedMaterialMaps* baked = nullptr);

} // namespace velvet
