// The CPU twin of the graph compiler (core/graph/graph_eval.h) against the GPU: every node type
// (texture nodes sampling their default white) is previewed on the GPU through the graph
// compiler (render/graph_preview.h, 64x64) and evaluated on the CPU at the same pixel centres;
// the two agree within 1.5/255 at all but the few pixels a discontinuity (a checker edge, a yarn
// boundary) straddles. Plus known answers of the material output's conversion and clamp.
#include "core/graph/graph.h"
#include "core/graph/graph_eval.h"
#include "core/material.h"
#include "render/graph_preview.h"
#include "render_test_util.h"

#include <QtTest>
#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

using namespace velvet;
using namespace velvet::graph;

namespace {

constexpr int kSide = 64;

float srgb(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

// What the GPU preview shows of an output value (graph_compiler.cpp previewRgba, then
// graph_preview.frag): colours sRGB-encoded, data clamped; 0..255 units.
glm::vec3 previewBytes(glm::vec4 v, PortType type) {
    glm::vec3 rgb;
    switch (type) {
    case PortType::Float:
        rgb = glm::vec3(v.x);
        break;
    case PortType::Vec2:
        rgb = glm::vec3(v.x, v.y, 0.0f);
        break;
    case PortType::Normal:
        rgb = glm::vec3(v) * 0.5f + 0.5f;
        break;
    default:
        rgb = glm::vec3(srgb(v.x), srgb(v.y), srgb(v.z));
        break;
    }
    return glm::clamp(rgb, 0.0f, 1.0f) * 255.0f;
}

NodeId add(Graph& g, const char* type) {
    const EditResult r = g.addNode(type);
    if (!r)
        qFatal("addNode(%s): %s", type, r.message.c_str());
    return r.node;
}

PortIndex in(const Graph& g, NodeId n, const char* name) {
    return PortIndex(g.node(n)->type->inputIndex(name));
}
PortIndex out(const Graph& g, NodeId n, const char* name) {
    return PortIndex(g.node(n)->type->outputIndex(name));
}

void link(Graph& g, NodeId from, const char* output, NodeId to, const char* input) {
    const EditResult r = g.connect({from, out(g, from, output), to, in(g, to, input)});
    if (!r)
        qFatal("connect: %s", r.message.c_str());
}

} // namespace

class TestRenderGraphEval : public QObject {
    Q_OBJECT
    std::unique_ptr<render::GraphPreview> m_preview;

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        m_preview = std::make_unique<render::GraphPreview>(kSide);
    }
    void cleanupTestCase() { m_preview.reset(); }

