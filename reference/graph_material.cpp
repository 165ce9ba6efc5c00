#include "reference/graph_material.h"

#include "core/graph/graph.h"
#include "core/graph/graph_eval.h"
#include "core/texture_cache.h"

#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <map>

namespace velvet::reference {
namespace {

// Bilinear with repeat, as the viewport's graph textures sample (GL_REPEAT, GL_LINEAR at mip 0).
glm::vec4 bilinearRepeat(const Image& img, glm::vec2 uv) {
    const float fx = uv.x * img.width - 0.5f, fy = uv.y * img.height - 0.5f;
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    const float ax = fx - float(x0), ay = fy - float(y0);
    const auto at = [&](int x, int y) {
        x = ((x % img.width) + img.width) % img.width;
        y = ((y % img.height) + img.height) % img.height;
        return img.rgba(x, y);
    };
    return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), ax),
                    glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), ax), ay);
}

class CachedGraphTextures : public graph::GraphTextures {
public:
    std::map<graph::NodeId, std::shared_ptr<const Image>> images;
    glm::vec4 sample(graph::NodeId node, glm::vec2 uv) const override {
        const auto it = images.find(node);
        return it == images.end() || !it->second ? glm::vec4(1.0f)
                                                 : bilinearRepeat(*it->second, uv);
    }
    glm::ivec2 size(graph::NodeId node) const override {
        const auto it = images.find(node);
        return it == images.end() || !it->second
                   ? glm::ivec2(1)
                   : glm::ivec2(it->second->width, it->second->height);
    }
};

} // namespace

glm::vec3 anisotropyWorldDirection(glm::vec3 n, glm::vec4 tangent, const AnisotropyInputs& a) {
    // The tangent made orthogonal to the shading normal (Gram-Schmidt); the direction rotated
    // counter-clockwise, tangent toward bitangent (KHR_materials_anisotropy's mat2(c, s, -s, c)).
    glm::vec3 t = glm::vec3(tangent) - n * glm::dot(n, glm::vec3(tangent));
    if (glm::dot(t, t) < 1e-12f) // no usable tangent: any unit vector orthogonal to n
        t = std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0))
                                 : glm::cross(n, glm::vec3(0, 1, 0));
    t = glm::normalize(t);
    const glm::vec3 b = glm::cross(n, t) * (tangent.w < 0.0f ? -1.0f : 1.0f);
    glm::vec2 d = glm::dot(a.direction, a.direction) > 1e-12f ? glm::normalize(a.direction)
                                                              : glm::vec2(1.0f, 0.0f);
    const float r = glm::radians(a.rotationDeg), c = std::cos(r), sn = std::sin(r);
    d = glm::vec2(c * d.x - sn * d.y, sn * d.x + c * d.y);
    return glm::normalize(t * d.x + b * d.y);
}

struct GraphMaterial::Impl {
    CachedGraphTextures textures;
    std::unique_ptr<graph::GraphEvaluator> evaluator;
    // The material's own values, for lobes whose weight and colour the graph feeds separately.
    float sheenWeight = 0, emissionStrength = 0, normalScale = 1;
    glm::vec3 sheenColor{0}, emissionColor{0};
    int sheenWeightIn = -1, sheenColorIn = -1, emissionColorIn = -1, emissionStrengthIn = -1;
    int normalIn = -1, anisotropyDirectionIn = -1, occlusionIn = -1;
};

