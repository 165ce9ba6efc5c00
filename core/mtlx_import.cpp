// MaterialX 1.39 import. References: the MaterialX Specification v1.39 (document structure,
// inputs' value / nodename / nodegraph / output / interfacename, fileprefix, colorspace; the
// standard nodes image, extract, multiply, add, mix, clamp, power, normalmap, convert,
// texcoord, combine3, separate3, constant), and the Physically Based Shading Nodes document
// (standard_surface, open_pbr_surface, gltf_pbr). The inverse of core/mtlx_export.cpp; every
// mapping is tabled in docs/interchange.md ("Import").
#include "core/mtlx_import.h"

#include "core/graph/graph.h"
#include "core/import_text.h"
#include "core/mtlx_shader_inputs.h"
#include "core/mtlx_values.h"
#include "core/utf8_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <glm/trigonometric.hpp>
#include <map>
#include <optional>
#include <pugixml.hpp>
#include <set>

namespace velvet {
namespace {

namespace fs = std::filesystem;
using graph::Graph;
using graph::NodeId;

struct Failure {
    ImportProblem problem;
};

using S = TextureSlot;
using P = ParamId;
using mtlx::Target;
using mtlx::targetsOf;
using mtlx::velvetColorSpace;

using mtlx::parseNumbers;

class Reader {
public:
    explicit Reader(fs::path file) : m_file(std::move(file)) {}

    void load() {
        std::ifstream in(m_file, std::ios::binary);
        if (!in)
            fail(pugi::xml_node(), "cannot be read");
        m_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        const pugi::xml_parse_result r = m_doc.load_buffer(m_text.data(), m_text.size());
        if (!r)
            throw Failure{{ImportProblem::Kind::Malformed, lineOf(size_t(r.offset)),
                           std::string("broken XML: ") + r.description()}};
        // pugixml does not check UTF-8; a name read as bytes that are not text would make a
        // preset Velvet's JSON reader refuses (found by fuzz_mtlx). Declared encodings (latin1,
        // UTF-16) were converted to UTF-8 by pugixml already.
        if (r.encoding == pugi::encoding_utf8)
            if (const auto bad = firstNonText(m_text)) {
                char byte[8];
                std::snprintf(byte, sizeof byte, "0x%02X",
                              static_cast<unsigned char>(m_text[*bad]));
                throw Failure{{ImportProblem::Kind::Malformed, lineOf(*bad),
                               std::string("not UTF-8 text (byte ") + byte +
                                   "); declare the encoding in the XML declaration"}};
            }
        m_root = m_doc.child("materialx");
        if (!m_root)
            fail(m_doc.first_child(), "the root element is not <materialx>");
        const std::string version = m_root.attribute("version").value();
        if (version.rfind("1.3", 0) != 0)
            m_warnings.push_back("materialx version \"" + version +
                                 "\": read as 1.39 (Velvet reads 1.38 and 1.39)");
        const std::string cs = m_root.attribute("colorspace").value();
        if (!cs.empty() && cs != "lin_rec709")
            m_warnings.push_back("materialx colorspace \"" + cs +
                                 "\": colour values are read as lin_rec709 (not converted)");
        for (pugi::xml_node n : m_root.children("surfacematerial"))
            m_materials.push_back(n);
    }

    std::vector<std::string> names() const {
        std::vector<std::string> out;
        for (pugi::xml_node n : m_materials)
            out.emplace_back(n.attribute("name").value());
        return out;
    }

