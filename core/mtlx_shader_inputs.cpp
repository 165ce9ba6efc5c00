#include "core/mtlx_shader_inputs.h"

#include "core/brdf.h"

#include <algorithm>
#include <cmath>

namespace velvet::mtlx {

using S = TextureSlot;
using P = ParamId;

const std::map<std::string, Target>& targetsOf(const std::string& shader) {
    static const std::map<std::string, Target> standard{
        {"base_color", {P::BaseColor, S::BaseColor}},
        {"metalness", {P::Metallic, S::MetallicRoughness, 2}},
        {"specular", {P::SpecularWeight, S::Specular, 3}},
        {"specular_color", {P::SpecularColor, S::SpecularColor}},
        {"specular_roughness", {P::Roughness, S::MetallicRoughness, 1}},
        {"specular_IOR", {P::Ior}},
        {"coat", {P::ClearcoatWeight, S::Clearcoat, 0}},
        {"coat_roughness", {P::ClearcoatRoughness, S::ClearcoatRoughness, 1}},
        {"sheen", {P::SheenWeight}},
        {"sheen_color", {P::SheenColor, S::SheenColor}},
        {"sheen_roughness", {P::SheenRoughness, S::SheenRoughness, 3}},
        {"emission", {P::EmissiveStrength}},
        {"emission_color", {P::EmissiveColor, S::Emissive}},
        {"normal", {P::NormalScale, S::Normal, -1, true}},
        {"coat_normal", {P::ClearcoatNormalScale, S::ClearcoatNormal, -1, true}},
    };
    static const std::map<std::string, Target> openPbr{
        {"base_color", {P::BaseColor, S::BaseColor}},
        {"base_metalness", {P::Metallic, S::MetallicRoughness, 2}},
        {"specular_weight", {P::SpecularWeight, S::Specular, 3}},
        {"specular_color", {P::SpecularColor, S::SpecularColor}},
        {"specular_roughness", {P::Roughness, S::MetallicRoughness, 1}},
        {"specular_ior", {P::Ior}},
        {"coat_weight", {P::ClearcoatWeight, S::Clearcoat, 0}},
        {"coat_roughness", {P::ClearcoatRoughness, S::ClearcoatRoughness, 1}},
        {"fuzz_weight", {P::SheenWeight}},
        {"fuzz_color", {P::SheenColor, S::SheenColor}},
        {"fuzz_roughness", {P::SheenRoughness, S::SheenRoughness, 3}},
        {"emission_luminance", {P::EmissiveStrength}},
        {"emission_color", {P::EmissiveColor, S::Emissive}},
        {"geometry_normal", {P::NormalScale, S::Normal, -1, true}},
        {"geometry_coat_normal", {P::ClearcoatNormalScale, S::ClearcoatNormal, -1, true}},
    };
    static const std::map<std::string, Target> gltf{
        {"base_color", {P::BaseColor, S::BaseColor}},
        {"metallic", {P::Metallic, S::MetallicRoughness, 2}},
        {"roughness", {P::Roughness, S::MetallicRoughness, 1}},
        {"specular", {P::SpecularWeight, S::Specular, 3}},
        {"specular_color", {P::SpecularColor, S::SpecularColor}},
        {"ior", {P::Ior}},
        {"sheen_color", {P::SheenColor, S::SheenColor}},
        {"sheen_roughness", {P::SheenRoughness, S::SheenRoughness, 3}},
        {"clearcoat", {P::ClearcoatWeight, S::Clearcoat, 0}},
        {"clearcoat_roughness", {P::ClearcoatRoughness, S::ClearcoatRoughness, 1}},
        {"emissive", {P::EmissiveColor, S::Emissive}},
        {"emissive_strength", {P::EmissiveStrength}},
        {"normal", {P::NormalScale, S::Normal, -1, true}},
        {"clearcoat_normal", {P::ClearcoatNormalScale, S::ClearcoatNormal, -1, true}},
        {"occlusion", {P::OcclusionStrength, S::Occlusion, 0}},
    };
    static const std::map<std::string, Target> none;
    if (shader == "standard_surface")
        return standard;
    if (shader == "open_pbr_surface")
        return openPbr;
    if (shader == "gltf_pbr")
        return gltf;
    return none;
}

float strengthToMtlxAnisotropy(float s, float roughness) {
    const glm::vec2 a = brdf::anisotropicAlphas(roughness, s); // (alpha_t, alpha_b)
    return std::clamp(1.0f - a.y / a.x, 0.0f, 1.0f);
}

float mtlxAnisotropyToStrength(float a, float roughness) {
    const float alpha = brdf::anisotropicAlphas(roughness, 0.0f).y;
    if (alpha >= 1.0f)
        return 0.0f; // alpha_t = alpha_b = 1 whatever the strength
    const float at = alpha / std::max(1.0f - std::clamp(a, 0.0f, 1.0f), 1e-6f);
    return std::sqrt(std::clamp((at - alpha) / (1.0f - alpha), 0.0f, 1.0f));
}

std::string velvetColorSpace(const std::string& mx) {
    static const std::map<std::string, std::string> names{{"srgb_texture", "sRGB texture"},
                                                          {"lin_rec709", "Linear Rec.709"},
                                                          {"acescg", "ACEScg"},
                                                          {"lin_ap1", "ACEScg"},
                                                          {"raw", "Raw"},
                                                          {"none", "Raw"}};
    const auto it = names.find(mx);
    return it == names.end() ? mx : it->second;
}

} // namespace velvet::mtlx
