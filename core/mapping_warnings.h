#pragma once
/// @file mapping_warnings.h
/// What no interchange format carries of a Velvet material, said once for every exporter
/// (glTF, MaterialX): the BRDF term choices and the node graph (docs/interchange.md).

#include "core/material.h"

#include <string>
#include <string_view>
#include <vector>

namespace velvet {

/// One line per loss when @p material goes to @p target ("glTF 2.0", "MaterialX
/// standard_surface"): each BRDF term choice off Velvet's default (glTF 2.0 Appendix B's terms,
/// which those formats' shaders share), the sheen model with sheen on, and the node graph
/// (naming the material inputs it drives) when the export was not given its baked maps
/// (core/baked_maps.h).
std::vector<std::string> mappingWarnings(const Material& material, std::string_view target);

} // namespace velvet
