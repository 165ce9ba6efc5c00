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

/// KHR_materials_anisotropy's strength @p s as the anisotropy a of standard_surface
/// (`specular_anisotropy`) and open_pbr_surface (`specular_roughness_anisotropy`): both shaders
/// take the ratio of their two alphas from it (alpha_b / alpha_t = 1 - a), so a = 1 - alpha /
/// mix(alpha, 1, s^2) keeps the extension's ratio at the material's @p roughness (alpha =
/// roughness^2, clamped as brdf::anisotropicAlphas). Their alphas' magnitudes differ
/// (docs/interchange.md); mtlxAnisotropyToStrength() is the exact inverse for roughness < 1.
float strengthToMtlxAnisotropy(float s, float roughness);
float mtlxAnisotropyToStrength(float a, float roughness);

/// "srgb_texture" -> "sRGB texture", "lin_rec709" -> "Linear Rec.709", "acescg" / "lin_ap1" ->
/// "ACEScg", "raw" / "none" -> "Raw" (the names of resources/ocio/config.ocio); others kept.
std::string velvetColorSpace(const std::string& mx);

} // namespace velvet::mtlx
