#pragma once
/// @file baked_maps.h
/// The node graph's maps in a glTF or MaterialX export (issue 12): what the graph drives is
/// baked on the GPU (render/material_bake.h, the same bake as engine texture sets) and each baked
/// map replaces the texture uses of the inputs it carries, with those inputs' factors set so
/// factor x texture = the baked value (1, white; emission's peak as its strength). Inputs the
/// graph does not drive keep their factors and texture slots. Core only plans: the bake itself
/// is render/'s (render/baked_export.h). docs/interchange.md, "The node graph".

#include "core/gltf_textures.h"
#include "core/material.h"
#include "core/texture_set_export.h"

#include <array>
#include <set>
#include <string>
#include <vector>

namespace velvet {

/// The baked maps an export can reference, each standing for a group of material inputs.
enum class BakedMap {
    BaseColor,  ///< baseColor (and its alpha)
    Orm,        ///< metallic, roughness, occlusion, occlusionStrength
    Normal,     ///< normal, normalScale
    Emission,   ///< emissiveColor, emissiveStrength
    Coat,       ///< clearcoatWeight, clearcoatRoughness
    Sheen,      ///< sheenWeight, sheenColor, sheenRoughness
    Specular,   ///< specularWeight, specularColor
    Anisotropy, ///< anisotropyStrength, anisotropyRotation, anisotropyDirection
    Count
};
inline constexpr int kBakedMapCount = int(BakedMap::Count);

/// Which maps @p material's graph drives, and the graph-driven inputs no map carries.
struct BakedInputs {
    std::array<bool, kBakedMapCount> driven{};
    std::vector<std::string> unbakeable; ///< output inputs (ior, clearcoatNormal, …) by name
    bool occlusion = false; ///< occlusion or its strength driven (the ORM's R is then read)
    bool any() const;
};

/// The inputs of @p material's graph's material output that a link feeds (empty without a graph).
std::vector<std::string> graphDrivenInputs(const Material& material);
/// graphDrivenInputs grouped into the baked maps that carry them, less those in @p skip (the
/// inputs a MaterialX export writes as a nodegraph: core/mtlx_graph_export.h).
BakedInputs bakedInputsOf(const Material& material, const std::set<std::string>& skip = {});

/// The maps baked for an export and the size they were baked at.
struct BakedMaterialMaps {
    MaterialMaps maps;
    BakedInputs inputs;
    int size = 0;
};

/// Adds @p baked's driven maps to @p plan as images ("baked_<map>", encoded as glTF reads them)
/// and points the slots that read them there; returns @p material with those inputs' factors
/// set so factor x texture = the baked value, and without its graph (whose lines, for inputs no
/// map carries, go to @p warnings). Images no slot reads any more are dropped from the plan.
Material applyBakedMaps(const Material& material, const BakedMaterialMaps& baked,
                        GltfTexturePlan& plan, std::vector<std::string>& warnings);

} // namespace velvet