    void read(size_t index, ImportedMaterial& out) {
        const pugi::xml_node material = m_materials[index];
        Material& m = out.material;
        m = Material();
        m.name = material.attribute("doc").empty() ? material.attribute("name").value()
                                                   : material.attribute("doc").value();
        pugi::xml_node shaderRef = findInput(material, "surfaceshader");
        if (!shaderRef)
            fail(material, "has no surfaceshader input");
        const pugi::xml_node shader = resolve(shaderRef, pugi::xml_node());
        if (!shader)
            fail(shaderRef, "connects to nothing");
        m_shader = shader.name();
        const auto& targets = targetsOf(m_shader);
        if (targets.empty())
            fail(shader, "<" + m_shader +
                             ">: not a shader Velvet reads (standard_surface, open_pbr_surface, "
                             "gltf_pbr)");
        for (pugi::xml_node extra : material.children("input"))
            if (std::string(extra.attribute("name").value()) != "surfaceshader")
                m_warnings.push_back(where(extra) + "surfacematerial input \"" +
                                     extra.attribute("name").value() + "\" not mapped");
        m_material = &m;
        float baseWeight = 1.0f;
        float mxAniso = -1.0f; // standard_surface / open_pbr_surface: converted after the loop
        for (pugi::xml_node in : shader.children("input")) {
            const std::string name = in.attribute("name").value();
            const std::string label = m_shader + "." + name;
            if (readAnisotropy(in, name, label, mxAniso))
                continue;
            if (name == "base" || name == "base_weight") {
                baseWeight = constantScalar(in, label, 1.0f);
                continue;
            }
            if (name == "coat_IOR" || name == "coat_ior") {
                const float v = constantScalar(in, label, 1.5f);
                if (std::abs(v - 1.5f) > 1e-6f)
                    m_warnings.push_back(where(in) + label + " = " + std::to_string(v) +
                                         " not mapped: Velvet's coat has glTF's IOR 1.5");
                continue;
            }
            if (name == "alpha_mode" || name == "alpha_cutoff" || name == "opacity" ||
                name == "geometry_opacity" || name == "alpha") {
                if (!isDefaultAlpha(in, name))
                    m_warnings.push_back(where(in) + label +
                                         " not mapped: Velvet cuts out the base colour "
                                         "texture's alpha below 0.5, and has no opacity input");
                continue;
            }
            const auto t = targets.find(name);
            if (t == targets.end()) {
                m_warnings.push_back(where(in) + label + " not mapped (Velvet has no counterpart)");
                continue;
            }
            readInput(in, label, t->second);
        }
        mtlx::finishMaterial(m, m_shader, baseWeight, mxAniso,
                             m_graph && m_driven.count(P::BaseColor),
                             m_driven.count(P::SheenColor) > 0, m_warnings);
        if (m_graph)
            m.graph = SharedGraph(std::make_shared<const Graph>(std::move(*m_graph)));
        out.warnings = m_warnings;
    }

private:
    [[noreturn]] void fail(pugi::xml_node at, std::string message) const {
        throw Failure{{ImportProblem::Kind::Malformed,
                       at ? lineOf(size_t(at.offset_debug())) : std::string(),
                       (at && at.attribute("name") ? "<" + std::string(at.name()) + " name=\"" +
                                                         at.attribute("name").value() + "\">: "
                                                   : std::string()) +
                           message}};
    }
    std::string lineOf(size_t offset) const { return lineColumn(m_text, offset); }
    std::string where(pugi::xml_node n) const { return lineOf(size_t(n.offset_debug())) + ": "; }
    static pugi::xml_node findInput(pugi::xml_node node, const char* name) {
        return node.find_child_by_attribute("input", "name", name);
    }

    /// The node an input connects to (nodename in @p scope or the document; nodegraph + output;
    /// interfacename: the graph's own input, followed). Null for a plain value. Dangling names
    /// are malformed.
    pugi::xml_node resolve(pugi::xml_node in, pugi::xml_node scope, int hops = 0) {
        if (hops > 64) // graph inputs and outputs naming each other round in a circle
            fail(in, "connections loop through node graph inputs and outputs");
        if (const char* iface = in.attribute("interfacename").value(); *iface) {
            const pugi::xml_node graphInput = findInput(scope, iface);
            if (!scope || !graphInput)
                fail(in, "interfacename \"" + std::string(iface) +
                             "\" names no input of the "
                             "node graph");
            return resolve(graphInput, pugi::xml_node(), hops + 1); // graph inputs: from outside
        }
        if (const char* graphName = in.attribute("nodegraph").value(); *graphName) {
            const pugi::xml_node g = m_root.find_child_by_attribute("nodegraph", "name", graphName);
            if (!g)
                fail(in, "nodegraph \"" + std::string(graphName) + "\" does not exist");
            std::string output = in.attribute("output").value();
            pugi::xml_node out = output.empty()
                                     ? g.child("output")
                                     : g.find_child_by_attribute("output", "name", output.c_str());
            if (!out)
                fail(in,
                     "output \"" + output + "\" of nodegraph \"" + graphName + "\" does not exist");
            return resolve(out, g, hops + 1);
        }
        if (const char* nodeName = in.attribute("nodename").value(); *nodeName) {
            pugi::xml_node n;
            for (pugi::xml_node c : (scope ? scope : m_root).children())
                if (std::string(c.attribute("name").value()) == nodeName &&
                    std::string(c.name()) != "input" && std::string(c.name()) != "output")
                    n = c;
            if (!n)
                fail(in, "nodename \"" + std::string(nodeName) + "\" names no node");
            m_scopeOf[n.offset_debug()] = scope;
            return n;
        }
        return {};
    }

