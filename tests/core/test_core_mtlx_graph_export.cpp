// Issue 12: `velvet export -f mtlx` writes a graph-driven input as a MaterialX <nodegraph> when
// every node upstream of it has a standard-library counterpart (core/mtlx_graph_export.h), and
// bakes only the others. Known answers: the document is read back by Velvet's own importer and
// both graphs are evaluated by the CPU twin (core/graph/graph_eval.h) at several UVs, through a
// smooth periodic image, so the UV transforms, the image alpha, the mix, the float / colour
// typing and the output clamp must all survive the trip (1e-4).
#include "core/baked_maps.h"
#include "core/color_management.h"
#include "core/graph/graph.h"
#include "core/graph/graph_eval.h"
#include "core/graph/node_catalogue.h"
#include "core/image.h"
#include "core/mtlx_export.h"
#include "core/mtlx_graph_export.h"
#include "core/mtlx_import.h"
#include "core/texture_cache.h"

#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <fstream>

using namespace velvet;
using graph::Graph;
using graph::NodeId;

namespace {

/// The same smooth image for every texture node, so both graphs sample alike.
class WaveTextures : public graph::GraphTextures {
public:
    glm::vec4 sample(NodeId, glm::vec2 uv) const override {
        const float t = 6.2831853f;
        return {0.5f + 0.5f * std::sin(t * uv.x), 0.5f + 0.5f * std::cos(t * uv.y),
                0.5f + 0.25f * std::sin(t * (uv.x + uv.y)),
                0.5f + 0.5f * std::sin(t * (uv.x - 2.0f * uv.y))};
    }
};

int inputOf(const Graph& g, NodeId id, const char* name) {
    return g.node(id)->type->inputIndex(name);
}
bool link(Graph& g, NodeId from, int output, NodeId to, int input) {
    return bool(g.connect({from, graph::PortIndex(output), to, graph::PortIndex(input)}));
}
bool link(Graph& g, NodeId from, int output, NodeId to, const char* input) {
    return link(g, from, output, to, inputOf(g, to, input));
}
NodeId constant(Graph& g, glm::vec4 v, bool colour) {
    const NodeId id = g.addNode(colour ? "constant.color" : "constant.float").node;
    g.setInputValue(id, 0, v);
    return id;
}

std::string writeWave(const QTemporaryDir& dir) {
    Image image(8, 8, 4);
    for (float& p : image.pixels)
        p = 0.5f;
    const std::string file = dir.filePath("wave.png").toStdString();
    std::string error;
    if (!writeImage(file, image, PixelFormat::UInt8, &error))
        qFatal("%s", error.c_str());
    return file;
}

/// baseColor = mix(red, blue, image alpha) x image colour (a tiled, offset, rotated image read
/// through input.uv); roughness = image alpha + 0.2 (clamped by the output); emissionColor =
/// combine(0.2, alpha, 0.5); ior = 1.6.
Material mappableMaterial(const std::string& imageFile) {
    Graph g;
    const NodeId out = g.addNode(graph::kOutputTypeId).node;
    const NodeId uv = g.addNode("input.uv").node;
    const NodeId img = g.addNode("texture.image").node;
    g.setSetting(img, "file", imageFile);
    g.setInputValue(img, graph::PortIndex(inputOf(g, img, "scale")), {2.0f, 3.0f, 0, 0});
    g.setInputValue(img, graph::PortIndex(inputOf(g, img, "offset")), {0.1f, 0.2f, 0, 0});
    g.setInputValue(img, graph::PortIndex(inputOf(g, img, "rotation")), {30.0f, 0, 0, 0});
    link(g, uv, 0, img, "uv");
    const NodeId mix = g.addNode("math.mix").node;
    link(g, constant(g, {0.8f, 0.1f, 0.1f, 0}, true), 0, mix, "a");
    link(g, constant(g, {0.1f, 0.2f, 0.9f, 0}, true), 0, mix, "b");
    link(g, img, 1, mix, "factor");
    const NodeId mul = g.addNode("math.multiply").node;
    link(g, mix, 0, mul, "a");
    link(g, img, 0, mul, "b");
    link(g, mul, 0, out, graph::outputInputForParam(ParamId::BaseColor));
    const NodeId add = g.addNode("math.add").node;
    link(g, img, 1, add, "a");
    link(g, constant(g, glm::vec4(0.2f), false), 0, add, "b");
    link(g, add, 0, out, graph::outputInputForParam(ParamId::Roughness));
    const NodeId combine = g.addNode("channel.combine").node;
    g.setInputValue(combine, 0, glm::vec4(0.2f));
    link(g, img, 1, combine, "g");
    g.setInputValue(combine, 2, glm::vec4(0.5f));
    link(g, combine, 0, out, graph::outputInputForParam(ParamId::EmissiveColor));
    link(g, constant(g, glm::vec4(1.6f), false), 0, out, graph::outputInputForParam(ParamId::Ior));
    Material m;
    m.name = "wave";
    m.graph = SharedGraph(std::make_shared<const Graph>(std::move(g)));
    return m;
}

bool writeFiles(const QTemporaryDir& dir, const BuiltExport& built) {
    for (const ExportFile& f : built.files) {
        std::ofstream out(dir.filePath(QString::fromStdString(f.name)).toStdString(),
                          std::ios::binary);
        out << f.bytes;
        if (!out)
            return false;
    }
    return true;
}

} // namespace

