#include "core/graph/graph_compiler.h"

#include "core/graph/fabric.h"
#include "core/graph/glsl_format.h"

#include <algorithm>
#include <functional>
#include <map>
#include <queue>
#include <set>

namespace velvet::graph {
namespace {

// ---- GLSL helpers (emitted once each, only when a compiled node needs them) ------------------

// Blender's Mapping node order (type Point): scale, rotate about the origin, translate.
constexpr std::string_view kUvTransformGlsl =
    R"(// UV transform: scale, then rotate (degrees, counter-clockwise), then offset.
vec2 velvetGraphUvTransform(vec2 uv, vec2 scale, vec2 offset, float rotationDeg) {
    float r = radians(rotationDeg);
    float c = cos(r);
    float s = sin(r);
    vec2 p = uv * scale;
    return vec2(c * p.x - s * p.y, s * p.x + c * p.y) + offset;
}
)";

constexpr std::string_view kNoiseGlsl =
    R"(// pcg2d, the shaders' one integer hash (resources/shaders/common_hash.glsl).
#include "common_hash.glsl"

// A unit gradient per lattice point, its angle taken from the hash (replacing the permutation
// table and the 12 fixed gradients of Perlin's reference implementation).
vec2 velvetGraphGradient(ivec2 cell) {
    uvec2 h = pcg2d(uvec2(cell));
    float a = float(h.x >> 8u) * (6.28318530718 / 16777216.0);
    return vec2(cos(a), sin(a));
}

// Gradient noise: Perlin 2002, "Improving Noise", SIGGRAPH (quintic fade 6t^5 - 15t^4 + 10t^3),
// in 2D with hashed gradients. Range [-sqrt(1/2), sqrt(1/2)].
float velvetGraphPerlin(vec2 p) {
    vec2 i = floor(p);
    vec2 f = p - i;
    vec2 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    ivec2 c = ivec2(i);
    float n00 = dot(velvetGraphGradient(c), f);
    float n10 = dot(velvetGraphGradient(c + ivec2(1, 0)), f - vec2(1.0, 0.0));
    float n01 = dot(velvetGraphGradient(c + ivec2(0, 1)), f - vec2(0.0, 1.0));
    float n11 = dot(velvetGraphGradient(c + ivec2(1, 1)), f - vec2(1.0, 1.0));
    return mix(mix(n00, n10, u.x), mix(n01, n11, u.x), u.y);
}

// Perlin noise mapped to [0, 1] (0.5 + n / (2 sqrt(1/2))).
float velvetGraphPerlin01(vec2 p) {
    return clamp(0.5 + 0.70710678 * velvetGraphPerlin(p), 0.0, 1.0);
}

// Fractal Brownian motion: Musgrave's fBm (Ebert et al. 2003, "Texturing and Modeling", ch. 16),
// a sum of octaves of gradient noise, normalised by the sum of amplitudes and mapped to [0, 1].
// Each octave is offset so the lattices' origins do not line up.
float velvetGraphFbm(vec2 p, float octaves, float lacunarity, float gain) {
    int count = clamp(int(octaves + 0.5), 1, 8);
    float sum = 0.0;
    float norm = 0.0;
    float amplitude = 1.0;
    for (int i = 0; i < 8; ++i) {
        if (i >= count)
            break;
        sum += amplitude * velvetGraphPerlin(p);
        norm += amplitude;
        amplitude *= gain;
        p = p * lacunarity + vec2(17.31, 9.73);
    }
    return clamp(0.5 + 0.70710678 * sum / max(norm, 1e-6), 0.0, 1.0);
}
)";

std::string_view swizzle(PortType t) {
    switch (t) {
    case PortType::Float:
        return ".x";
    case PortType::Vec2:
        return ".xy";
    case PortType::Color:
    case PortType::Normal:
        return ".xyz";
    default:
        return "";
    }
}

std::string glslVec(const glm::vec4& v, PortType t) {
    if (t == PortType::Float)
        return glslFloat(v.x);
    std::string s(portTypeGlsl(t));
    s += "(";
    for (int i = 0; i < portTypeComponents(t); ++i)
        s += (i ? ", " : "") + glslFloat(v[i]);
    return s + ")";
}

std::string varName(NodeId id, std::string_view port) {
    std::string name = "n";
    name += std::to_string(id);
    name += '_';
    name += port;
    return name;
}

void appendPrelude(std::string& o) {
    const NodeType& out = *findNodeType(kOutputTypeId);
    o += "// Material inputs: the material's parameters as the G-buffer pass uses them "
         "(core/graph/graph_compiler.h).\n";
    o += "struct MaterialInputs {\n";
    for (const InputSpec& in : out.inputs)
        o += "    " + std::string(portTypeGlsl(in.type)) + " " + std::string(in.name) + ";\n";
    o += "};\n\n";
    o += "MaterialInputs velvetGraphDefaults() {\n    MaterialInputs m;\n";
    for (const InputSpec& in : out.inputs)
        o += "    m." + std::string(in.name) + " = " + glslVec(in.defaultValue, in.type) + ";\n";
    o += "    return m;\n}\n\n";
}