    /// KHR_materials_anisotropy's counterparts (docs/interchange.md): gltf_pbr's strength and
    /// radians map directly; standard_surface's rotation is a fraction of a turn, and its and
    /// open_pbr_surface's anisotropy (@p mxAniso) becomes a strength once the roughness is known.
    bool readAnisotropy(pugi::xml_node in, const std::string& name, const std::string& label,
                        float& mxAniso) {
        const bool gltf = m_shader == "gltf_pbr";
        if (gltf && name == "anisotropy_strength") {
            set(P::AnisotropyStrength, {constantScalar(in, label, 0.0f)}, in, label);
        } else if (gltf && name == "anisotropy_rotation") {
            const float deg = glm::degrees(constantScalar(in, label, 0.0f));
            m_material->setScalar(P::AnisotropyRotation, std::remainder(deg, 360.0f));
        } else if (m_shader == "standard_surface" && name == "specular_rotation") {
            const float deg = 360.0f * constantScalar(in, label, 0.0f);
            m_material->setScalar(P::AnisotropyRotation, std::remainder(deg, 360.0f));
        } else if ((m_shader == "standard_surface" && name == "specular_anisotropy") ||
                   (m_shader == "open_pbr_surface" && name == "specular_roughness_anisotropy")) {
            mxAniso = std::clamp(constantScalar(in, label, 0.0f), 0.0f, 1.0f);
        } else {
            return false;
        }
        return true;
    }

    float constantScalar(pugi::xml_node in, const std::string& label, float fallback) {
        if (resolve(in, pugi::xml_node())) {
            m_warnings.push_back(where(in) + label + ": a connection is not mapped; " +
                                 std::to_string(fallback) + " used");
            return fallback;
        }
        return value(in, 1, label)[0];
    }
    bool isDefaultAlpha(pugi::xml_node in, const std::string& name) {
        return mtlx::isDefaultAlpha(name, in.attribute("value").value(),
                                    in.attribute("nodename") || in.attribute("nodegraph"));
    }
    /// The value of a constant input: @p count numbers (a scalar is splat for colours).
    std::vector<float> value(pugi::xml_node in, size_t count, const std::string& label) {
        const std::string text = in.attribute("value").value();
        std::vector<float> v;
        if (const std::string problem = mtlx::constantValue(text, count, v); !problem.empty())
            fail(in, label + ": value \"" + text + "\" " + problem);
        return v;
    }
    void set(ParamId id, std::vector<float> v, pugi::xml_node in, const std::string& label) {
        mtlx::setParam(*m_material, id, v, where(in) + label, in.attribute("value").value(),
                       m_warnings);
    }

