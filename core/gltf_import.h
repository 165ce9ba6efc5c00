#pragma once
/// @file gltf_import.h
/// A material of a glTF 2.0 asset (.gltf with its files, or .glb) as a Velvet material: the
/// metallic-roughness core, KHR_materials_clearcoat, _sheen, _specular, _ior,
/// _emissive_strength, _anisotropy, KHR_texture_transform, and KHR_materials_pbrSpecularGlossiness
/// converted (core/gltf_spec_gloss.h). Parsed with nlohmann-json; every mapping in
/// docs/interchange.md.

#include "core/material_import.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {

/// The names of the asset's materials ("" for unnamed ones). False + @p problem when the file
/// is not a readable glTF 2.0 asset.
bool readGltfMaterialNames(const std::filesystem::path& file, std::vector<std::string>& names,
                           ImportProblem& problem);

/// Reads material @p select (selectMaterial()) of @p file. Embedded images are planned as
/// @p imageFolder / STEM_<name>.<ext> (@p imageStem already safe), not written.
bool importGltfMaterial(const std::filesystem::path& file, std::string_view select,
                        const std::filesystem::path& imageFolder, std::string_view imageStem,
                        ImportedMaterial& out, ImportProblem& problem);

} // namespace velvet
