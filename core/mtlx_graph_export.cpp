// Velvet graph nodes as MaterialX 1.39 standard-library nodes (MaterialX Specification v1.39,
// "Standard Source Nodes" and "Standard Operator Nodes"). Only exact counterparts are written:
//   constant.float / constant.color -> constant (float / color3)
//   texture.image  -> image (color3; color4 + extract index 3 for its alpha), with its UV
//                     transform as uvtiling / uvoffset or a place2d (mtlx::mtlxPlacement)
//   math.add / math.multiply -> add / multiply (in1 = a, in2 = b)
//   math.mix       -> mix (bg = a, fg = b, mix = factor: bg (1 - mix) + fg mix, GLSL's mix)
//   math.clamp     -> clamp (in, low, high: the color3FA / float variants)
//   channel.combine -> combine3
// Velvet's math runs on colours and a float input reads a colour's luminance (graph_types.h);
// a float-typed subgraph is written as float nodes, which is exact when every value in it is a
// grey (the luminance of a grey is the grey, the Rec.709 weights summing to 1), so a non-grey
// value there makes the input unmappable. math.power is left out (Velvet clamps the base at 0,
// MaterialX's power does not), as are noise (other functions), fabric, atlas, levels, invert,
// split and normal nodes: an input they feed is baked.
#include "core/mtlx_graph_export.h"

#include "core/graph/graph.h"
#include "core/graph/node_catalogue.h"
#include "core/mtlx_shader_inputs.h"
#include "core/mtlx_values.h"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

namespace velvet::mtlx {
namespace {

using graph::Graph;
using graph::NodeId;
using graph::PortIndex;

std::string num(float f) {
    char text[32];
    const auto r = std::to_chars(text, text + sizeof text, f);
    return std::string(text, r.ptr);
}

std::string xmlEscape(std::string_view s) {
    std::string out;
    for (const char c : s) {
        if (c == '&')
            out += "&amp;";
        else if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c == '"')
            out += "&quot;";
        else
            out += c;
    }
    return out;
}

/// The MaterialX colour space of a texture node's "colorSpace" setting for file @p file; empty
/// when it has none. "" is the OCIO config's file rules (resources/ocio/config.ocio: EXR and HDR
/// linear, the rest sRGB); Raw is lin_rec709, the document's space, so nothing converts it.
std::optional<std::string> mxColorSpace(const std::string& velvet, const std::string& file) {
    if (velvet.empty()) {
        std::string ext = std::filesystem::path(file).extension().string();
        for (char& c : ext)
            c = char(std::tolower(static_cast<unsigned char>(c)));
        return (ext == ".exr" || ext == ".hdr") ? "lin_rec709" : "srgb_texture";
    }
    if (velvet == "sRGB texture")
        return "srgb_texture";
    if (velvet == "Linear Rec.709" || velvet == "Raw")
        return "lin_rec709";
    if (velvet == "ACEScg")
        return "acescg";
    return std::nullopt;
}

/// Writes the nodes upstream of one output, typed float or color3; nullopt where a node has no
/// exact counterpart.
class Emitter {
public:
    Emitter(const Graph& g, std::string base) : m_g(g), m_base(std::move(base)) {}

    std::optional<std::string> emit(NodeId id, PortIndex port, bool colour) {
        const std::string key =
            std::to_string(id) + "/" + std::to_string(port) + (colour ? "c" : "f");
        if (auto it = done.find(key); it != done.end())
            return it->second;
        const graph::Node* n = m_g.node(id);
        if (!n || m_depth >= 256)
            return std::nullopt;
        ++m_depth;
        std::optional<std::string> r = build(*n, port, colour);
        --m_depth;
        if (r)
            done[key] = *r;
        return r;
    }
    /// The value or connection of input @p port of @p n, as an <input> line.
    std::optional<std::string> input(const graph::Node& n, const char* mxName, const char* port,
                                     bool colour) {
        const int index = n.type->inputIndex(port);
        if (index < 0)
            return std::nullopt;
        const std::string type = colour ? "color3" : "float";
        const std::string head =
            "      <input name=\"" + std::string(mxName) + "\" type=\"" + type + "\"";
        if (const graph::Connection* c = m_g.connectionTo(n.id, PortIndex(index))) {
            const std::optional<std::string> up = emit(c->outNode, c->outPort, colour);
            if (!up)
                return std::nullopt;
            return head + " nodename=\"" + *up + "\" />\n";
        }
        const glm::vec4 v = n.inputValues[size_t(index)];
        const bool scalarPort = n.type->inputs[size_t(index)].type == graph::PortType::Float;
        if (colour)
            return scalarPort ? head + " value=\"" + num(v.x) + ", " + num(v.x) + ", " + num(v.x) +
                                    "\" />\n"
                              : head + " value=\"" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) +
                                    "\" />\n";
        if (!scalarPort && (v.y != v.x || v.z != v.x))
            return std::nullopt; // a colour read as a float: its luminance, not one of its values
        return head + " value=\"" + num(v.x) + "\" />\n";
    }