    /// One shader input: a constant, the export's patterns into a texture slot (image,
    /// extract of the slot's channel, × a constant factor, normalmap, gltf_pbr's occlusion
    /// mix), else the upstream nodes as a Velvet graph.
    void readInput(pugi::xml_node in, const std::string& label, const Target& t) {
        const size_t count = paramMeta(t.param).type == ParamType::Color ? 3 : 1;
        pugi::xml_node src = resolve(in, pugi::xml_node());
        if (!src) {
            if (!t.normal && t.slot != S::Occlusion)
                set(t.param, value(in, count, label), in, label);
            else if (t.slot == S::Occlusion && value(in, 1, label)[0] != 1.0f)
                m_warnings.push_back(where(in) + label +
                                     ": a constant occlusion is not mapped (Velvet's occlusion "
                                     "comes from a map)");
            return;
        }
        std::string category = src.name();
        if (t.normal && category == "normalmap") {
            pugi::xml_node image = resolve(findInput(src, "in"), m_scopeOf[src.offset_debug()]);
            if (image && std::string(image.name()) == "image") {
                if (pugi::xml_node s = findInput(src, "scale"))
                    set(t.param, value(s, 1, label + " scale"), s, label + " scale");
                fillSlot(image, t.slot, label);
                return;
            }
        }
        float factor = 1.0f;
        pugi::xml_node inner = src;
        if (category == "multiply" && !t.normal) { // texture x constant factor
            pugi::xml_node a = findInput(src, "in1"), b = findInput(src, "in2");
            const pugi::xml_node scope = m_scopeOf[src.offset_debug()];
            pugi::xml_node ra = a ? resolve(a, scope) : pugi::xml_node();
            pugi::xml_node rb = b ? resolve(b, scope) : pugi::xml_node();
            if (ra && b && !rb) {
                inner = ra;
                const std::vector<float> f = value(b, count, label + " factor");
                set(t.param, f, b, label);
                factor = 0.0f; // the factor is set
            } else if (rb && a && !ra) {
                inner = rb;
                set(t.param, value(a, count, label + " factor"), a, label);
                factor = 0.0f;
            }
        }
        if (t.slot == S::Occlusion && std::string(inner.name()) == "mix") { // mix(1, ao, strength)
            pugi::xml_node fg = findInput(inner, "fg"), mixIn = findInput(inner, "mix");
            pugi::xml_node rfg =
                fg ? resolve(fg, m_scopeOf[inner.offset_debug()]) : pugi::xml_node();
            if (rfg && mixIn && !resolve(mixIn, m_scopeOf[inner.offset_debug()])) {
                set(P::OcclusionStrength, value(mixIn, 1, label + " mix"), mixIn, label);
                inner = rfg;
                factor = 0.0f; // the strength is set
            }
        }
        const std::string ic = inner.name();
        if (t.slot != S::Count && !t.normal) {
            if (ic == "image" && count == 3) {
                fillSlot(inner, t.slot, label);
                if (factor != 0.0f)
                    m_material->setColor(t.param, glm::vec3(1.0f));
                return;
            }
            if (ic == "extract" && count == 1) {
                pugi::xml_node idx = findInput(inner, "index");
                pugi::xml_node image =
                    resolve(findInput(inner, "in"), m_scopeOf[inner.offset_debug()]);
                const int channel = idx ? int(value(idx, 1, label + " index")[0]) : 0;
                if (image && std::string(image.name()) == "image" && channel == t.channel) {
                    fillSlot(image, t.slot, label);
                    if (factor != 0.0f)
                        m_material->setScalar(t.param, 1.0f);
                    return;
                }
            }
        }
        // Anything else: the upstream nodes as a graph driving the material output's input.
        const int port = t.normal
                             ? graph::findNodeType(graph::kOutputTypeId)
                                   ->inputIndex(t.slot == S::Normal ? "normal" : "clearcoatNormal")
                             : graph::outputInputForParam(t.param);
        const auto [node, output] = graphNode(src, m_scopeOf[src.offset_debug()], label, 1);
        if (node == graph::kInvalidNodeId)
            return;
        const graph::EditResult r = m_graph->connect(
            {node, graph::PortIndex(output), outputNode(), graph::PortIndex(port)});
        if (!r)
            m_warnings.push_back(where(in) + label + ": " + r.message + "; not mapped");
        else
            m_driven.insert(t.param);
    }