/// The nodes that feed @p output (itself included), in topological order with ties broken by id.
std::vector<NodeId> liveOrder(const Graph& g, NodeId output) {
    std::set<NodeId> live;
    std::vector<NodeId> stack{output};
    while (!stack.empty()) {
        const NodeId n = stack.back();
        stack.pop_back();
        if (!live.insert(n).second)
            continue;
        for (const Connection& c : g.connections())
            if (c.inNode == n)
                stack.push_back(c.outNode);
    }
    // Kahn 1962, "Topological sorting of large networks", with a min-heap for determinism.
    std::map<NodeId, int> pending;
    for (NodeId n : live)
        pending[n] = 0;
    for (const Connection& c : g.connections())
        if (live.count(c.inNode) && live.count(c.outNode))
            ++pending[c.inNode];
    std::priority_queue<NodeId, std::vector<NodeId>, std::greater<>> ready;
    for (const auto& [n, count] : pending)
        if (count == 0)
            ready.push(n);
    std::vector<NodeId> order;
    while (!ready.empty()) {
        const NodeId n = ready.top();
        ready.pop();
        order.push_back(n);
        for (const Connection& c : g.connections())
            if (c.outNode == n && live.count(c.inNode) && --pending[c.inNode] == 0)
                ready.push(c.inNode);
    }
    return order; // the model refuses cycles, so every live node is here
}

/// What the compiler keeps between emitting the declarations and the node bodies.
struct Layout {
    std::map<std::pair<NodeId, PortIndex>, int> slotOf;
    std::map<NodeId, int> samplerOf;
};

/// Assigns value slots and samplers to r.order's nodes and emits everything before the entry
/// function: the prelude, the value block, the samplers and the helpers. False (r.error set)
/// when @p options' limits are exceeded.
bool emitDeclarations(const Graph& graph, const CompileOptions& options, CompiledGraph& r,
                      Layout& layout) {
    // Value slots and samplers, in emission order.
    for (NodeId id : r.order) {
        const Node& n = *graph.node(id);
        for (PortIndex i = 0; i < n.type->inputs.size(); ++i)
            if (n.type->inputs[i].fallback == Fallback::Value && !graph.connectionTo(id, i)) {
                layout.slotOf[{id, i}] = int(r.valueSlots.size());
                r.valueSlots.push_back({id, i});
            }
        if (n.type->samplesTexture) {
            SamplerBinding b;
            b.node = id;
            b.unit = options.firstSamplerUnit + int(r.samplers.size());
            b.uniform = "u_graphTex" + std::to_string(r.samplers.size());
            b.file = n.settings[size_t(n.type->settingIndex("file"))];
            b.colorSpace = n.settings[size_t(n.type->settingIndex("colorSpace"))];
            layout.samplerOf[id] = int(r.samplers.size());
            r.samplers.push_back(std::move(b));
        }
    }
    if (int(r.samplers.size()) > options.maxSamplers) {
        r.error = "the graph samples " + std::to_string(r.samplers.size()) + " textures; at most " +
                  std::to_string(options.maxSamplers) + " are allowed";
        return false;
    }
    if (int(r.valueSlots.size()) > options.maxValueSlots) {
        r.error = "the graph has " + std::to_string(r.valueSlots.size()) + " values; at most " +
                  std::to_string(options.maxValueSlots) + " are allowed";
        return false;
    }
    r.values = graphValues(graph, r.valueSlots);

    std::string& o = r.glsl;
    o += "// Material graph: generated by core/graph/graph_compiler.cpp; do not edit.\n\n";
    appendPrelude(o);
    o += "layout(std140, binding = " + std::to_string(options.valuesBinding) +
         ") uniform VelvetGraphValues {\n    vec4 u_graphValues[" +
         std::to_string(r.values.size()) + "];\n};\n";
    for (const SamplerBinding& b : r.samplers)
        o += "layout(binding = " + std::to_string(b.unit) + ") uniform sampler2D " + b.uniform +
             "; // node " + std::to_string(b.node) + "\n";
    o += "\n";
    unsigned helpers = HelperNone;
    for (NodeId id : r.order)
        helpers |= graph.node(id)->type->helpers;
    if (helpers & HelperUvTransform)
        o += std::string(kUvTransformGlsl) + "\n";
    if (helpers & HelperNoise)
        o += std::string(kNoiseGlsl) + "\n";
    if (helpers & HelperFabric)
        o += std::string(fabric::fabricGlsl()) + "\n";
    return true;
}