    std::string xml;
    std::vector<std::pair<NodeId, std::string>> images; ///< node, file name beside the .mtlx
    std::map<std::string, std::string> done;            ///< node/port/type -> written name

private:
    std::optional<std::string> node(const std::string& category, const std::string& name,
                                    bool colour, std::vector<std::optional<std::string>> inputs,
                                    const std::string& type = {}) {
        std::string text = "    <" + category + " name=\"" + name + "\" type=\"" +
                           (type.empty() ? (colour ? "color3" : "float") : type) + "\">\n";
        for (const auto& i : inputs) {
            if (!i)
                return std::nullopt;
            text += *i;
        }
        xml += text + "    </" + category + ">\n";
        return name;
    }

    std::optional<std::string> build(const graph::Node& n, PortIndex port, bool colour) {
        const std::string t(n.type->id);
        const std::string name = "n" + std::to_string(n.id) + "_" + (colour ? "c" : "f");
        if (t == "constant.float" || t == "constant.color")
            return node("constant", name, colour,
                        {input(n, "value", t == "constant.float" ? "value" : "color", colour)});
        if (t == "math.add" || t == "math.multiply")
            return node(t == "math.add" ? "add" : "multiply", name, colour,
                        {input(n, "in1", "a", colour), input(n, "in2", "b", colour)});
        if (t == "math.mix")
            return node("mix", name, colour,
                        {input(n, "bg", "a", colour), input(n, "fg", "b", colour),
                         input(n, "mix", "factor", false)});
        if (t == "math.clamp")
            return node("clamp", name, colour,
                        {input(n, "in", "value", colour), input(n, "low", "min", false),
                         input(n, "high", "max", false)});
        if (t == "channel.combine" && colour)
            return node("combine3", name, true,
                        {input(n, "in1", "r", false), input(n, "in2", "g", false),
                         input(n, "in3", "b", false)});
        if (t == "texture.image")
            return image(n, port, colour);
        return std::nullopt;
    }

    /// An image node: its colour as color3, its alpha (port 1) as extract 3 of a color4.
    std::optional<std::string> image(const graph::Node& n, PortIndex port, bool colour) {
        if ((port == 0) != colour)
            return std::nullopt; // colour read as a float (luminance) or alpha splat to a colour
        const graph::NodeType& type = *n.type;
        for (const char* p : {"uv", "scale", "offset", "rotation"})
            if (const graph::Connection* c = m_g.connectionTo(n.id, PortIndex(type.inputIndex(p))))
                if (std::string_view(p) != "uv" ||
                    m_g.node(c->outNode)->type->id != std::string_view("input.uv"))
                    return std::nullopt;
        const std::string file = n.settings[size_t(type.settingIndex("file"))];
        const std::optional<std::string> space =
            mxColorSpace(n.settings[size_t(type.settingIndex("colorSpace"))], file);
        if (file.empty() || !space)
            return std::nullopt;
        const std::string mxType = colour ? "color3" : "color4";
        const std::string name = "image" + std::to_string(n.id) + "_" + mxType;
        const std::string fileName = m_base + "_graph" + std::to_string(n.id) +
                                     std::filesystem::path(file).extension().string();
        const auto value = [&](const char* p) { return n.inputValues[size_t(type.inputIndex(p))]; };
        const MtlxPlacement place = mtlxPlacement(glm::vec2(value("scale")),
                                                  glm::vec2(value("offset")), value("rotation").x);
        std::vector<std::optional<std::string>> in{
            "      <input name=\"file\" type=\"filename\" value=\"" + xmlEscape(fileName) +
            "\" colorspace=\"" + *space + "\" />\n"};
        auto vec2 = [](const char* name, glm::vec2 v) {
            return std::optional<std::string>("      <input name=\"" + std::string(name) +
                                              "\" type=\"vector2\" value=\"" + num(v.x) + ", " +
                                              num(v.y) + "\" />\n");
        };
        if (place.place) { // as core/mtlx_export.cpp writes a slot's rotated placement
            xml += "    <place2d name=\"place2d_" + name + "\" type=\"vector2\">\n" +
                   *vec2("scale", place.place->scale) +
                   "      <input name=\"rotate\" type=\"float\" value=\"" +
                   num(place.place->rotate) + "\" />\n    </place2d>\n";
            in.push_back("      <input name=\"texcoord\" type=\"vector2\" nodename=\"place2d_" +
                         name + "\" />\n");
        } else {
            in.push_back(vec2("uvtiling", place.tiling));
        }
        in.push_back(vec2("uvoffset", place.offset));
        node("image", name, colour, in, mxType);
        images.emplace_back(n.id, fileName);
        if (colour)
            return name;
        return node("extract", name + "_a", false,
                    {"      <input name=\"in\" type=\"color4\" nodename=\"" + name + "\" />\n",
                     std::string("      <input name=\"index\" type=\"integer\" value=\"3\" />\n")});
    }