    /// The UV transform of image node @p image: its uvtiling / uvoffset and a place2d on its
    /// texcoord (@p placed: one was read), the inverse of the export's (core/mtlx_values.h).
    /// @p graph: connected tiling / offset are skipped (they are graph inputs), else refused.
    UvTransform placement(pugi::xml_node image, pugi::xml_node scope, const std::string& label,
                          bool graph, bool& placed) {
        mtlx::MtlxPlacement p;
        if (pugi::xml_node t = findInput(image, "uvtiling"); t && !(graph && resolve(t, scope))) {
            const std::vector<float> v = value(t, 2, label + " uvtiling");
            p.tiling = {v[0], v[1]};
        }
        if (pugi::xml_node o = findInput(image, "uvoffset"); o && !(graph && resolve(o, scope))) {
            const std::vector<float> v = value(o, 2, label + " uvoffset");
            p.offset = {v[0], v[1]};
        }
        placed = false;
        if (pugi::xml_node tc = findInput(image, "texcoord"))
            if (pugi::xml_node up = resolve(tc, scope); up && std::string(up.name()) == "place2d") {
                p.place = place2d(up, m_scopeOf[up.offset_debug()], label);
                placed = true;
            }
        UvTransform uv;
        if (!mtlx::velvetPlacement(p, uv))
            m_warnings.push_back(where(image) + label +
                                 ": the placement's shear (a non-uniform scale after a rotation) "
                                 "is not mapped; the nearest scale and rotation are used");
        return uv;
    }
    /// A place2d node's constant inputs; a connected one, or a texcoord other than the mesh's
    /// first UV set, is said and left at its default.
    mtlx::Place2d place2d(pugi::xml_node n, pugi::xml_node scope, const std::string& label) {
        mtlx::Place2d p;
        for (pugi::xml_node in : n.children("input")) {
            const std::string name = in.attribute("name").value();
            const pugi::xml_node up = resolve(in, scope);
            if (name == "texcoord" &&
                (!up || (std::string(up.name()) == "texcoord" &&
                         std::atoi(findInput(up, "index").attribute("value").value()) == 0)))
                continue;
            const bool known = name == "pivot" || name == "scale" || name == "offset" ||
                               name == "rotate" || name == "operationorder";
            if (up || !known) {
                m_warnings.push_back(where(in) + label + ": place2d input \"" + name +
                                     "\" not mapped" + (known ? " (connected)" : ""));
                continue;
            }
            const std::vector<float> v =
                value(in, name == "rotate" || name == "operationorder" ? 1 : 2,
                      label + " place2d " + name);
            if (name == "pivot")
                p.pivot = {v[0], v[1]};
            else if (name == "scale")
                p.scale = {v[0], v[1]};
            else if (name == "offset")
                p.offset = {v[0], v[1]};
            else if (name == "rotate")
                p.rotate = v[0];
            else
                p.operationOrder = int(v[0]);
        }
        return p;
    }

    /// An `image` node into a texture slot: file (fileprefix, relative to the .mtlx), its
    /// colour space, its placement (placement()).
    void fillSlot(pugi::xml_node image, TextureSlot slot, const std::string& label) {
        TextureRef ref;
        ref.file = imageFile(image, label);
        const pugi::xml_node file = findInput(image, "file");
        std::string cs = file.attribute("colorspace").value();
        if (cs.empty())
            cs = image.attribute("colorspace").value();
        const bool colourType = std::string(image.attribute("type").value()).rfind("color", 0) == 0;
        if (auto v =
                mtlx::slotColorSpace(cs, colourType, slot, fs::path(ref.file).extension().string()))
            ref.colorSpace = *v;
        bool placed = false;
        ref.uv = placement(image, m_scopeOf[image.offset_debug()], label, false, placed);
        for (pugi::xml_node i : image.children("input")) {
            const std::string n = i.attribute("name").value();
            if (n != "file" && n != "uvtiling" && n != "uvoffset" && n != "default" &&
                !(placed && n == "texcoord"))
                m_warnings.push_back(where(i) + label + ": image input \"" + n + "\" not mapped");
        }
        m_material->setTexture(slot, std::move(ref));
    }
    std::string imageFile(pugi::xml_node image, const std::string& label) {
        const pugi::xml_node file = findInput(image, "file");
        if (!file || !*file.attribute("value").value())
            fail(image, label + ": the image has no file");
        std::string prefix;
        for (pugi::xml_node p = image; p; p = p.parent())
            if (p.attribute("fileprefix")) {
                prefix = p.attribute("fileprefix").value();
                break;
            }
        const fs::path path = m_file.parent_path() / (prefix + file.attribute("value").value());
        std::error_code ec;
        if (!fs::is_regular_file(path, ec))
            fail(file, label + ": image file not found: " + path.lexically_normal().string());
        return path.lexically_normal().string();
    }

