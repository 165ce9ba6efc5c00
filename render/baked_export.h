#pragma once
/// @file baked_export.h
/// `velvet export -f glb|gltf|mtlx` and File > Export…: what the material's node graph drives is
/// baked on the GPU (bakeMaterialMaps, the texture sets' bake, at ExportOptions::bakeSize) and
/// the export references the baked maps (core/baked_maps.h) through core's exportMaterial.

#include "core/material_export.h"

namespace velvet::render {

/// exportMaterial with the graph baked: when @p scene's material has a graph that drives a map
/// and the format is glTF or MaterialX, its maps are baked at options.bakeSize (making a headless
/// context when none is current) and passed as options.baked. A bake that cannot run (no OpenGL
/// context, a graph that does not compile) fails the export with status Failed and a line
/// saying so; a texture the bake cannot read is BadInput. Nothing is written then.
ExportOutcome exportMaterialBaked(const Scene& scene, const std::filesystem::path& folder,
                                  std::string_view baseName, const ExportOptions& options,
                                  TextureCache* textures = nullptr);

} // namespace velvet::render