class TestCoreMtlxGraphExport : public QObject {
    Q_OBJECT
    ColorManagement m_cm;

private slots:
    void mappableGraphIsANodegraph_data() {
        QTest::addColumn<int>("shader");
        for (int s = 0; s < int(MtlxShader::Count); ++s)
            QTest::newRow(mtlxShaderId(MtlxShader(s)).data()) << s;
    }
    void mappableGraphIsANodegraph() {
        QFETCH(int, shader);
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        const Material m = mappableMaterial(writeWave(dir));
        const std::string id(mtlxShaderId(MtlxShader(shader)));
        const std::set<std::string> mapped = mtlx::mappableGraphInputs(m, id);
        const std::vector<std::string> driven = graphDrivenInputs(m);
        QCOMPARE(mapped, (std::set<std::string>(driven.begin(), driven.end())));
        QVERIFY(!bakedInputsOf(m, mapped).any()); // nothing left to bake: no GPU needed
        QVERIFY(bakedInputsOf(m).any());

        TextureCache textures(m_cm);
        BuiltExport built;
        std::string error;
        QVERIFY2(buildMtlx(m, "wave", MtlxShader(shader), textures, built, &error), error.c_str());
        for (const std::string& w : built.warnings)
            QVERIFY2(w.rfind("graph:", 0) != 0, w.c_str()); // all of it went out
        const std::string& xml = built.files.back().bytes;
        QVERIFY(xml.find("<nodegraph name=\"NG_wave\">") != std::string::npos);
        QVERIFY(xml.find("nodegraph=\"NG_wave\" output=\"out_baseColor\"") != std::string::npos);
        QVERIFY(xml.find("colorspace=\"srgb_texture\"") != std::string::npos);
        for (const ExportFile& f : built.files)
            QVERIFY2(f.name.find("baked") == std::string::npos, f.name.c_str());
        QVERIFY(writeFiles(dir, built));

        ImportedMaterial back;
        ImportProblem problem;
        QVERIFY2(importMtlxMaterial(dir.filePath("wave.mtlx").toStdString(), "", back, problem),
                 problem.message.c_str());
        QVERIFY(back.material.graph);
        for (const graph::Node& n : [&] {
                 std::vector<graph::Node> v;
                 for (const auto& [nid, node] : back.material.graph->nodes())
                     v.push_back(node);
                 return v;
             }())
            if (n.type->samplesTexture) {
                QCOMPARE(n.settings[size_t(n.type->settingIndex("colorSpace"))],
                         std::string("sRGB texture")); // "" was the file rule: sRGB for PNG
                QVERIFY(n.settings[0].find("wave_graph") != std::string::npos &&
                        n.settings[0].ends_with(".png"));
            }
        const WaveTextures wave;
        const graph::GraphEvaluator before(*m.graph, &wave), after(*back.material.graph, &wave);
        const std::string ior =
            std::string(graph::findNodeType(graph::kOutputTypeId)
                            ->inputs[size_t(graph::outputInputForParam(ParamId::Ior))]
                            .name);
        for (const glm::vec2 uv : {glm::vec2(0.1f, 0.2f), glm::vec2(0.37f, 0.81f),
                                   glm::vec2(0.9f, 0.55f), glm::vec2(0.63f, 0.04f)}) {
            const graph::GraphSample a = before.evaluate(uv), b = after.evaluate(uv);
            int compared = 0;
            for (size_t i = 0; i < a.outputInputs.size(); ++i) {
                if (!a.outputInputs[i])
                    continue;
                QVERIFY2(b.outputInputs[i], std::to_string(i).c_str());
                for (int k = 0; k < 3; ++k)
                    QVERIFY2(std::abs((*a.outputInputs[i])[k] - (*b.outputInputs[i])[k]) < 1e-4f,
                             qPrintable(QString("input %1 channel %2 at (%3, %4): %5 vs %6")
                                            .arg(i)
                                            .arg(k)
                                            .arg(uv.x)
                                            .arg(uv.y)
                                            .arg((*a.outputInputs[i])[k])
                                            .arg((*b.outputInputs[i])[k])));
                ++compared;
            }
            QCOMPARE(compared, 4);
        }
    }

