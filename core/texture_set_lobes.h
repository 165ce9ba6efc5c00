#pragma once
/// @file texture_set_lobes.h
/// The lobe maps of engine texture sets (internal to core/texture_set_export.cpp, and the export's
/// warnings in render/material_bake.cpp): clearcoat,
/// sheen, specular and anisotropy, baked like the base maps (MaterialMaps), written where the
/// target engine has an input for them — glTF's KHR_materials_clearcoat, _sheen, _specular and
/// _anisotropy textures; Unreal's Clear Coat, Cloth (fuzz) and Specular / Anisotropy inputs;
/// HDRP Lit's coat mask and anisotropy map; Godot's clearcoat texture and anisotropy flowmap —
/// and otherwise named in a warning. docs/interchange.md, "Engine texture sets".

#include "core/material.h"
#include "core/texture_set_export.h"

#include <string>
#include <string_view>
#include <vector>

namespace velvet {

/// Which lobes the baked maps carry: some texel of the coat weight, sheen colour or anisotropy
/// strength above 0, or some specular texel off the default (weight 1, colour white). An empty
/// map carries nothing.
struct LobePresence {
    bool coat = false;
    bool sheen = false;
    bool specular = false;
    bool anisotropy = false;
};
LobePresence lobePresence(const MaterialMaps& maps);

/// The lobe files @p options.target reads for the lobes @p present, named as the base maps are
/// (prefix + @p base + suffix), in the order they are written (after the base maps).
std::vector<TextureSetFile> planLobeMaps(const TextureSetOptions& options, std::string_view base,
                                         const LobePresence& present);

/// The texels of planned lobe file @p file (one of planLobeMaps()) from @p maps, as they go into
/// the file: colour channels of an "srgb" file sRGB-encoded (not in EXR), the rest linear.
/// False + @p error when @p file is not a lobe file.
bool packLobeMap(const TextureSetFile& file, const MaterialMaps& maps, bool exr, Image& out,
                 std::string* error);

/// What @p target's set cannot carry of @p m's lobes (the engine has no input for it), one
/// warning line each, naming the parameter and the engine.
std::vector<std::string> lobeGaps(const Material& m, TextureSetTarget target);

} // namespace velvet
