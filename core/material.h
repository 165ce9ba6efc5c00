#pragma once
/// @file material.h
/// A layered material: the glTF 2.0 metal-rough model with KHR_materials_clearcoat, _sheen,
/// _specular, _ior, _emissive_strength and _anisotropy, plus the BRDF term choices of the seed
/// documents. Values are addressed by ParamId; their metadata comes from paramMeta().

#include "core/param_meta.h"
#include "core/texture_ref.h"

#include <array>
#include <glm/vec3.hpp>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {

namespace graph {
class Graph;
}

/// A material's node graph (core/graph/graph.h), shared and immutable: copying a Material copies
/// a pointer, an edit makes a new graph. Compared by value (same nodes, values and links), so
/// Material keeps a defaulted ==. Empty: the material has no graph.
class SharedGraph {
public:
    SharedGraph() = default;
    explicit SharedGraph(std::shared_ptr<const graph::Graph> g) : m_graph(std::move(g)) {}
    /// Copies @p g (listeners are not copied).
    explicit SharedGraph(const graph::Graph& g);

    const graph::Graph* get() const { return m_graph.get(); }
    const graph::Graph* operator->() const { return m_graph.get(); }
    const graph::Graph& operator*() const { return *m_graph; }
    explicit operator bool() const { return m_graph != nullptr; }
    const std::shared_ptr<const graph::Graph>& pointer() const { return m_graph; }
    /// Both empty, or both set and equal as graphs.
    bool operator==(const SharedGraph& other) const;

private:
    std::shared_ptr<const graph::Graph> m_graph;
};

/// Every material parameter. The order is the order of panels, files and the GPU material table.
enum class ParamId : int {
    // Base lobe (glTF 2.0 pbrMetallicRoughness, KHR_materials_specular, _ior)
    BaseColor,
    Metallic,
    Roughness,
    SpecularWeight,
    SpecularColor,
    Ior,
    NormalScale,
    OcclusionStrength,
    // Emission (glTF emissiveFactor, KHR_materials_emissive_strength)
    EmissiveColor,
    EmissiveStrength,
    // Clearcoat lobe (KHR_materials_clearcoat)
    ClearcoatWeight,
    ClearcoatRoughness,
    ClearcoatNormalScale,
    // Sheen lobe (KHR_materials_sheen; colour = weight * colour on export)
    SheenWeight,
    SheenColor,
    SheenRoughness,
    // Anisotropy of the base specular lobe (KHR_materials_anisotropy; rotation in degrees)
    AnisotropyStrength,
    AnisotropyRotation,
    // BRDF term choices (seed documents; renderer issue implements each)
    Distribution,
    Visibility,
    Fresnel,
    Diffuse,
    SheenModel,
    Count
};
inline constexpr int kParamCount = static_cast<int>(ParamId::Count);

/// Normal distribution function D.
enum class Distribution : int { GGX, Beckmann, BlinnPhong };
/// Geometry / visibility term G or V.
enum class Visibility : int {
    SmithGGXSeparable,  ///< glTF 2.0 Appendix B form (default)
    SmithGGXCorrelated, ///< Heitz 2014 height-correlated, as Filament uses
    SchlickGGX,
    CookTorrance,
    Implicit,
    Neumann,
    Kelemen
};
/// Fresnel term F.
enum class Fresnel : int { Schlick, SchlickSphericalGaussian, ExactDielectric };
/// Diffuse term.
enum class Diffuse : int { Lambert, Burley };
/// Sheen model: Charlie D (Estevez & Kulla 2017) with one of three visibility terms.
enum class SheenModel : int { CharlieContyKulla, CharlieAshikhmin, CharlieNeubelt };

/// Metadata of every parameter, indexed by ParamId.
std::span<const ParamMeta> paramMetas();
/// Metadata of one parameter.
const ParamMeta& paramMeta(ParamId id);
/// The parameter whose JSON id is @p id ("lobes.base.roughness"), or ParamId::Count.
ParamId paramIdFromString(std::string_view id);

/// A material: name, parameter values, texture slots. Plain value type; compare with ==.
class Material {
public:
    /// A material with every parameter at its default.
    Material();

    std::string name = "Untitled";
    /// Free-form search words for the material library ("fabric", "metal", "glossy").
    std::vector<std::string> tags;

    float scalar(ParamId id) const { return m_values[index(id)].x; }
    glm::vec3 color(ParamId id) const { return m_values[index(id)]; }
    int choice(ParamId id) const { return static_cast<int>(m_values[index(id)].x); }
    /// Raw value (x holds scalars and choices). Used by generic code: panels, serializers.
    glm::vec3 value(ParamId id) const { return m_values[index(id)]; }

    /// Sets a value, clamped to the parameter's hard range (choices rounded to an index).
    void setValue(ParamId id, glm::vec3 v);
    void setScalar(ParamId id, float v) { setValue(id, glm::vec3(v)); }
    void setColor(ParamId id, glm::vec3 c) { setValue(id, c); }
    void setChoice(ParamId id, int i) { setValue(id, glm::vec3(static_cast<float>(i))); }
    /// Back to the metadata default.
    void resetValue(ParamId id);

    Distribution distribution() const {
        return static_cast<Distribution>(choice(ParamId::Distribution));
    }
    Visibility visibility() const { return static_cast<Visibility>(choice(ParamId::Visibility)); }
    Fresnel fresnel() const { return static_cast<Fresnel>(choice(ParamId::Fresnel)); }
    Diffuse diffuse() const { return static_cast<Diffuse>(choice(ParamId::Diffuse)); }
    SheenModel sheenModel() const { return static_cast<SheenModel>(choice(ParamId::SheenModel)); }

    const TextureRef& texture(TextureSlot slot) const { return m_textures[slotIndex(slot)]; }
    void setTexture(TextureSlot slot, TextureRef ref) {
        m_textures[slotIndex(slot)] = std::move(ref);
    }

    /// The node graph feeding the material's inputs (none by default). Its material output's
    /// connected inputs override the parameters in the G-buffer pass (graph_compiler.h).
    SharedGraph graph;

    bool operator==(const Material&) const = default;

private:
    static int index(ParamId id) { return static_cast<int>(id); }
    static int slotIndex(TextureSlot s) { return static_cast<int>(s); }
    std::array<glm::vec3, kParamCount> m_values{};
    std::array<TextureRef, kTextureSlotCount> m_textures{};
};

} // namespace velvet