    // ---- Node graphs --------------------------------------------------------------------------
    NodeId outputNode() {
        if (!m_graph) {
            m_graph.emplace();
            m_output = m_graph->addNode(graph::kOutputTypeId, {800, 0}).node;
        }
        return m_output;
    }

    /// The Velvet node for MaterialX node @p n (built once), and which output stands for it.
    std::pair<NodeId, int> graphNode(pugi::xml_node n, pugi::xml_node scope,
                                     const std::string& label, int depth) {
        outputNode();
        const auto key = n.offset_debug();
        if (auto it = m_built.find(key); it != m_built.end())
            return it->second;
        // A cycle would recurse forever (MaterialX forbids them; Velvet's graph refuses them too).
        if (!m_visiting.insert(key).second || depth > 256)
            fail(n, "is part of a cycle of connections");
        struct Leave {
            std::set<ptrdiff_t>& set;
            ptrdiff_t key;
            ~Leave() { set.erase(key); }
        } leave{m_visiting, key};
        const std::string c = n.name();
        const std::string name = n.attribute("name").value();
        const glm::vec2 pos(800.0f - 260.0f * float(depth), 160.0f * float(m_built.size()));
        if (c == "constant") {
            pugi::xml_node v = findInput(n, "value");
            const bool colour = std::string(n.attribute("type").value()).rfind("color", 0) == 0;
            const NodeId id =
                m_graph->addNode(colour ? "constant.color" : "constant.float", pos).node;
            if (v) {
                const std::vector<float> x = value(v, colour ? 3 : 1, label);
                m_graph->setInputValue(
                    id, 0, glm::vec4(x[0], x[x.size() > 1 ? 1 : 0], x[x.size() > 2 ? 2 : 0], 0.0f));
            }
            return m_built[key] = {id, 0};
        }
        if (c == "extract" || c == "convert") { // a channel of a colour, or a pass-through
            pugi::xml_node in = findInput(n, "in");
            pugi::xml_node src = in ? resolve(in, scope) : pugi::xml_node();
            if (!src) {
                m_warnings.push_back(where(n) + label + ": <" + c + " name=\"" + name +
                                     "\"> on a constant not mapped");
                return {graph::kInvalidNodeId, 0};
            }
            auto [up, upOut] = graphNode(src, m_scopeOf[src.offset_debug()], label, depth + 1);
            if (up == graph::kInvalidNodeId || c == "convert")
                return m_built[key] = {up, upOut};
            const int index =
                findInput(n, "index") ? int(value(findInput(n, "index"), 1, label)[0]) : 0;
            const graph::Node* upNode = m_graph->node(up);
            if (index == 3 && upNode->type->samplesTexture)
                return m_built[key] = {up, 1}; // an image's alpha output
            const NodeId split = m_graph->addNode("channel.split", pos).node;
            m_graph->connect({up, graph::PortIndex(upOut), split, 0});
            return m_built[key] = {split, std::clamp(index, 0, 2)};
        }
        const mtlx::GraphCounterpart* counterpart = mtlx::graphCounterpart(c);
        if (!counterpart) {
            m_warnings.push_back(where(n) + label + ": node <" + c + " name=\"" + name +
                                 "\"> has no Velvet graph counterpart; not mapped (the "
                                 "parameter's value applies)");
            return m_built[key] = {graph::kInvalidNodeId, 0};
        }
        const NodeId id = m_graph->addNode(counterpart->velvetType, pos).node;
        const graph::NodeType& type = *m_graph->node(id)->type;
        if (type.samplesTexture) {
            m_graph->setSetting(id, "file", imageFile(n, label));
            const pugi::xml_node file = findInput(n, "file");
            std::string cs = file.attribute("colorspace").value();
            const bool colourType = std::string(n.attribute("type").value()).rfind("color", 0) == 0;
            m_graph->setSetting(id, "colorSpace",
                                colourType ? (cs.empty() ? std::string() : velvetColorSpace(cs))
                                           : std::string("Raw"));
        }
        bool placed = false;
        if (type.samplesTexture) { // placement as for slots: v flipped (fillSlot)
            const UvTransform uv = placement(n, scope, label, true, placed);
            m_graph->setInputValue(id, graph::PortIndex(type.inputIndex("scale")),
                                   glm::vec4(uv.scale, 0.0f, 0.0f));
            m_graph->setInputValue(id, graph::PortIndex(type.inputIndex("offset")),
                                   glm::vec4(uv.offset, 0.0f, 0.0f));
            if (uv.rotation != 0.0f)
                m_graph->setInputValue(id, graph::PortIndex(type.inputIndex("rotation")),
                                       glm::vec4(uv.rotation, 0.0f, 0.0f, 0.0f));
        }
        const std::map<std::string, std::string>& portMap = counterpart->ports;
        for (pugi::xml_node in : n.children("input")) {
            const std::string mxName = in.attribute("name").value();
            if (type.samplesTexture &&
                (mxName == "file" || mxName == "uvtiling" || mxName == "uvoffset" ||
                 mxName == "default" || (placed && mxName == "texcoord")))
                continue;
            const auto mapped = portMap.find(mxName);
            const int port = type.inputIndex(mapped != portMap.end() ? mapped->second : mxName);
            if (port < 0) {
                m_warnings.push_back(where(in) + label + ": input \"" + mxName + "\" of <" + c +
                                     " name=\"" + name + "\"> not mapped");
                continue;
            }
            if (pugi::xml_node up = resolve(in, scope)) {
                auto [upId, upOut] = graphNode(up, m_scopeOf[up.offset_debug()], label, depth + 1);
                if (upId != graph::kInvalidNodeId)
                    if (auto r = m_graph->connect(
                            {upId, graph::PortIndex(upOut), id, graph::PortIndex(port)});
                        !r)
                        m_warnings.push_back(where(in) + label + ": " + r.message);
                continue;
            }
            std::vector<float> v;
            try {
                v = parseNumbers(in.attribute("value").value());
            } catch (const std::exception&) {
                fail(in, label + ": value \"" + in.attribute("value").value() +
                             "\" is not a number list");
            }
            if (v.empty())
                fail(in, label + ": input \"" + mxName + "\" has neither a value nor a connection");
            glm::vec4 x(0.0f);
            for (int i = 0; i < 4; ++i)
                x[i] = v[std::min(size_t(i), v.size() - 1)];
            if (!m_graph->setInputValue(id, graph::PortIndex(port), x))
                m_warnings.push_back(where(in) + label + ": value of \"" + mxName + "\" refused");
        }
        return m_built[key] = {id, 0};
    }