GraphMaterial::GraphMaterial(const Material& material, TextureCache& cache, Problems* problems)
    : m_impl(std::make_unique<Impl>()) {
    if (!material.graph)
        return;
    const graph::Graph& g = *material.graph;
    for (const auto& [id, node] : g.nodes()) {
        if (!node.type->samplesTexture)
            continue;
        const int fileIndex = node.type->settingIndex("file");
        const int spaceIndex = node.type->settingIndex("colorSpace");
        const std::string file = fileIndex >= 0 ? node.settings[size_t(fileIndex)] : "";
        if (file.empty())
            continue;
        const Texture t = cache.get(file, TextureUsage::Color,
                                    spaceIndex >= 0 ? node.settings[size_t(spaceIndex)] : "");
        if (problems)
            for (const Problem& p : t.problems)
                problems->items.push_back(p);
        m_impl->textures.images[id] = t.image;
    }
    m_impl->evaluator = std::make_unique<graph::GraphEvaluator>(g, &m_impl->textures);
    Impl& d = *m_impl;
    d.sheenWeight = material.scalar(ParamId::SheenWeight);
    d.sheenColor = material.color(ParamId::SheenColor);
    d.emissionStrength = material.scalar(ParamId::EmissiveStrength);
    d.emissionColor = material.color(ParamId::EmissiveColor);
    d.normalScale = material.scalar(ParamId::NormalScale);
    d.sheenWeightIn = graph::outputInputForParam(ParamId::SheenWeight);
    d.sheenColorIn = graph::outputInputForParam(ParamId::SheenColor);
    d.emissionColorIn = graph::outputInputForParam(ParamId::EmissiveColor);
    d.emissionStrengthIn = graph::outputInputForParam(ParamId::EmissiveStrength);
    if (const graph::NodeType* out = graph::findNodeType(graph::kOutputTypeId)) {
        d.normalIn = out->inputIndex("normal");
        d.anisotropyDirectionIn = out->inputIndex("anisotropyDirection");
        d.occlusionIn = out->inputIndex("occlusion");
    }
}

GraphMaterial::~GraphMaterial() = default;

bool GraphMaterial::active() const {
    return m_impl->evaluator && m_impl->evaluator->drivesMaterial();
}

void GraphMaterial::apply(glm::vec2 uv, brdf::Surface& s, glm::vec3& tangentNormal, bool& normalFed,
                          AnisotropyInputs* anisotropy, float* occlusion) const {
    if (!active())
        return;
    const Impl& d = *m_impl;
    const graph::GraphSample g = d.evaluator->evaluate(uv);
    const auto fed = [&](int input) -> const std::optional<glm::vec4>* {
        return input >= 0 && size_t(input) < g.outputInputs.size() && g.outputInputs[size_t(input)]
                   ? &g.outputInputs[size_t(input)]
                   : nullptr;
    };
    const auto scalar = [&](ParamId id, float& field) {
        if (const auto* v = fed(graph::outputInputForParam(id)))
            field = (**v).x;
    };
    const auto colour = [&](ParamId id, glm::vec3& field) {
        if (const auto* v = fed(graph::outputInputForParam(id)))
            field = glm::vec3(**v);
    };
    colour(ParamId::BaseColor, s.baseColor);
    scalar(ParamId::Metallic, s.metallic);
    scalar(ParamId::Roughness, s.roughness);
    scalar(ParamId::SpecularWeight, s.specularWeight);
    colour(ParamId::SpecularColor, s.specularColor);
    scalar(ParamId::Ior, s.ior);
    scalar(ParamId::SheenRoughness, s.sheenRoughness);
    scalar(ParamId::ClearcoatWeight, s.clearcoat);
    scalar(ParamId::ClearcoatRoughness, s.clearcoatRoughness);
    scalar(ParamId::AnisotropyStrength, s.anisotropyStrength);
    if (anisotropy) {
        scalar(ParamId::AnisotropyRotation, anisotropy->rotationDeg);
        if (const auto* v = fed(d.anisotropyDirectionIn))
            anisotropy->direction = glm::vec2(**v);
    }
    if (occlusion)
        if (const auto* v = fed(d.occlusionIn))
            *occlusion = (**v).x;
    if (fed(d.sheenWeightIn) || fed(d.sheenColorIn)) {
        const float w = fed(d.sheenWeightIn) ? (**fed(d.sheenWeightIn)).x : d.sheenWeight;
        const glm::vec3 c = fed(d.sheenColorIn) ? glm::vec3(**fed(d.sheenColorIn)) : d.sheenColor;
        s.sheenColor = w * c;
    }
    if (fed(d.emissionColorIn) || fed(d.emissionStrengthIn)) {
        const glm::vec3 c =
            fed(d.emissionColorIn) ? glm::vec3(**fed(d.emissionColorIn)) : d.emissionColor;
        const float k =
            fed(d.emissionStrengthIn) ? (**fed(d.emissionStrengthIn)).x : d.emissionStrength;
        s.emissive = glm::max(c * k, glm::vec3(0.0f));
    }
    if (const auto* n = fed(d.normalIn)) {
        float scale = d.normalScale;
        scalar(ParamId::NormalScale, scale);
        tangentNormal = glm::vec3(**n);
        tangentNormal.x *= scale;
        tangentNormal.y *= scale;
        normalFed = true;
    }
}

} // namespace velvet::reference
