#pragma once
/// @file light_rigs.h
/// Named light rigs: the sets of lights a look-dev artist switches between to judge a material
/// (a key light, studio three-point, softboxes, sun, a stage spot, many small coloured points,
/// or the environment alone). Marmoset Toolbag and Substance ship the same idea as "light
/// presets". Units as in docs/units.md.

#include "core/scene.h"

#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace velvet {

struct LightRig {
    std::string_view id;    ///< stable, for files and the command line ("three-point")
    std::string_view label; ///< for menus ("Studio three-point")
    std::string_view description;
};

/// Every rig, in menu order; the first ("key") is the default scene's.
std::span<const LightRig> lightRigs();

/// The lights of rig @p id; nullopt for an unknown id.
std::optional<std::vector<Light>> lightRigLights(std::string_view id);

/// The id of the rig whose lights equal @p lights exactly; nullopt when they were edited (a
/// custom rig).
std::optional<std::string_view> matchingLightRig(const std::vector<Light>& lights);

} // namespace velvet
