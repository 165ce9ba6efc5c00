#include "core/material.h"

#include "core/graph/graph.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace velvet {
namespace {

constexpr std::array<std::string_view, 3> kDistributionNames{"ggx", "beckmann", "blinn-phong"};
constexpr std::array<std::string_view, 7> kVisibilityNames{"smith-ggx-separable",
                                                           "smith-ggx-correlated",
                                                           "schlick-ggx",
                                                           "cook-torrance",
                                                           "implicit",
                                                           "neumann",
                                                           "kelemen"};
constexpr std::array<std::string_view, 3> kFresnelNames{"schlick", "schlick-sg",
                                                        "exact-dielectric"};
constexpr std::array<std::string_view, 2> kDiffuseNames{"lambert", "burley"};
constexpr std::array<std::string_view, 3> kSheenModelNames{"charlie-conty-kulla",
                                                           "charlie-ashikhmin", "charlie-neubelt"};

// Ranges and defaults follow glTF 2.0 and its KHR_materials_* extensions, so that a preset with
// defaults exports as a plain glTF material.
const std::array<ParamMeta, kParamCount> kParams{
    colorParam("lobes.base.color", "Base colour", "Base", 0, 1, glm::vec3(0.8f),
               "Diffuse albedo of dielectrics, specular colour of metals (glTF baseColorFactor)."),
    floatParam("lobes.base.metallic", "Metallic", "Base", 0, 1, 0, "",
               "0 for dielectrics, 1 for metals (glTF metallicFactor)."),
    floatParam("lobes.base.roughness", "Roughness", "Base", 0, 1, 0.5f, "",
               "Perceptual roughness; alpha = roughness^2 (glTF roughnessFactor)."),
    floatParam("lobes.base.specularWeight", "Specular weight", "Base", 0, 1, 1, "",
               "Strength of the dielectric specular reflection (KHR_materials_specular)."),
    colorParam("lobes.base.specularColor", "Specular colour", "Base", 0, 1, glm::vec3(1.0f),
               "Tint of the dielectric F0 (KHR_materials_specular specularColorFactor)."),
    floatParam("lobes.base.ior", "IOR", "Base", 1, 3, 1.5f, "",
               "Index of refraction; 1.5 gives F0 = 0.04 (KHR_materials_ior)."),
    floatParam("lobes.base.normalScale", "Normal strength", "Base", 0, 2, 1, "",
               "Scale of the normal map's XY (glTF normalTexture.scale)."),
    floatParam(
        "lobes.base.occlusionStrength", "Occlusion strength", "Base", 0, 1, 1, "",
        "How much the occlusion map darkens indirect light (glTF occlusionTexture.strength)."),
    colorParam("lobes.emission.color", "Emissive colour", "Emission", 0, 1, glm::vec3(0.0f),
               "Emitted radiance before strength (glTF emissiveFactor)."),
    floatParam("lobes.emission.strength", "Emissive strength", "Emission", 0, 1000, 1, "nits",
               "Multiplier on the emissive colour (KHR_materials_emissive_strength).", 20.0f),
    floatParam("lobes.clearcoat.weight", "Clearcoat", "Clearcoat", 0, 1, 0, "",
               "Weight of the clear coat layer over the base (KHR_materials_clearcoat)."),
    floatParam("lobes.clearcoat.roughness", "Clearcoat roughness", "Clearcoat", 0, 1, 0.03f, "",
               "Perceptual roughness of the coat (clearcoatRoughnessFactor)."),
    floatParam("lobes.clearcoat.normalScale", "Clearcoat normal strength", "Clearcoat", 0, 2, 1, "",
               "Scale of the clearcoat normal map's XY."),
    floatParam("lobes.sheen.weight", "Sheen", "Sheen", 0, 1, 0, "",
               "Weight of the sheen lobe; the exported sheenColorFactor is weight x colour."),
    colorParam("lobes.sheen.color", "Sheen colour", "Sheen", 0, 1, glm::vec3(1.0f),
               "Colour of the fibre retro-reflection (KHR_materials_sheen sheenColorFactor)."),
    floatParam("lobes.sheen.roughness", "Sheen roughness", "Sheen", 0, 1, 0.3f, "",
               "Spread of the sheen lobe (KHR_materials_sheen sheenRoughnessFactor)."),
    floatParam("lobes.anisotropy.strength", "Anisotropy", "Anisotropy", 0, 1, 0, "",
               "Stretches the base highlight along the anisotropy direction "
               "(KHR_materials_anisotropy anisotropyStrength)."),
    floatParam("lobes.anisotropy.rotation", "Anisotropy rotation", "Anisotropy", -180, 180, 0, "°",
               "Direction of the stretch, counter-clockwise from the tangent toward the "
               "bitangent (anisotropyRotation, in degrees)."),
    choiceParam("brdf.distribution", "Distribution (D)", "BRDF", kDistributionNames, 0,
                "Microfacet normal distribution: GGX (Walter 2007), Beckmann (1963), Blinn-Phong."),
    choiceParam("brdf.visibility", "Geometry (G/V)", "BRDF", kVisibilityNames, 0,
                "Masking-shadowing term; the glTF specification uses separable Smith-GGX."),
    choiceParam(
        "brdf.fresnel", "Fresnel (F)", "BRDF", kFresnelNames, 0,
        "Fresnel reflectance: Schlick 1994, its spherical-gaussian form, or exact dielectric."),
    choiceParam("brdf.diffuse", "Diffuse", "BRDF", kDiffuseNames, 0,
                "Diffuse term: Lambert, or Burley 2012 (Disney) with retro-reflection."),
    choiceParam(
        "brdf.sheen", "Sheen model", "BRDF", kSheenModelNames, 0,
        "Charlie D (Estevez & Kulla 2017) with Conty-Kulla, Ashikhmin or Neubelt visibility."),
};

const std::array<TextureSlotMeta, kTextureSlotCount> kSlots{{
    {"baseColor", "Base colour", true, "RGB base colour, A alpha."},
    {"metallicRoughness", "Metallic / roughness", false, "glTF packing: G roughness, B metallic."},
    {"specRoughMetal", "Specular / roughness / metallic", false,
     "Material atlas packing: R specular, G roughness, B metallic."},
    {"normal", "Normal", false, "Tangent-space normal map (OpenGL convention, +Y up)."},
    {"occlusion", "Occlusion", false, "R: ambient occlusion."},
    {"emissive", "Emissive", true, "RGB emission."},
    {"clearcoat", "Clearcoat", false, "R: clearcoat weight."},
    {"clearcoatRoughness", "Clearcoat roughness", false, "G: clearcoat roughness."},
    {"clearcoatNormal", "Clearcoat normal", false, "Tangent-space normal of the coat."},
    {"sheenColor", "Sheen colour", true, "RGB sheen colour."},
    {"sheenRoughness", "Sheen roughness", false, "A: sheen roughness."},
    {"specular", "Specular", false, "A: specular weight."},
    {"specularColor", "Specular colour", true, "RGB specular colour."},
    {"anisotropy", "Anisotropy", false,
     "RG: direction in tangent space ([0, 1] to [-1, 1]), B: strength multiplier."},
}};

} // namespace

