// MaterialX 1.39 export. References: the MaterialX Specification v1.39 (document structure,
// `image`, `extract`, `multiply`, `mix`, `convert`, `normalmap`), the Physically Based Shading
// Nodes document (standard_surface, open_pbr_surface, gltf_pbr), and MaterialX's own
// translation graph standard_surface_to_gltf_pbr (libraries/bxdf/translation), whose mapping
// this inverts: base_color x base, metallic = metalness, roughness = specular_roughness,
// sheen_color x sheen, clearcoat = coat, emissive = emission_color x emission.
#include "core/mtlx_export.h"

#include "core/gltf_textures.h"
#include "core/graph/graph.h"
#include "core/graph/node_catalogue.h"
#include "core/mapping_warnings.h"
#include "core/mtlx_graph_export.h"
#include "core/mtlx_shader_inputs.h"
#include "core/mtlx_values.h"

#include <array>
#include <charconv>
#include <cmath>
#include <glm/trigonometric.hpp>
#include <map>
#include <set>

namespace velvet {
namespace {

constexpr std::array<std::string_view, size_t(MtlxShader::Count)> kShaderIds{
    "standard_surface", "open_pbr_surface", "gltf_pbr"};

std::string num(float f) {
    char text[32];
    const auto r = std::to_chars(text, text + sizeof text, f);
    return std::string(text, r.ptr);
}

std::string vec3Text(glm::vec3 v) {
    return num(v.x) + ", " + num(v.y) + ", " + num(v.z);
}

/// XML attribute text (XML 1.0 section 2.4: &, <, > and quotes escaped).
std::string xmlEscape(std::string_view s) {
    std::string out;
    for (const char c : s) {
        switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        case '\'':
            out += "&apos;";
            break;
        default:
            out += c;
        }
    }
    return out;
}

struct MxInput {
    std::string name, type, value, nodename, colorspace;
    std::string nodegraph, output; ///< a nodegraph's output (core/mtlx_graph_export.h)
};
struct MxNode {
    std::string category, name, type;
    std::vector<MxInput> inputs;
    std::string doc;
};

/// The document's nodes, built from the material and its texture plan.
class Builder {
public:
    Builder(const GltfTexturePlan& plan, std::string base)
        : m_plan(plan), m_base(std::move(base)) {}

    bool has(TextureSlot slot) const { return m_plan.uses[size_t(slot)].has_value(); }

    /// A float input: @p factor, times channel @p channel of @p slot's texture when it has one.
    MxInput scalar(const std::string& name, float factor, TextureSlot slot, int channel) {
        if (!has(slot))
            return {name, "float", num(factor), {}, {}};
        std::string source = extract(slot, channel);
        if (factor != 1.0f)
            source = multiply(name, "float", source, num(factor));
        return {name, "float", {}, source, {}};
    }
    MxInput scalar(const std::string& name, float value) {
        return {name, "float", num(value), {}, {}};
    }
    /// A colour input: @p factor, times @p slot's RGB (an sRGB image) when it has one.
    MxInput color(const std::string& name, glm::vec3 factor, TextureSlot slot) {
        if (!has(slot))
            return {name, "color3", vec3Text(factor), {}, {}};
        std::string source = image(slot, "color3");
        if (factor != glm::vec3(1.0f))
            source = multiply(name, "color3", source, vec3Text(factor));
        return {name, "color3", {}, source, {}};
    }
    /// A normal input from @p slot's tangent-space map through `normalmap`, or nothing.
    std::optional<MxInput> normal(const std::string& name, TextureSlot slot, float scale) {
        if (!has(slot))
            return std::nullopt;
        MxNode n{"normalmap", "normalmap_" + name, "vector3", {}};
        n.inputs.push_back({"in", "vector3", {}, image(slot, "vector3"), {}});
        n.inputs.push_back({"scale", "float", num(scale), {}, {}});
        m_nodes.push_back(n);
        return MxInput{name, "vector3", {}, n.name, {}};
    }
    /// Base colour alpha (A of the sRGB image, linear in MaterialX as in glTF).
    std::string alpha() {
        MxNode e{"extract", "alpha", "float", {}};
        e.inputs.push_back({"in", "color4", {}, image(TextureSlot::BaseColor, "color4"), {}});
        e.inputs.push_back({"index", "integer", "3", {}, {}});
        m_nodes.push_back(e);
        return e.name;
    }
    /// gltf_pbr's occlusion: 1 + strength (texel - 1), i.e. mix(1, texel, strength).
    std::optional<MxInput> occlusion(const std::string& name, float strength) {
        if (!has(TextureSlot::Occlusion))
            return std::nullopt;
        std::string source = extract(TextureSlot::Occlusion, 0);
        if (strength != 1.0f) {
            MxNode mix{"mix", "mix_" + name, "float", {}};
            mix.inputs.push_back({"fg", "float", {}, source, {}});
            mix.inputs.push_back({"bg", "float", "1", {}, {}});
            mix.inputs.push_back({"mix", "float", num(strength), {}, {}});
            m_nodes.push_back(mix);
            source = mix.name;
        }
        return MxInput{name, "float", {}, source, {}};
    }
    std::string convertToColor(const std::string& source) {
        MxNode c{"convert", "convert_" + source, "color3", {}};
        c.inputs.push_back({"in", "float", {}, source, {}});
        m_nodes.push_back(c);
        return c.name;
    }

