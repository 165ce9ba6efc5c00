#pragma once
/// @file material_bake.h
/// A material's per-pixel maps baked on the GPU in UV space, for engine texture sets
/// (core/texture_set_export.h, `velvet export -f texture-set`): the values the G-buffer pass
/// computes — parameters times their texture slots (atlas regions cut by the same sampleSlot), the
/// base maps and the lobes' (clearcoat, sheen, specular, anisotropy),
/// then the material's node graph compiled by the graph compiler over them — drawn into float
/// targets at the requested size (resources/shaders/material_bake.frag). A constant parameter
/// gives a flat map.

#include "core/diagnostics.h"
#include "core/material.h"
#include "core/material_export.h"
#include "core/texture_set_export.h"

#include <filesystem>
#include <string>
#include <string_view>

namespace velvet {
class TextureCache;
}

namespace velvet::render {

/// Bakes @p material's maps at @p width x @p height (1..8192) into @p out (row 0 = v ~ 0, the
/// image's top row, as Velvet's and glTF's UVs). Creates a headless EGL context when none is
/// current (as renderSceneOffscreen). Texture and graph problems (a missing file: the slot falls
/// back to its parameter, as in the viewport) go to @p problems. False + @p error when no
/// context can be made, the graph does not compile or the bake program fails.
bool bakeMaterialMaps(const Material& material, int width, int height, MaterialMaps& out,
                      Problems* problems, std::string* error);

/// `velvet export -f texture-set` and File > Export…'s texture sets: bakes @p material's maps at
/// options.size (bakeMaterialMaps), packs and names them for options.target (buildTextureSet) and
/// writes them with the manifest into @p folder (writeExportFiles: @p baseName sanitised, every
/// existing target refused unless @p force, each file atomic; nothing written unless all could
/// be built). The outcome's warnings name what the target's set cannot carry (a lobe the engine
/// has no input for: core/texture_set_lobes.h; the IOR; the BRDF term choices) and the texture
/// problems met while baking.
ExportOutcome exportTextureSet(const Material& material, const std::filesystem::path& folder,
                               std::string_view baseName, const TextureSetOptions& options,
                               bool force);

} // namespace velvet::render