std::span<const ParamMeta> paramMetas() {
    return kParams;
}

const ParamMeta& paramMeta(ParamId id) {
    return kParams[static_cast<size_t>(id)];
}

ParamId paramIdFromString(std::string_view id) {
    for (int i = 0; i < kParamCount; ++i)
        if (kParams[i].id == id)
            return static_cast<ParamId>(i);
    return ParamId::Count;
}

std::span<const TextureSlotMeta> textureSlotMetas() {
    return kSlots;
}

const TextureSlotMeta& textureSlotMeta(TextureSlot slot) {
    return kSlots[static_cast<size_t>(slot)];
}

Material::Material() {
    for (int i = 0; i < kParamCount; ++i)
        m_values[i] = kParams[i].defaultValue;
}

void Material::setValue(ParamId id, glm::vec3 v) {
    m_values[index(id)] = constrainParamValue(paramMeta(id), v);
}

void Material::resetValue(ParamId id) {
    m_values[index(id)] = paramMeta(id).defaultValue;
}

SharedGraph::SharedGraph(const graph::Graph& g)
    : m_graph(std::make_shared<const graph::Graph>(g)) {}

bool SharedGraph::operator==(const SharedGraph& other) const {
    if (m_graph == other.m_graph)
        return true;
    if (!m_graph || !other.m_graph)
        return false;
    return *m_graph == *other.m_graph;
}

} // namespace velvet