    const Graph& m_g;
    std::string m_base;
    int m_depth = 0;
};

/// The output input of @p material's graph that parameter @p p's shader input maps to, when
/// it is one the MaterialX shader reads as exactly the parameter.
std::string outputName(ParamId p) {
    const int port = graph::outputInputForParam(p);
    if (port < 0)
        return {};
    return std::string(graph::findNodeType(graph::kOutputTypeId)->inputs[size_t(port)].name);
}

/// Emits every mappable driven input into @p e; returns output input -> top node name.
std::map<std::string, std::string> emitAll(const Material& m, const std::string& shaderId,
                                           Emitter& e) {
    std::map<std::string, std::string> tops;
    if (!m.graph)
        return tops;
    const Graph& g = *m.graph;
    const NodeId out = g.outputNode();
    for (const auto& [mxName, target] : targetsOf(shaderId)) {
        // Normal inputs carry a scale, occlusion a strength, and gltf_pbr's sheen_color is
        // weight x colour: none is the parameter alone.
        if (target.normal || target.slot == TextureSlot::Occlusion ||
            (shaderId == "gltf_pbr" && target.param == ParamId::SheenColor))
            continue;
        if (target.slot != TextureSlot::Count && !m.texture(target.slot).empty())
            continue; // Velvet multiplies the graph's value by the slot's texture
        const std::string name = outputName(target.param);
        const int port = graph::outputInputForParam(target.param);
        const graph::Connection* c = name.empty() ? nullptr : g.connectionTo(out, PortIndex(port));
        if (!c || tops.count(name))
            continue;
        const bool colour = paramMeta(target.param).type == ParamType::Color;
        const std::string saved = e.xml;
        const auto images = e.images;
        const auto done = e.done;
        const std::optional<std::string> top = e.emit(c->outNode, c->outPort, colour);
        if (!top) { // keep no half-written subgraph
            e.xml = saved;
            e.images = images;
            e.done = done;
            continue;
        }
        // The material output clamps to the parameter's range (node_catalogue.cpp's
        // outputSnippet); MaterialX's shaders take what they get, so the clamp is written.
        const ParamMeta& meta = paramMeta(target.param);
        const std::string type = colour ? "color3" : "float";
        const std::string clampName = "clamp_" + name;
        e.xml += "    <clamp name=\"" + clampName + "\" type=\"" + type + "\">\n" +
                 "      <input name=\"in\" type=\"" + type + "\" nodename=\"" + *top + "\" />\n" +
                 "      <input name=\"low\" type=\"float\" value=\"" + num(meta.min) + "\" />\n" +
                 "      <input name=\"high\" type=\"float\" value=\"" + num(meta.max) +
                 "\" />\n    </clamp>\n";
        e.xml += "    <output name=\"out_" + name + "\" type=\"" + type + "\" nodename=\"" +
                 clampName + "\" />\n";
        tops[name] = "out_" + name;
    }
    return tops;
}

} // namespace

std::set<std::string> mappableGraphInputs(const Material& material, const std::string& shaderId) {
    std::set<std::string> names;
    if (!material.graph)
        return names;
    Emitter e(*material.graph, "x");
    for (const auto& [name, output] : emitAll(material, shaderId, e))
        names.insert(name);
    return names;
}

bool exportGraph(const Material& material, std::string_view baseName, const std::string& shaderId,
                 GraphExport& out, std::string* error) {
    out = {};
    if (!material.graph)
        return true;
    const std::string base(baseName);
    Emitter e(*material.graph, base);
    out.outputs = emitAll(material, shaderId, e);
    if (out.outputs.empty())
        return true;
    out.name = "NG_" + base;
    for (char& c : out.name)
        if (c == '-')
            c = '_';
    out.xml = "  <nodegraph name=\"" + out.name + "\">\n" + e.xml + "  </nodegraph>\n";
    for (const auto& [id, fileName] : e.images) {
        const graph::Node* n = material.graph->node(id);
        const std::string file = n->settings[size_t(n->type->settingIndex("file"))];
        std::ifstream in(file, std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        if (!in) {
            if (error)
                *error =
                    "graph node " + std::to_string(id) + " (Image texture): cannot read " + file;
            return false;
        }
        out.files.push_back({fileName, bytes.str()});
    }
    return true;
}

} // namespace velvet::mtlx