    /// A fabric node (Weave) has no MaterialX counterpart: the roughness it drives is baked,
    /// the base colour (a mix of two constants) is a nodegraph, and the bake plans only the ORM.
    void fabricInputAloneIsBaked() {
        Graph g;
        const NodeId out = g.addNode(graph::kOutputTypeId).node;
        const NodeId mix = g.addNode("math.mix").node;
        link(g, constant(g, {0.8f, 0.1f, 0.1f, 0}, true), 0, mix, "a");
        link(g, constant(g, {0.1f, 0.2f, 0.9f, 0}, true), 0, mix, "b");
        link(g, mix, 0, out, graph::outputInputForParam(ParamId::BaseColor));
        const NodeId weave = g.addNode("fabric.weave").node;
        const graph::NodeType& wt = *g.node(weave)->type;
        int floatOut = -1;
        for (size_t i = 0; i < wt.outputs.size() && floatOut < 0; ++i)
            if (wt.outputs[i].type == graph::PortType::Float)
                floatOut = int(i);
        QVERIFY(floatOut >= 0);
        QVERIFY(link(g, weave, floatOut, out, graph::outputInputForParam(ParamId::Roughness)));
        Material m;
        m.graph = SharedGraph(std::make_shared<const Graph>(std::move(g)));

        const std::set<std::string> mapped = mtlx::mappableGraphInputs(m, "standard_surface");
        QCOMPARE(mapped.size(), size_t(1));
        QVERIFY(mapped.count(graph::findNodeType(graph::kOutputTypeId)
                                 ->inputs[size_t(graph::outputInputForParam(ParamId::BaseColor))]
                                 .name.data()));
        BakedMaterialMaps baked;
        baked.inputs = bakedInputsOf(m, mapped);
        QVERIFY(baked.inputs.driven[size_t(BakedMap::Orm)]);
        QVERIFY(!baked.inputs.driven[size_t(BakedMap::BaseColor)]);
        // What render/baked_export.cpp's bake hands over: the ORM map alone.
        baked.maps.orm = Image(4, 4, 3);
        for (float& p : baked.maps.orm.pixels)
            p = 0.5f;
        baked.size = 4;
        TextureCache textures(m_cm);
        BuiltExport built;
        std::string error;
        QVERIFY2(
            buildMtlx(m, "mixed", MtlxShader::StandardSurface, textures, built, &error, &baked),
            error.c_str());
        std::vector<std::string> names;
        for (const ExportFile& f : built.files)
            names.push_back(f.name);
        QCOMPARE(names, (std::vector<std::string>{"mixed_baked_orm.png", "mixed.mtlx"}));
        const std::string& xml = built.files.back().bytes;
        QVERIFY(xml.find("name=\"base_color\" type=\"color3\" nodegraph=\"NG_mixed\"") !=
                std::string::npos);
        QVERIFY(xml.find("mixed_baked_orm.png") != std::string::npos);
        QVERIFY(xml.find("<mix name=") != std::string::npos);
    }

    /// A colour read as a float is its luminance in Velvet, which no single MaterialX node of
    /// the same inputs gives: such an input stays baked.
    void colourReadAsFloatIsNotMapped() {
        Graph g;
        const NodeId out = g.addNode(graph::kOutputTypeId).node;
        link(g, constant(g, {0.8f, 0.1f, 0.1f, 0}, true), 0, out,
             graph::outputInputForParam(ParamId::Roughness));
        Material m;
        m.graph = SharedGraph(std::make_shared<const Graph>(std::move(g)));
        QVERIFY(mtlx::mappableGraphInputs(m, "standard_surface").empty());
    }
};

QTEST_GUILESS_MAIN(TestCoreMtlxGraphExport)
#include "test_core_mtlx_graph_export.moc"
