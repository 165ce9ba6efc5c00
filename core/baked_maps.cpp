// The graph's baked maps in a glTF / MaterialX texture plan. Each image is encoded as the glTF
// 2.0 specification reads the texture it stands for (section 3.9; KHR_materials_clearcoat,
// _sheen, _specular, _anisotropy): colour channels sRGB-encoded, data channels linear.
#include "core/baked_maps.h"

#include "core/color_management.h"
#include "core/graph/graph.h"
#include "core/graph/node_catalogue.h"

#include <algorithm>
#include <map>

namespace velvet {
namespace {

/// The map that carries output input @p name, or Count when no baked map does.
BakedMap mapOf(const std::string& name) {
    static const std::map<std::string, BakedMap> kMaps{
        {"baseColor", BakedMap::BaseColor},
        {"metallic", BakedMap::Orm},
        {"roughness", BakedMap::Orm},
        {"occlusion", BakedMap::Orm},
        {"occlusionStrength", BakedMap::Orm},
        {"normal", BakedMap::Normal},
        {"normalScale", BakedMap::Normal},
        {"emissionColor", BakedMap::Emission},
        {"emissionStrength", BakedMap::Emission},
        {"clearcoatWeight", BakedMap::Coat},
        {"clearcoatRoughness", BakedMap::Coat},
        {"sheenWeight", BakedMap::Sheen},
        {"sheenColor", BakedMap::Sheen},
        {"sheenRoughness", BakedMap::Sheen},
        {"specularWeight", BakedMap::Specular},
        {"specularColor", BakedMap::Specular},
        {"anisotropyStrength", BakedMap::Anisotropy},
        {"anisotropyRotation", BakedMap::Anisotropy},
        {"anisotropyDirection", BakedMap::Anisotropy},
    };
    const auto it = kMaps.find(name);
    return it == kMaps.end() ? BakedMap::Count : it->second;
}

/// Counts colour values 8 bits cannot hold (above 1) while encoding channels [0, @p colour).
float encode(float v, bool srgb, long& clamped) {
    if (v > 1.0f + 1e-6f)
        ++clamped;
    v = std::clamp(v, 0.0f, 1.0f);
    return srgb ? linearToSrgb(v) : v;
}

/// @p source's first @p channels channels, the first @p colour of them sRGB-encoded, each
/// value v mapped through v * scale + bias before encoding.
Image encoded(const Image& source, int channels, int colour, long& clamped, float scale = 1.0f,
              float bias = 0.0f, int remapped = 0) {
    Image out(source.width, source.height, channels);
    for (int y = 0; y < source.height; ++y)
        for (int x = 0; x < source.width; ++x)
            for (int c = 0; c < channels; ++c) {
                float v = c < source.channels ? source.at(x, y)[c] : 1.0f;
                if (c < remapped)
                    v = v * scale + bias;
                out.at(x, y)[c] = encode(v, c < colour, clamped);
            }
    return out;
}

/// Drops images no use reads and renumbers the uses.
void pruneImages(GltfTexturePlan& plan) {
    std::vector<int> renumber(plan.images.size(), -1);
    for (const auto& use : plan.uses)
        if (use)
            renumber[size_t(use->image)] = 0;
    std::vector<GltfImage> kept;
    for (size_t i = 0; i < plan.images.size(); ++i)
        if (renumber[i] == 0) {
            renumber[i] = int(kept.size());
            kept.push_back(std::move(plan.images[i]));
        }
    plan.images = std::move(kept);
    for (auto& use : plan.uses)
        if (use)
            use->image = renumber[size_t(use->image)];
}

} // namespace

bool BakedInputs::any() const {
    return std::any_of(driven.begin(), driven.end(), [](bool b) { return b; });
}

std::vector<std::string> graphDrivenInputs(const Material& material) {
    std::vector<std::string> names;
    if (!material.graph)
        return names;
    const graph::Graph& g = *material.graph;
    const graph::NodeId out = g.outputNode();
    const graph::NodeType* type = graph::findNodeType(graph::kOutputTypeId);
    if (out == graph::kInvalidNodeId || !type)
        return names;
    for (const graph::Connection& c : g.connections())
        if (c.inNode == out && c.inPort < type->inputs.size())
            names.emplace_back(type->inputs[c.inPort].name);
    return names;
}

BakedInputs bakedInputsOf(const Material& material, const std::set<std::string>& skip) {
    BakedInputs in;
    for (const std::string& name : graphDrivenInputs(material)) {
        if (skip.count(name))
            continue;
        const BakedMap map = mapOf(name);
        if (map == BakedMap::Count)
            in.unbakeable.push_back(name);
        else
            in.driven[size_t(map)] = true;
        if (name == "occlusion" || name == "occlusionStrength")
            in.occlusion = true;
    }
    return in;
}

Material applyBakedMaps(const Material& material, const BakedMaterialMaps& baked,
                        GltfTexturePlan& plan, std::vector<std::string>& warnings) {
    Material m = material;
    m.graph = SharedGraph();
    const MaterialMaps& maps = baked.maps;
    long clamped = 0;
    auto driven = [&](BakedMap map) { return baked.inputs.driven[size_t(map)]; };
    auto add = [&](const char* label, Image pixels, std::initializer_list<TextureSlot> slots) {
        plan.images.push_back({std::string("baked_") + label, std::move(pixels)});
        for (TextureSlot s : slots) {
            GltfTextureUse use;
            use.image = int(plan.images.size()) - 1; // the bake is in the mesh's UVs: no transform
            plan.uses[size_t(s)] = use;
        }
    };
    if (driven(BakedMap::BaseColor)) {
        // RGB the base colour (sRGB, section 3.9.2), A the slot's alpha (linear); alphaCutout
        // stays the plan's: the baked alpha is the base-colour slot's own.
        add("baseColor", encoded(maps.baseColor, 4, 3, clamped), {TextureSlot::BaseColor});
        m.setColor(ParamId::BaseColor, glm::vec3(1.0f));
    }
    if (driven(BakedMap::Orm)) {
        // glTF's packing: R occlusion (strength already applied), G roughness, B metallic. A
        // specular A that shared the slots' packed image keeps reading that image.
        const bool occlusion =
            plan.uses[size_t(TextureSlot::Occlusion)].has_value() || baked.inputs.occlusion;
        add("orm", encoded(maps.orm, 3, 0, clamped), {TextureSlot::MetallicRoughness});
        if (occlusion) {
            plan.uses[size_t(TextureSlot::Occlusion)] =
                plan.uses[size_t(TextureSlot::MetallicRoughness)];
            m.setScalar(ParamId::OcclusionStrength, 1.0f);
        }
        m.setScalar(ParamId::Metallic, 1.0f);
        m.setScalar(ParamId::Roughness, 1.0f);
    }
    if (driven(BakedMap::Normal)) {
        // Unit tangent-space normals with the scale applied, as n * 0.5 + 0.5 (section 3.9.3).
        add("normal", encoded(maps.normal, 3, 0, clamped, 0.5f, 0.5f, 3), {TextureSlot::Normal});
        m.setScalar(ParamId::NormalScale, 1.0f);
    }
    if (driven(BakedMap::Emission)) {
        // Emission may exceed 1: the texture holds it over its peak, which becomes the
        // strength (KHR_materials_emissive_strength) with a white factor.
        float peak = 0.0f;
        for (float v : maps.emission.pixels)
            peak = std::max(peak, v);
        if (peak > 0.0f) {
            add("emission", encoded(maps.emission, 3, 3, clamped, 1.0f / peak, 0.0f, 3),
                {TextureSlot::Emissive});
            m.setColor(ParamId::EmissiveColor, glm::vec3(1.0f));
            m.setScalar(ParamId::EmissiveStrength, peak);
        } else {
            plan.uses[size_t(TextureSlot::Emissive)].reset();
            m.setColor(ParamId::EmissiveColor, glm::vec3(0.0f));
        }
    }
    if (driven(BakedMap::Coat)) {
        // clearcoatTexture reads R, clearcoatRoughnessTexture G: one image serves both.
        add("clearcoat", encoded(maps.coat, 3, 0, clamped),
            {TextureSlot::Clearcoat, TextureSlot::ClearcoatRoughness});
        m.setScalar(ParamId::ClearcoatWeight, 1.0f);
        m.setScalar(ParamId::ClearcoatRoughness, 1.0f);
    }
    if (driven(BakedMap::Sheen)) {
        // sheenColorTexture reads RGB (sRGB; weight x colour), sheenRoughnessTexture A.
        add("sheen", encoded(maps.sheen, 4, 3, clamped),
            {TextureSlot::SheenColor, TextureSlot::SheenRoughness});
        m.setScalar(ParamId::SheenWeight, 1.0f);
        m.setColor(ParamId::SheenColor, glm::vec3(1.0f));
        m.setScalar(ParamId::SheenRoughness, 1.0f);
    }
    if (driven(BakedMap::Specular)) {
        // specularColorTexture reads RGB (sRGB), specularTexture A.
        add("specular", encoded(maps.specular, 4, 3, clamped),
            {TextureSlot::Specular, TextureSlot::SpecularColor});
        m.setScalar(ParamId::SpecularWeight, 1.0f);
        m.setColor(ParamId::SpecularColor, glm::vec3(1.0f));
    }
    if (driven(BakedMap::Anisotropy)) {
        // RG the direction as d * 0.5 + 0.5 (rotation applied, so the rotation is 0), B the
        // strength (KHR_materials_anisotropy).
        add("anisotropy", encoded(maps.anisotropy, 3, 0, clamped, 0.5f, 0.5f, 2),
            {TextureSlot::Anisotropy});
        m.setScalar(ParamId::AnisotropyStrength, 1.0f);
        m.setScalar(ParamId::AnisotropyRotation, 0.0f);
    }
    pruneImages(plan);
    for (const std::string& name : baked.inputs.unbakeable)
        warnings.push_back("graph: drives " + name +
                           ", which no exported texture carries; the parameter's own value is "
                           "exported instead");
    if (clamped > 0)
        warnings.push_back(std::to_string(clamped) +
                           " baked values above 1 clamped to 1: the images are 8-bit");
    return m;
}

} // namespace velvet