    std::vector<MxNode>& nodes() { return m_nodes; }
    /// Images referenced, by plan index (only those are written).
    const std::set<int>& usedImages() const { return m_used; }
    std::string imageFile(int index) const {
        return m_base + "_" + m_plan.images[size_t(index)].label + ".png";
    }

private:
    /// An `image` node reading @p slot's image as @p type. Colour types are tagged
    /// srgb_texture (the PNG holds sRGB-encoded values), vector types are data and are not
    /// colour-transformed (MaterialX Specification, "Color Spaces").
    std::string image(TextureSlot slot, const std::string& type) {
        const GltfTextureUse& use = *m_plan.uses[size_t(slot)];
        const int index = use.image;
        const std::string uvKey = use.transformed ? mxUvKey(use) : std::string();
        const std::string key = std::to_string(index) + "/" + type + uvKey;
        if (auto it = m_images.find(key); it != m_images.end())
            return it->second;
        m_used.insert(index);
        std::string name = "image_" + m_plan.images[size_t(index)].label + "_" + type;
        if (use.transformed) // one image node per UV mapping of the same file
            name += "_" + std::string(textureSlotMeta(slot).id);
        MxNode n{"image", name, type, {}};
        const bool colour = type.rfind("color", 0) == 0;
        n.inputs.push_back(
            {"file", "filename", imageFile(index), {}, colour ? "srgb_texture" : ""});
        if (use.transformed) {
            // The image node's own placement, uv * uvtiling + uvoffset in MaterialX's UV space
            // (v up from the bottom row, MaterialX Specification "Texture nodes"), and for a
            // rotation a place2d on its texcoord (core/mtlx_values.h derives both).
            const mtlx::MtlxPlacement p =
                mtlx::mtlxPlacement(use.scale, use.offset, -glm::degrees(use.rotation));
            if (p.place) {
                MxNode place{"place2d", "place2d_" + name, "vector2", {}};
                place.inputs.push_back({"scale",
                                        "vector2",
                                        num(p.place->scale.x) + ", " + num(p.place->scale.y),
                                        {},
                                        {}});
                place.inputs.push_back({"rotate", "float", num(p.place->rotate), {}, {}});
                m_nodes.push_back(place);
                n.inputs.push_back({"texcoord", "vector2", {}, place.name, {}});
            } else {
                n.inputs.push_back(
                    {"uvtiling", "vector2", num(p.tiling.x) + ", " + num(p.tiling.y), {}, {}});
            }
            n.inputs.push_back(
                {"uvoffset", "vector2", num(p.offset.x) + ", " + num(p.offset.y), {}, {}});
        }
        m_nodes.push_back(n);
        return m_images[key] = n.name;
    }

