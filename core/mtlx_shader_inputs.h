#pragma once
/// @file mtlx_shader_inputs.h
/// Which Velvet parameter (and texture slot, and channel) each input of the MaterialX shaders
/// Velvet reads stands for — the inverse of core/mtlx_export.cpp's table (docs/interchange.md,
/// "From MaterialX 1.39") — and MaterialX colour space names as Velvet's OCIO config names them.
/// Internal to core/mtlx_import.cpp.

#include "core/material.h"

#include <map>
#include <string>

namespace velvet::mtlx {

/// Where one shader input is mapped: a parameter, optionally a texture slot and the channel
/// the slot reads (so `extract` of that channel of an image fills the slot directly).
struct Target {
    ParamId param = ParamId::Count;
    TextureSlot slot = TextureSlot::Count;
    int channel = -1; ///< the channel the slot reads for a scalar; -1: RGB
    bool normal = false;
};

/// The mapped inputs of @p shader ("standard_surface", "open_pbr_surface", "gltf_pbr"); empty
/// for any other shader. base / base_weight, coat_IOR / coat_ior and the alpha inputs are read
/// apart (they multiply or are checked, not mapped to one parameter).
const std::map<std::string, Target>& targetsOf(const std::string& shader);

/// "srgb_texture" -> "sRGB texture", "lin_rec709" -> "Linear Rec.709", "acescg" / "lin_ap1" ->
/// "ACEScg", "raw" / "none" -> "Raw" (the names of resources/ocio/config.ocio); others kept.
std::string velvetColorSpace(const std::string& mx);

} // namespace velvet::mtlx
