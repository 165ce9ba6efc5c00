#pragma once
/// @file mtlx_import.h
/// A material of a MaterialX 1.39 document as a Velvet material: standard_surface,
/// open_pbr_surface and gltf_pbr shader nodes (the inverse of core/mtlx_export.h), constant
/// inputs, `image` inputs with their colour spaces (and uvtiling / uvoffset), and node graphs
/// mapped to Velvet graph nodes (core/graph) where a counterpart exists. Parsed with pugixml;
/// every mapping in docs/interchange.md ("Import").

#include "core/material_import.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {

/// The document's surfacematerial names, in document order. False + @p problem when the file
/// is not readable MaterialX.
bool readMtlxMaterialNames(const std::filesystem::path& file, std::vector<std::string>& names,
                           ImportProblem& problem);

/// Reads the surfacematerial @p select (selectMaterial()) of @p file.
bool importMtlxMaterial(const std::filesystem::path& file, std::string_view select,
                        ImportedMaterial& out, ImportProblem& problem);

} // namespace velvet