    static std::string mxUvKey(const GltfTextureUse& u) {
        return "/" + num(u.scale.x) + "," + num(u.scale.y) + "," + num(u.offset.x) + "," +
               num(u.offset.y) + "," + num(u.rotation);
    }
    std::string extract(TextureSlot slot, int channel) {
        const std::string source = image(slot, "vector4");
        const std::string name = source + "_" + "rgba"[channel];
        for (const MxNode& n : m_nodes)
            if (n.name == name)
                return name;
        MxNode e{"extract", name, "float", {}};
        e.inputs.push_back({"in", "vector4", {}, source, {}});
        e.inputs.push_back({"index", "integer", std::to_string(channel), {}, {}});
        m_nodes.push_back(e);
        return name;
    }
    std::string multiply(const std::string& input, const std::string& type,
                         const std::string& source, const std::string& factor) {
        MxNode n{"multiply", "multiply_" + input, type, {}};
        n.inputs.push_back({"in1", type, {}, source, {}});
        n.inputs.push_back({"in2", type, factor, {}, {}});
        m_nodes.push_back(n);
        return n.name;
    }

    const GltfTexturePlan& m_plan;
    std::string m_base;
    std::vector<MxNode> m_nodes;
    std::map<std::string, std::string> m_images;
    std::set<int> m_used;
};

/// A MaterialX name ([A-Za-z_][A-Za-z0-9_]*, MaterialX Specification "Names") from a stem.
std::string mxName(std::string_view prefix, std::string_view stem) {
    std::string s(prefix);
    for (const char c : stem)
        s += (c == '-') ? '_' : c;
    return s;
}

/// The inputs of @p shader for @p m; the anisotropy inputs, constants in every shader, are
/// @p anisotropy's (its strength, rotation and roughness).
std::vector<MxInput> shaderInputs(MtlxShader shader, const Material& m, Builder& b,
                                  std::vector<std::string>& warnings, const Material& anisotropy) {
    using P = ParamId;
    using S = TextureSlot;
    std::vector<MxInput> in;
    auto add = [&](std::optional<MxInput> i) {
        if (i)
            in.push_back(std::move(*i));
    };
    const float sheen = m.scalar(P::SheenWeight);
    // KHR_materials_anisotropy, written only when on (docs/interchange.md): standard_surface and
    // open_pbr_surface take the ratio of their alphas (mtlx_shader_inputs.h), standard_surface's
    // rotation is a fraction of a turn in [0, 1), gltf_pbr's is radians as glTF's.
    const float aniso = anisotropy.scalar(P::AnisotropyStrength);
    const float rotation = anisotropy.scalar(P::AnisotropyRotation);
    const float mxAniso = mtlx::strengthToMtlxAnisotropy(aniso, anisotropy.scalar(P::Roughness));
    switch (shader) {
    case MtlxShader::StandardSurface:
        add(b.scalar("base", 1.0f));
        add(b.color("base_color", m.color(P::BaseColor), S::BaseColor));
        add(b.scalar("metalness", m.scalar(P::Metallic), S::MetallicRoughness, 2));
        add(b.scalar("specular", m.scalar(P::SpecularWeight), S::Specular, 3));
        add(b.color("specular_color", m.color(P::SpecularColor), S::SpecularColor));
        add(b.scalar("specular_roughness", m.scalar(P::Roughness), S::MetallicRoughness, 1));
        add(b.scalar("specular_IOR", m.scalar(P::Ior)));
        add(b.scalar("coat", m.scalar(P::ClearcoatWeight), S::Clearcoat, 0));
        add(b.scalar("coat_roughness", m.scalar(P::ClearcoatRoughness), S::ClearcoatRoughness, 1));
        add(b.scalar("coat_IOR", 1.5f)); // KHR_materials_clearcoat's fixed coat IOR
        add(b.scalar("sheen", sheen));
        add(b.color("sheen_color", m.color(P::SheenColor), S::SheenColor));
        add(b.scalar("sheen_roughness", m.scalar(P::SheenRoughness), S::SheenRoughness, 3));
        add(b.scalar("emission", m.scalar(P::EmissiveStrength)));
        add(b.color("emission_color", m.color(P::EmissiveColor), S::Emissive));
        add(b.normal("normal", S::Normal, m.scalar(P::NormalScale)));
        add(b.normal("coat_normal", S::ClearcoatNormal, m.scalar(P::ClearcoatNormalScale)));
        if (aniso > 0.0f) {
            add(b.scalar("specular_anisotropy", mxAniso));
            const float turns = rotation / 360.0f;
            add(b.scalar("specular_rotation", turns - std::floor(turns)));
        }
        break;
    case MtlxShader::OpenPbrSurface:
        add(b.scalar("base_weight", 1.0f));
        add(b.color("base_color", m.color(P::BaseColor), S::BaseColor));
        add(b.scalar("base_metalness", m.scalar(P::Metallic), S::MetallicRoughness, 2));
        add(b.scalar("specular_weight", m.scalar(P::SpecularWeight), S::Specular, 3));
        add(b.color("specular_color", m.color(P::SpecularColor), S::SpecularColor));
        add(b.scalar("specular_roughness", m.scalar(P::Roughness), S::MetallicRoughness, 1));
        add(b.scalar("specular_ior", m.scalar(P::Ior)));
        add(b.scalar("coat_weight", m.scalar(P::ClearcoatWeight), S::Clearcoat, 0));
        add(b.scalar("coat_roughness", m.scalar(P::ClearcoatRoughness), S::ClearcoatRoughness, 1));
        add(b.scalar("coat_ior", 1.5f)); // OpenPBR's default is 1.6; glTF's coat has 1.5
        add(b.scalar("fuzz_weight", sheen));
        add(b.color("fuzz_color", m.color(P::SheenColor), S::SheenColor));
        add(b.scalar("fuzz_roughness", m.scalar(P::SheenRoughness), S::SheenRoughness, 3));
        add(b.scalar("emission_luminance", m.scalar(P::EmissiveStrength)));
        add(b.color("emission_color", m.color(P::EmissiveColor), S::Emissive));
        add(b.normal("geometry_normal", S::Normal, m.scalar(P::NormalScale)));
        add(b.normal("geometry_coat_normal", S::ClearcoatNormal,
                     m.scalar(P::ClearcoatNormalScale)));
        if (aniso > 0.0f) {
            add(b.scalar("specular_roughness_anisotropy", mxAniso));
            if (rotation != 0.0f)
                warnings.push_back(std::string(paramMeta(P::AnisotropyRotation).id) +
                                   ": open_pbr_surface has no rotation input (its anisotropy "
                                   "follows geometry_tangent); not exported");
        }
        break;
    case MtlxShader::GltfPbr:
        add(b.color("base_color", m.color(P::BaseColor), S::BaseColor));
        add(b.scalar("metallic", m.scalar(P::Metallic), S::MetallicRoughness, 2));
        add(b.scalar("roughness", m.scalar(P::Roughness), S::MetallicRoughness, 1));
        add(b.normal("normal", S::Normal, m.scalar(P::NormalScale)));
        add(b.occlusion("occlusion", m.scalar(P::OcclusionStrength)));
        add(b.scalar("specular", m.scalar(P::SpecularWeight), S::Specular, 3));
        add(b.color("specular_color", m.color(P::SpecularColor), S::SpecularColor));
        add(b.scalar("ior", m.scalar(P::Ior)));
        add(b.color("sheen_color", sheen * m.color(P::SheenColor), S::SheenColor));
        add(b.scalar("sheen_roughness", m.scalar(P::SheenRoughness), S::SheenRoughness, 3));
        add(b.scalar("clearcoat", m.scalar(P::ClearcoatWeight), S::Clearcoat, 0));
        add(b.scalar("clearcoat_roughness", m.scalar(P::ClearcoatRoughness), S::ClearcoatRoughness,
                     1));
        add(b.normal("clearcoat_normal", S::ClearcoatNormal, m.scalar(P::ClearcoatNormalScale)));
        add(b.color("emissive", m.color(P::EmissiveColor), S::Emissive));
        add(b.scalar("emissive_strength", m.scalar(P::EmissiveStrength)));
        if (aniso > 0.0f) {
            add(b.scalar("anisotropy_strength", aniso));
            add(b.scalar("anisotropy_rotation", glm::radians(rotation)));
        }
        break;
    case MtlxShader::Count:
        break;
    }
    const std::string id(kShaderIds[size_t(shader)]);
    if (b.has(S::Anisotropy))
        warnings.push_back("textures.anisotropy: " + id +
                           " has no anisotropy direction input; not exported (the strength and "
                           "rotation are)");
    if (shader != MtlxShader::GltfPbr && b.has(S::Occlusion))
        warnings.push_back("textures.occlusion: " + id +
                           " has no occlusion input (ambient occlusion is the renderer's); "
                           "not exported (gltf_pbr has one)");
    return in;
}

/// The mean of channel @p c of @p image.
float meanChannel(const Image& image, int c) {
    double sum = 0.0;
    for (size_t i = size_t(c); i < image.pixels.size(); i += size_t(image.channels))
        sum += image.pixels[i];
    return float(sum / double(size_t(image.width) * size_t(image.height)));
}

/// What the constant anisotropy inputs are written from: the material's own strength, rotation
/// and roughness, or, where the graph drives them and they were baked into textures (which no
/// shader's anisotropy input reads: its direction texture is not exported either), their means
/// over the baked maps, with a warning. The rotation is the parameter's (the bake turns the
/// direction by it, which MaterialX does not read).
Material anisotropyOf(const Material& source, const BakedMaterialMaps* baked,
                      std::vector<std::string>& warnings) {
    Material m = source;
    if (!baked)
        return m;
    const bool strength =
        baked->inputs.driven[size_t(BakedMap::Anisotropy)] && !baked->maps.anisotropy.empty();
    const bool roughness = baked->inputs.driven[size_t(BakedMap::Orm)] && !baked->maps.orm.empty();
    if (strength)
        m.setScalar(ParamId::AnisotropyStrength, meanChannel(baked->maps.anisotropy, 2));
    if (roughness)
        m.setScalar(ParamId::Roughness, meanChannel(baked->maps.orm, 1));
    if ((strength || roughness) && m.scalar(ParamId::AnisotropyStrength) > 0.0f)
        warnings.push_back(
            "graph: the anisotropy inputs are constants in MaterialX; written from the baked "
            "maps' mean anisotropy strength (" +
            num(m.scalar(ParamId::AnisotropyStrength)) + ") and roughness (" +
            num(m.scalar(ParamId::Roughness)) + ")");
    return m;
}

} // namespace