/// Emits the statements of r.order's nodes (the body of the entry function).
void emitNodes(const Graph& graph, const Layout& layout, CompiledGraph& r) {
    std::string& o = r.glsl;
    for (NodeId id : r.order) {
        const Node& n = *graph.node(id);
        const NodeType& type = *n.type;
        SnippetArgs args;
        for (PortIndex i = 0; i < type.inputs.size(); ++i) {
            const InputSpec& spec = type.inputs[i];
            const Connection* link = graph.connectionTo(id, i);
            args.connected.push_back(link != nullptr);
            args.outputFields.emplace_back(spec.name);
            if (link) {
                const Node& from = *graph.node(link->outNode);
                const OutputSpec& out = from.type->outputs[link->outPort];
                args.in.push_back(*convertGlsl(varName(from.id, out.name), out.type, spec.type));
                if (type.isOutput)
                    r.writtenFields.emplace_back(spec.name);
            } else if (spec.fallback == Fallback::Value) {
                args.in.push_back("u_graphValues[" + std::to_string(layout.slotOf.at({id, i})) +
                                  "]" + std::string(swizzle(spec.type)));
            } else if (spec.fallback == Fallback::MeshUv) {
                args.in.emplace_back("uv");
            } else {
                args.in.emplace_back();
            }
        }
        o += "    // node " + std::to_string(id) + ": " + std::string(type.id) + "\n";
        for (const OutputSpec& out : type.outputs) {
            args.out.push_back(varName(id, out.name));
            o += "    " + std::string(portTypeGlsl(out.type)) + " " + args.out.back() + ";\n";
        }
        if (const auto s = layout.samplerOf.find(id); s != layout.samplerOf.end())
            args.sampler = r.samplers[size_t(s->second)].uniform;
        std::string body;
        type.glsl(args, body);
        if (!body.empty()) {
            o += "    {\n";
            // Indent the snippet's lines one more level inside its block.
            size_t start = 0;
            while (start < body.size()) {
                size_t end = body.find('\n', start);
                if (end == std::string::npos)
                    end = body.size();
                o += "    " + body.substr(start, end - start) + "\n";
                start = end + 1;
            }
            o += "    }\n";
        }
    }
}

/// A value of type @p t as the RGBA a preview shows: a float as grey, a 2D vector as (x, y, 0),
/// a normal as the usual n * 0.5 + 0.5 map colour, opaque.
std::string previewRgba(const std::string& expr, PortType t) {
    switch (t) {
    case PortType::Float:
        return "vec4(vec3(" + expr + "), 1.0)";
    case PortType::Vec2:
        return "vec4(" + expr + ", 0.0, 1.0)";
    case PortType::Color:
        return "vec4(" + expr + ", 1.0)";
    case PortType::Normal:
        return "vec4(" + expr + " * 0.5 + 0.5, 1.0)";
    default:
        return expr;
    }
}

} // namespace

CompiledGraph compileGraph(const Graph& graph, const CompileOptions& options) {
    CompiledGraph r;
    const NodeId output = graph.outputNode();
    if (output != kInvalidNodeId)
        r.order = liveOrder(graph, output);
    Layout layout;
    if (!emitDeclarations(graph, options, r, layout))
        return r;
    r.glsl += "void velvetGraph(in vec2 uv, inout MaterialInputs m) {\n";
    emitNodes(graph, layout, r);
    r.glsl += "}\n";
    r.ok = true;
    return r;
}

CompiledGraph compileGraphPreview(const Graph& graph, NodeId node, PortIndex output,
                                  const CompileOptions& options) {
    CompiledGraph r;
    const Node* n = graph.node(node);
    if (!n) {
        r.error = "no node " + std::to_string(node) + " to preview";
        return r;
    }
    if (output >= n->type->outputs.size()) {
        r.error = "node " + std::to_string(node) + " (" + std::string(n->type->id) +
                  ") has no output " + std::to_string(output) + " to preview";
        return r;
    }
    r.order = liveOrder(graph, node);
    Layout layout;
    if (!emitDeclarations(graph, options, r, layout))
        return r;
    const OutputSpec& out = n->type->outputs[output];
    r.previewType = out.type;
    r.glsl += "vec4 velvetGraphPreview(in vec2 uv) {\n";
    emitNodes(graph, layout, r);
    r.glsl += "    return " + previewRgba(varName(node, out.name), out.type) + ";\n}\n";
    r.ok = true;
    return r;
}

std::vector<glm::vec4> graphValues(const Graph& graph, std::span<const ValueSlot> valueSlots) {
    std::vector<glm::vec4> values;
    values.reserve(std::max<size_t>(1, valueSlots.size()));
    for (const ValueSlot& s : valueSlots) {
        const Node* n = graph.node(s.node);
        values.push_back(n && s.input < n->inputValues.size() ? n->inputValues[s.input]
                                                              : glm::vec4(0.0f));
    }
    if (values.empty())
        values.emplace_back(0.0f);
    return values;
}

} // namespace velvet::graph
