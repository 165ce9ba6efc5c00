// The CPU twin of the graph compiler: each node's snippet (node_catalogue.cpp, fabric_nodes.cpp)
// written again with GLM, and the conversions of graph_types.h. Tests hold the two together
// (test_render_graph_eval: CPU against the GPU's node thumbnails).
#include "core/graph/graph_eval.h"

#include "core/graph/fabric.h"
#include "core/material.h"
#include "core/param_meta.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <initializer_list>
#include <map>
#include <string_view>

namespace velvet::graph {
namespace {

using glm::vec2;
using glm::vec3;
using glm::vec4;

// Rec.709 luminance, graph_types.h's colour-to-float conversion.
float luminance(vec3 c) {
    return glm::dot(c, vec3(0.2126f, 0.7152f, 0.0722f));
}

// graph_types.h's table; components beyond the target type are 0 (as value slots are).
vec4 convert(vec4 v, PortType from, PortType to) {
    if (from == to)
        return v;
    switch (to) {
    case PortType::Float:
        return vec4(from == PortType::Vec2 ? v.x : luminance(vec3(v)), 0, 0, 0);
    case PortType::Vec2:
        return from == PortType::Float ? vec4(v.x, v.x, 0, 0) : vec4(v.x, v.y, 0, 0);
    case PortType::Color:
        if (from == PortType::Float)
            return vec4(v.x, v.x, v.x, 0);
        if (from == PortType::Vec2)
            return vec4(v.x, v.y, 0, 0);
        return vec4(vec3(v), 0);
    case PortType::Vec4:
        if (from == PortType::Float)
            return vec4(v.x, v.x, v.x, 1);
        if (from == PortType::Vec2)
            return vec4(v.x, v.y, 0, 1);
        return vec4(vec3(v), 1);
    default:
        return v; // Normal only from Normal
    }
}

vec2 uvTransform(vec2 uv, vec2 scale, vec2 offset, float rotationDeg) {
    const float r = glm::radians(rotationDeg);
    const float c = std::cos(r), s = std::sin(r);
    const vec2 p = uv * scale;
    return vec2(c * p.x - s * p.y, s * p.x + c * p.y) + offset;
}

// GLSL's mod(x, y) = x - y * floor(x / y).
float glslMod(float x, float y) {
    return x - y * std::floor(x / y);
}

struct NodeIo {
    const std::vector<vec4>& in;
    vec4* out;
};

using EvalFn = void (*)(const GraphEvaluator::Step&, NodeIo, vec2 uv, const GraphTextures&);

// The fabric snippets assign each output from the struct field of the same name
// (fabric_nodes.cpp, assignOutputs), so outputs are matched by name, not position.
struct Named {
    std::string_view name;
    vec4 value;
};
void assignByName(const GraphEvaluator::Step& step, vec4* out,
                  std::initializer_list<Named> fields) {
    const auto& outputs = step.type->outputs;
    for (size_t i = 0; i < outputs.size(); ++i)
        for (const Named& f : fields)
            if (f.name == outputs[i].name)
                out[i] = f.value;
}

void writeSample(vec4* out, vec4 s) {
    out[0] = vec4(vec3(s), 0);
    out[1] = vec4(s.a, 0, 0, 0);
}

const std::map<std::string_view, EvalFn>& evaluators() {
    using Step = GraphEvaluator::Step;
    static const std::map<std::string_view, EvalFn> table = {
        {"constant.float",
         [](const Step&, NodeIo io, vec2, const GraphTextures&) { io.out[0] = io.in[0]; }},
        {"constant.color",
         [](const Step&, NodeIo io, vec2, const GraphTextures&) { io.out[0] = io.in[0]; }},
        {"input.uv",
         [](const Step&, NodeIo io, vec2 uv, const GraphTextures&) { io.out[0] = vec4(uv, 0, 0); }},
        {"texture.image",
         [](const Step& s, NodeIo io, vec2, const GraphTextures& t) {
             const vec2 st =
                 uvTransform(vec2(io.in[0]), vec2(io.in[1]), vec2(io.in[2]), io.in[3].x);
             writeSample(io.out, t.sample(s.id, st));
         }},
        {"texture.atlasRegion",
         [](const Step& s, NodeIo io, vec2, const GraphTextures& t) {
             const vec4 r = io.in[1];
             const vec2 size = glm::max(vec2(t.size(s.id)), vec2(1.0f));
             const vec2 st = (vec2(r) + glm::fract(vec2(io.in[0])) * vec2(r.z, r.w)) / size;
             writeSample(io.out, t.sample(s.id, st));
         }},
        {"channel.split",
         [](const Step&, NodeIo io, vec2, const GraphTextures&) {
             for (int c = 0; c < 3; ++c)
                 io.out[c] = vec4(io.in[0][c], 0, 0, 0);
         }},
        {"channel.combine",
         [](const Step&, NodeIo io, vec2, const GraphTextures&) {
             io.out[0] = vec4(io.in[0].x, io.in[1].x, io.in[2].x, 0);
         }},
        {"math.add", [](const Step&, NodeIo io, vec2,
                        const GraphTextures&) { io.out[0] = io.in[0] + io.in[1]; }},
        {"math.multiply", [](const Step&, NodeIo io, vec2,
                             const GraphTextures&) { io.out[0] = io.in[0] * io.in[1]; }},
        {"math.mix",
         [](const Step&, NodeIo io, vec2, const GraphTextures&) {
             io.out[0] = vec4(glm::mix(vec3(io.in[0]), vec3(io.in[1]), io.in[2].x), 0);
         }},
        {"math.remap",
         [](const Step&, NodeIo io, vec2, const GraphTextures&) {
             float d = io.in[2].x - io.in[1].x;
             d = std::abs(d) < 1e-6f ? 1e-6f : d;
             vec3 t = glm::clamp((vec3(io.in[0]) - io.in[1].x) / d, 0.0f, 1.0f);
             t = glm::pow(t, vec3(1.0f / std::max(io.in[3].x, 1e-3f)));
             io.out[0] = vec4(glm::mix(vec3(io.in[4].x), vec3(io.in[5].x), t), 0);
         }},
        {"math.invert",
         [](const Step&, NodeIo io, vec2, const GraphTextures&) {
             io.out[0] = vec4(vec3(1.0f) - vec3(io.in[0]), 0);
         }},
        {"math.clamp",
         [](const Step&, NodeIo io, vec2, const GraphTextures&) {
             io.out[0] = vec4(glm::clamp(vec3(io.in[0]), vec3(io.in[1].x), vec3(io.in[2].x)), 0);
         }},
        {"math.power",
         [](const Step&, NodeIo io, vec2, const GraphTextures&) {
             io.out[0] = vec4(glm::pow(glm::max(vec3(io.in[0]), vec3(0.0f)), vec3(io.in[1].x)), 0);
         }},
        {"noise.perlin",
         [](const Step&, NodeIo io, vec2, const GraphTextures&) {
             io.out[0] = vec4(fabric::perlin01(vec2(io.in[0]) * io.in[1].x), 0, 0, 0);
         }},
        {"noise.fbm",
         [](const Step&, NodeIo io, vec2, const GraphTextures&) {
             io.out[0] =
                 vec4(fabric::fbm(vec2(io.in[0]) * io.in[1].x, io.in[2].x, io.in[3].x, io.in[4].x),
                      0, 0, 0);
         }},
        {"noise.checker",
         [](const Step&, NodeIo io, vec2, const GraphTextures&) {
             const vec2 c = glm::floor(vec2(io.in[0]) * io.in[1].x);
             const float k = glslMod(c.x + c.y, 2.0f);
             io.out[0] = vec4(glm::mix(vec3(io.in[2]), vec3(io.in[3]), k), 0);
             io.out[1] = vec4(k, 0, 0, 0);
         }},
        {"noise.gradient",
         [](const Step&, NodeIo io, vec2, const GraphTextures&) {
             const float r = glm::radians(io.in[1].x);
             const vec2 dir(std::cos(r), std::sin(r));
             const float extent = std::abs(dir.x) + std::abs(dir.y);
             io.out[0] = vec4(
                 glm::clamp(glm::dot(vec2(io.in[0]) - vec2(0.5f), dir) / extent + 0.5f, 0.0f, 1.0f),
                 0, 0, 0);
         }},
        {"normal.map",
         [](const Step&, NodeIo io, vec2, const GraphTextures&) {
             vec3 n = vec3(io.in[0]) * 2.0f - 1.0f;
             n.x *= io.in[1].x;
             n.y *= io.in[1].x;
             const float len = glm::length(n);
             io.out[0] = vec4(len > 1e-6f ? n / len : vec3(0, 0, 1), 0);
         }},
        {"fabric.weave",
         [](const Step& s, NodeIo io, vec2, const GraphTextures&) {
             const auto& in = io.in;
             fabric::WeaveParams p;
             p.pattern = in[1].x, p.over = in[2].x, p.under = in[3].x, p.harness = in[4].x;
             p.step = in[5].x, p.group = in[6].x, p.density = vec2(in[7]), p.width = in[8].x;
             p.roundness = in[9].x, p.warpColor = vec3(in[10]), p.weftColor = vec3(in[11]);
             p.crossingHeight = in[12].x, p.roughness = in[13].x;
             const fabric::WeaveSample w = fabric::weave(vec2(in[0]), p);
             assignByName(s, io.out,
                          {{"color", vec4(w.color, 0)},
                           {"height", vec4(w.height, 0, 0, 0)},
                           {"normal", vec4(w.normal, 0)},
                           {"roughness", vec4(w.roughness, 0, 0, 0)},
                           {"sheen", vec4(w.sheen, 0, 0, 0)},
                           {"direction", vec4(w.direction, 0, 0)},
                           {"thread", vec4(w.thread, 0, 0, 0)},
                           {"warp", vec4(w.warp, 0, 0, 0)},
                           {"occlusion", vec4(w.occlusion, 0, 0, 0)}});
         }},
        {"fabric.knit",
         [](const Step& s, NodeIo io, vec2, const GraphTextures&) {
             const auto& in = io.in;
             fabric::KnitParams p;
             p.density = vec2(in[1]), p.width = in[2].x, p.roundness = in[3].x, p.lean = in[4].x;
             p.stitchHeight = in[5].x, p.color = vec3(in[6]);
             const fabric::KnitSample k = fabric::knit(vec2(in[0]), p);
             assignByName(s, io.out,
                          {{"color", vec4(k.color, 0)},
                           {"height", vec4(k.height, 0, 0, 0)},
                           {"normal", vec4(k.normal, 0)},
                           {"direction", vec4(k.direction, 0, 0)},
                           {"occlusion", vec4(k.occlusion, 0, 0, 0)}});
         }},
        {"fabric.fuzz",
         [](const Step& s, NodeIo io, vec2, const GraphTextures&) {
             const auto& in = io.in;
             fabric::FuzzParams p;
             p.direction = vec2(in[1]), p.baseColor = vec3(in[2]), p.roughness = in[3].x;
             p.fuzzColor = vec3(in[4]), p.density = in[5].x, p.stretch = in[6].x,
             p.amount = in[7].x;
             const fabric::FuzzSample f = fabric::fuzz(vec2(in[0]), p);
             assignByName(s, io.out,
                          {{"color", vec4(f.color, 0)},
                           {"roughness", vec4(f.roughness, 0, 0, 0)},
                           {"sheen", vec4(f.sheen, 0, 0, 0)},
                           {"mask", vec4(f.mask, 0, 0, 0)}});
         }},
        {"fabric.pile",
         [](const Step& s, NodeIo io, vec2, const GraphTextures&) {
             const auto& in = io.in;
             fabric::PileParams p;
             p.angle = in[1].x, p.lean = in[2].x, p.crush = in[3].x, p.scale = in[4].x;
             const fabric::PileSample q = fabric::pile(vec2(in[0]), p);
             assignByName(s, io.out,
                          {{"normal", vec4(q.normal, 0)},
                           {"sheen", vec4(q.sheen, 0, 0, 0)},
                           {"roughness", vec4(q.roughness, 0, 0, 0)},
                           {"crush", vec4(q.crush, 0, 0, 0)}});
         }},
        {"fabric.grain",
         [](const Step& s, NodeIo io, vec2, const GraphTextures&) {
             const auto& in = io.in;
             fabric::GrainParams p;
             p.scale = in[1].x, p.irregularity = in[2].x, p.creaseWidth = in[3].x;
             p.dome = in[4].x, p.depth = in[5].x, p.color = vec3(in[6]);
             p.creaseColor = vec3(in[7]), p.roughness = in[8].x, p.creaseRoughness = in[9].x;
             const fabric::GrainSample g = fabric::grain(vec2(in[0]), p);
             assignByName(s, io.out,
                          {{"color", vec4(g.color, 0)},
                           {"height", vec4(g.height, 0, 0, 0)},
                           {"normal", vec4(g.normal, 0)},
                           {"roughness", vec4(g.roughness, 0, 0, 0)},
                           {"cavity", vec4(g.cavity, 0, 0, 0)},
                           {"occlusion", vec4(g.occlusion, 0, 0, 0)},
                           {"cell", vec4(g.cell, 0, 0, 0)}});
         }},
    };
    return table;
}

// Pack/unpack nodes share the split / combine statements (as their snippets do).
EvalFn evaluatorFor(std::string_view id) {
    if (id == "channel.unpackOrm" || id == "channel.unpackSrm")
        id = "channel.split";
    else if (id == "channel.packOrm" || id == "channel.packSrm")
        id = "channel.combine";
    const auto& table = evaluators();
    const auto it = table.find(id);
    return it == table.end() ? nullptr : it->second;
}

const GraphTextures& whiteTextures() {
    static const GraphTextures white;
    return white;
}

} // namespace

glm::vec4 GraphTextures::sample(NodeId, glm::vec2) const {
    return glm::vec4(1.0f);
}

glm::ivec2 GraphTextures::size(NodeId) const {
    return glm::ivec2(1);
}

GraphEvaluator::GraphEvaluator(const Graph& graph, const GraphTextures* textures)
    : m_textures(textures) {
    // Kahn's order over the links (the graph refuses cycles, so every node gets a place).
    std::map<NodeId, int> pending;
    for (const auto& [id, node] : graph.nodes())
        pending[id] = 0;
    for (const Connection& c : graph.connections())
        ++pending[c.inNode];
    std::vector<NodeId> ready, order;
    for (const auto& [id, count] : pending)
        if (count == 0)
            ready.push_back(id);
    while (!ready.empty()) {
        const NodeId id = ready.front();
        ready.erase(ready.begin());
        order.push_back(id);
        for (const Connection& c : graph.connectionsOf(id))
            if (c.outNode == id && --pending[c.inNode] == 0)
                ready.push_back(c.inNode);
    }
    std::map<NodeId, int> stepIndex;
    for (const NodeId id : order) {
        const Node& node = *graph.node(id);
        Step step;
        step.id = id;
        step.type = node.type;
        step.values = node.inputValues;
        stepIndex[id] = int(m_steps.size());
        m_outputFirst.push_back(m_slots);
        m_slots += node.type->outputs.size();
        m_steps.push_back(std::move(step));
    }
    for (Step& step : m_steps) {
        step.sourceSlot.assign(step.type->inputs.size(), -1);
        step.sourceType.assign(step.type->inputs.size(), PortType::Float);
        for (PortIndex i = 0; i < step.type->inputs.size(); ++i)
            if (const Connection* c = graph.connectionTo(step.id, i)) {
                const int from = stepIndex.at(c->outNode);
                step.sourceSlot[i] = int(m_outputFirst[size_t(from)] + c->outPort);
                step.sourceType[i] = m_steps[size_t(from)].type->outputs[c->outPort].type;
            }
        if (step.type->isOutput) {
            m_outputStep = int(&step - m_steps.data());
            m_drives = std::any_of(step.sourceSlot.begin(), step.sourceSlot.end(),
                                   [](int s) { return s >= 0; });
        }
    }
}

int GraphEvaluator::stepOf(NodeId node) const {
    for (size_t i = 0; i < m_steps.size(); ++i)
        if (m_steps[i].id == node)
            return int(i);
    return -1;
}

void GraphEvaluator::run(glm::vec2 uv, std::vector<glm::vec4>& values, int lastStep) const {
    values.assign(m_slots, glm::vec4(0.0f));
    const GraphTextures& textures = m_textures ? *m_textures : whiteTextures();
    std::vector<glm::vec4> in;
    for (int s = 0; s <= lastStep; ++s) {
        const Step& step = m_steps[size_t(s)];
        if (step.type->isOutput)
            continue;
        in.resize(step.type->inputs.size());
        for (size_t i = 0; i < in.size(); ++i) {
            const InputSpec& spec = step.type->inputs[i];
            if (step.sourceSlot[i] >= 0)
                in[i] = convert(values[size_t(step.sourceSlot[i])], step.sourceType[i], spec.type);
            else if (spec.fallback == Fallback::MeshUv)
                in[i] = glm::vec4(uv, 0.0f, 0.0f);
            else
                in[i] = i < step.values.size() ? step.values[i] : spec.defaultValue;
        }
        if (const EvalFn fn = evaluatorFor(step.type->id))
            fn(step, NodeIo{in, values.data() + m_outputFirst[size_t(s)]}, uv, textures);
    }
}

GraphSample GraphEvaluator::evaluate(glm::vec2 uv) const {
    GraphSample sample;
    if (m_outputStep < 0)
        return sample;
    std::vector<glm::vec4> values;
    run(uv, values, m_outputStep);
    const Step& out = m_steps[size_t(m_outputStep)];
    sample.outputInputs.resize(out.type->inputs.size());
    for (PortIndex i = 0; i < out.type->inputs.size(); ++i) {
        if (out.sourceSlot[i] < 0)
            continue;
        const InputSpec& spec = out.type->inputs[i];
        glm::vec4 v = convert(values[size_t(out.sourceSlot[i])], out.sourceType[i], spec.type);
        // As outputSnippet: parameters within their hard range, occlusion in [0, 1].
        const ParamId param = paramForOutputInput(i);
        if (param != ParamId::Count) {
            const ParamMeta& m = paramMeta(param);
            v = glm::clamp(v, m.min, m.max);
        } else if (spec.name == "occlusion") {
            v = glm::clamp(v, 0.0f, 1.0f);
        }
        sample.outputInputs[i] = v;
    }
    return sample;
}

glm::vec4 GraphEvaluator::evaluateOutput(NodeId node, PortIndex output, glm::vec2 uv) const {
    const int step = stepOf(node);
    if (step < 0 || output >= m_steps[size_t(step)].type->outputs.size())
        return glm::vec4(0.0f);
    std::vector<glm::vec4> values;
    run(uv, values, step);
    return values[m_outputFirst[size_t(step)] + output];
}

} // namespace velvet::graph