std::string_view mtlxShaderId(MtlxShader shader) {
    return kShaderIds[size_t(shader)];
}

std::optional<MtlxShader> mtlxShaderFromId(std::string_view id) {
    for (size_t i = 0; i < kShaderIds.size(); ++i)
        if (kShaderIds[i] == id)
            return MtlxShader(i);
    return std::nullopt;
}

bool buildMtlx(const Material& source, std::string_view baseName, MtlxShader shader,
               TextureCache& textures, BuiltExport& out, std::string* error,
               const BakedMaterialMaps* baked) {
    out = {};
    GltfTexturePlan plan;
    if (!planGltfTextures(source, textures, plan, error, /*cutOutRegions=*/true))
        return false;
    std::vector<std::string> bakeWarnings;
    const std::string id(mtlxShaderId(shader));
    // The graph-driven inputs MaterialX's standard nodes express, as a nodegraph; the bake
    // (render/baked_export.cpp) left them out.
    mtlx::GraphExport graphOut;
    if (!mtlx::exportGraph(source, baseName, id, graphOut, error))
        return false;
    // The exported material: the baked inputs' factors neutral, their slots the bake's.
    Material material = baked ? applyBakedMaps(source, *baked, plan, bakeWarnings) : source;
    if (!baked && material.graph && !graphOut.outputs.empty()) {
        // The warning below names only what is neither a nodegraph output nor baked.
        graph::Graph rest = *material.graph;
        const graph::NodeType* output = graph::findNodeType(graph::kOutputTypeId);
        for (const graph::Connection& c : material.graph->connections())
            if (c.inNode == rest.outputNode() &&
                graphOut.outputs.count(std::string(output->inputs[c.inPort].name)))
                rest.disconnect(c);
        material.graph = graphOut.outputs.size() == graphDrivenInputs(source).size()
                             ? SharedGraph()
                             : SharedGraph(std::make_shared<const graph::Graph>(std::move(rest)));
    }
    // Grey images become RGBA as Velvet reads them (Image::rgba: RRR1), so every `extract`
    // index means the same channel whatever the file's channel count.
    for (GltfImage& image : plan.images)
        if (image.pixels.channels < 3) {
            Image rgba(image.pixels.width, image.pixels.height, 4);
            for (int y = 0; y < rgba.height; ++y)
                for (int x = 0; x < rgba.width; ++x) {
                    const glm::vec4 p = image.pixels.rgba(x, y);
                    std::copy(&p.x, &p.x + 4, rgba.at(x, y));
                }
            image.pixels = std::move(rgba);
        }
    const std::string base(baseName);
    out.warnings = mappingWarnings(material, "MaterialX " + id);
    out.warnings.insert(out.warnings.end(), bakeWarnings.begin(), bakeWarnings.end());
    out.warnings.insert(out.warnings.end(), plan.warnings.begin(), plan.warnings.end());

    Builder b(plan, base);
    std::vector<MxInput> inputs =
        shaderInputs(shader, material, b, out.warnings, anisotropyOf(source, baked, out.warnings));
    for (MxInput& in : inputs) { // the nodegraph's outputs replace the parameters' values
        const auto t = mtlx::targetsOf(id).find(in.name);
        if (t == mtlx::targetsOf(id).end() || t->second.normal)
            continue;
        const int port = graph::outputInputForParam(t->second.param);
        if (port < 0)
            continue;
        const std::string name(
            graph::findNodeType(graph::kOutputTypeId)->inputs[size_t(port)].name);
        if (const auto o = graphOut.outputs.find(name); o != graphOut.outputs.end())
            in = MxInput{in.name, in.type, {}, {}, {}, graphOut.name, o->second};
    }
    if (plan.alphaCutout) {
        const std::string alpha = b.alpha();
        if (shader == MtlxShader::GltfPbr) {
            inputs.push_back({"alpha", "float", {}, alpha, {}});
            inputs.push_back({"alpha_mode", "integer", "1", {}, {}}); // MASK
            inputs.push_back({"alpha_cutoff", "float", "0.5", {}, {}});
        } else {
            const bool sss = shader == MtlxShader::StandardSurface;
            inputs.push_back({sss ? "opacity" : "geometry_opacity",
                              sss ? "color3" : "float",
                              {},
                              sss ? b.convertToColor(alpha) : alpha,
                              {}});
            out.warnings.push_back("textures.baseColor: the alpha cut-out (below 0.5) becomes " +
                                   id + "'s opacity: it has no alpha cutoff (gltf_pbr has)");
        }
    }

    std::string xml = "<?xml version=\"1.0\"?>\n"
                      "<materialx version=\"1.39\" colorspace=\"lin_rec709\">\n";
    xml += "  <!-- Exported by Velvet; every mapping: docs/interchange.md -->\n";
    auto writeNode = [&xml](const MxNode& n) {
        xml += "  <" + n.category + " name=\"" + xmlEscape(n.name) + "\" type=\"" + n.type + "\"";
        if (!n.doc.empty()) // the material's own name: `doc` is allowed on every element
            xml += " doc=\"" + xmlEscape(n.doc) + "\"";
        xml += ">\n";
        for (const MxInput& i : n.inputs) {
            xml += "    <input name=\"" + i.name + "\" type=\"" + i.type + "\"";
            if (!i.nodegraph.empty())
                xml += " nodegraph=\"" + xmlEscape(i.nodegraph) + "\" output=\"" + i.output + "\"";
            else if (!i.nodename.empty())
                xml += " nodename=\"" + xmlEscape(i.nodename) + "\"";
            else
                xml += " value=\"" + xmlEscape(i.value) + "\"";
            if (!i.colorspace.empty())
                xml += " colorspace=\"" + i.colorspace + "\"";
            xml += " />\n";
        }
        xml += "  </" + n.category + ">\n";
    };
    xml += graphOut.xml;
    for (const MxNode& n : b.nodes())
        writeNode(n);
    const std::string shaderName = mxName("SR_", base);
    writeNode({id, shaderName, "surfaceshader", inputs});
    writeNode({"surfacematerial",
               mxName("M_", base),
               "material",
               {{"surfaceshader", "surfaceshader", {}, shaderName, {}}},
               material.name});
    xml += "</materialx>\n";

    for (const int index : b.usedImages()) {
        std::string png;
        if (!encodeImage(plan.images[size_t(index)].pixels, ".png", PixelFormat::UInt8, png, error))
            return false;
        out.files.push_back({b.imageFile(index), std::move(png)});
    }
    for (ExportFile& f : graphOut.files)
        out.files.push_back(std::move(f));
    out.files.push_back({base + ".mtlx", std::move(xml)});
    return true;
}

} // namespace velvet