    void cpuTwinMatchesTheGpu() {
        Graph g;
        const NodeId uv = add(g, "input.uv");
        const NodeId checker = add(g, "noise.checker");
        const NodeId perlin = add(g, "noise.perlin");
        const NodeId fbm = add(g, "noise.fbm");
        const NodeId gradient = add(g, "noise.gradient");
        const NodeId mix = add(g, "math.mix");
        const NodeId remap = add(g, "math.remap");
        const NodeId power = add(g, "math.power");
        const NodeId clampNode = add(g, "math.clamp");
        const NodeId invert = add(g, "math.invert");
        const NodeId addNode = add(g, "math.add");
        const NodeId multiply = add(g, "math.multiply");
        const NodeId split = add(g, "channel.split");
        const NodeId combine = add(g, "channel.combine");
        const NodeId unpack = add(g, "channel.unpackOrm");
        const NodeId pack = add(g, "channel.packSrm");
        const NodeId normalMap = add(g, "normal.map");
        const NodeId constant = add(g, "constant.color");
        const NodeId value = add(g, "constant.float");
        const NodeId image = add(g, "texture.image");
        const NodeId weave = add(g, "fabric.weave");
        const NodeId knit = add(g, "fabric.knit");
        const NodeId fuzz = add(g, "fabric.fuzz");
        const NodeId pile = add(g, "fabric.pile");
        const NodeId grain = add(g, "fabric.grain");
        QVERIFY(g.setInputValue(checker, in(g, checker, "scale"), glm::vec4(3.0f)));
        QVERIFY(g.setInputValue(gradient, in(g, gradient, "angle"), glm::vec4(30.0f)));
        QVERIFY(g.setInputValue(constant, 0, glm::vec4(0.2f, 0.5f, 0.9f, 0)));
        QVERIFY(g.setInputValue(value, 0, glm::vec4(0.3f)));
        QVERIFY(g.setInputValue(pile, in(g, pile, "crush"), glm::vec4(0.6f)));
        QVERIFY(g.setInputValue(power, in(g, power, "exponent"), glm::vec4(1.7f)));
        link(g, uv, "uv", checker, "uv");
        link(g, perlin, "value", mix, "factor");
        link(g, checker, "color", mix, "a");
        link(g, fbm, "value", mix, "b");
        link(g, mix, "result", remap, "value");
        link(g, gradient, "value", remap, "gamma");
        link(g, remap, "result", power, "value");
        link(g, power, "result", clampNode, "value");
        link(g, clampNode, "result", invert, "value");
        link(g, invert, "result", addNode, "a");
        link(g, constant, "color", addNode, "b");
        link(g, addNode, "result", multiply, "a");
        link(g, value, "value", multiply, "b");
        link(g, multiply, "result", split, "color");
        link(g, split, "r", combine, "g");
        link(g, split, "b", combine, "r");
        link(g, combine, "color", unpack, "packed");
        link(g, unpack, "roughness", pack, "metallic");
        link(g, weave, "color", normalMap, "color");
        link(g, weave, "direction", fuzz, "direction");
        link(g, image, "color", knit, "color");

        struct Probe {
            NodeId node;
            const char* output;
        };
        const Probe probes[] = {
            {checker, "color"},    {checker, "mask"},   {perlin, "value"},    {fbm, "value"},
            {gradient, "value"},   {mix, "result"},     {remap, "result"},    {power, "result"},
            {clampNode, "result"}, {invert, "result"},  {addNode, "result"},  {multiply, "result"},
            {split, "g"},          {combine, "color"},  {unpack, "metallic"}, {pack, "packed"},
            {normalMap, "normal"}, {weave, "color"},    {weave, "normal"},    {weave, "height"},
            {weave, "direction"},  {weave, "thread"},   {weave, "sheen"},     {knit, "color"},
            {knit, "normal"},      {fuzz, "color"},     {fuzz, "mask"},       {pile, "normal"},
            {pile, "sheen"},       {pile, "roughness"}, {uv, "uv"},           {image, "alpha"},
            {grain, "color"},      {grain, "normal"},   {grain, "roughness"}, {grain, "cavity"},
            {weave, "occlusion"},  {knit, "occlusion"},
        };
        std::vector<render::PreviewRequest> requests;
        for (const Probe& p : probes)
            requests.push_back({p.node, out(g, p.node, p.output)});
        Problems problems;
        const std::vector<Image> gpu = m_preview->render(g, requests, nullptr, &problems);
        QCOMPARE(gpu.size(), requests.size());
        const GraphEvaluator cpu(g);
        for (size_t r = 0; r < requests.size(); ++r) {
            const Probe& p = probes[r];
            const PortType type = g.node(p.node)->type->outputs[requests[r].output].type;
            QVERIFY2(!gpu[r].empty(), p.output);
            int off = 0;
            double sum = 0.0;
            for (int y = 0; y < kSide; ++y)
                for (int x = 0; x < kSide; ++x) {
                    const glm::vec2 at((x + 0.5f) / kSide, (y + 0.5f) / kSide);
                    const glm::vec3 want =
                        previewBytes(cpu.evaluateOutput(p.node, requests[r].output, at), type);
                    const glm::vec3 got = glm::vec3(gpu[r].rgba(x, y)) * 255.0f;
                    const float err = glm::length(want - got) / std::sqrt(3.0f);
                    sum += err;
                    if (glm::any(glm::greaterThan(glm::abs(want - got), glm::vec3(1.5f))))
                        ++off;
                }
            const QString what = QStringLiteral("%1.%2: %3 of %4 pixels off, mean %5/255")
                                     .arg(g.node(p.node)->type->id.data())
                                     .arg(p.output)
                                     .arg(off)
                                     .arg(kSide * kSide)
                                     .arg(sum / (kSide * kSide), 0, 'f', 3);
            qInfo("%s", qPrintable(what));
            // A discontinuity straddled by a pixel centre may round either way: at most 3 %.
            QVERIFY2(off <= kSide * kSide * 3 / 100, qPrintable(what));
            QVERIFY2(sum / (kSide * kSide) < 0.6, qPrintable(what));
        }
    }

    // The material output receives what the GLSL gives it: converted to the input's type and
    // clamped to the parameter's hard range; unlinked inputs stay the material's.
    void outputInputsAreConvertedAndClamped() {
        Graph g;
        const NodeId output = add(g, "output.material");
        const NodeId colour = add(g, "constant.color");
        const NodeId big = add(g, "constant.float");
        QVERIFY(g.setInputValue(colour, 0, glm::vec4(0.2f, 0.4f, 0.6f, 0)));
        QVERIFY(g.setInputValue(big, 0, glm::vec4(7.0f)));
        const PortIndex base = PortIndex(outputInputForParam(ParamId::BaseColor));
        const PortIndex rough = PortIndex(outputInputForParam(ParamId::Roughness));
        const PortIndex metal = PortIndex(outputInputForParam(ParamId::Metallic));
        QVERIFY(g.connect({colour, 0, output, base}));
        QVERIFY(g.connect({big, 0, output, rough}));
        QVERIFY(g.connect({colour, 0, output, metal}));
        const GraphEvaluator cpu(g);
        QVERIFY(cpu.drivesMaterial());
        const GraphSample s = cpu.evaluate({0.3f, 0.7f});
        QVERIFY(s.outputInputs[base]);
        QCOMPARE(glm::vec3(*s.outputInputs[base]), glm::vec3(0.2f, 0.4f, 0.6f));
        QCOMPARE(s.outputInputs[rough]->x, 1.0f); // 7 clamped to roughness's [0, 1]
        // A colour into a float: Rec.709 luminance.
        QVERIFY(std::abs(s.outputInputs[metal]->x -
                         (0.2126f * 0.2f + 0.7152f * 0.4f + 0.0722f * 0.6f)) < 1e-6f);
        QVERIFY(!s.outputInputs[PortIndex(outputInputForParam(ParamId::SheenWeight))]);
    }
};

QTEST_MAIN(TestRenderGraphEval)
#include "test_render_graph_eval.moc"