    fs::path m_file;
    std::string m_text;
    pugi::xml_document m_doc;
    pugi::xml_node m_root;
    std::vector<pugi::xml_node> m_materials;
    std::string m_shader;
    Material* m_material = nullptr;
    std::optional<Graph> m_graph;
    NodeId m_output = graph::kInvalidNodeId;
    std::map<ptrdiff_t, std::pair<NodeId, int>> m_built;
    std::map<ptrdiff_t, pugi::xml_node> m_scopeOf;
    std::set<ParamId> m_driven;
    std::set<ptrdiff_t> m_visiting; ///< graphNode()'s nodes being built (cycle check)

public:
    std::vector<std::string> m_warnings;
};

} // namespace

bool readMtlxMaterialNames(const fs::path& file, std::vector<std::string>& names,
                           ImportProblem& problem) {
    try {
        Reader r(file);
        r.load();
        names = r.names();
        return true;
    } catch (const Failure& f) {
        problem = f.problem;
        return false;
    }
}

bool importMtlxMaterial(const fs::path& file, std::string_view select, ImportedMaterial& out,
                        ImportProblem& problem) {
    out = {};
    try {
        Reader r(file);
        r.load();
        size_t index = 0;
        if (!selectMaterial(r.names(), select, index, problem))
            return false;
        r.read(index, out);
        return true;
    } catch (const Failure& f) {
        problem = f.problem;
        return false;
    }
}

} // namespace velvet
