// The fabric nodes on the GPU against their C++ twins (core/graph/fabric.h): every output of
// Weave (each pattern), Knit, Fibre fuzz, Pile and the leather Grain rendered as a 64x64 node
// thumbnail through the graph compiler (render/graph_preview.h) and compared, pixel centre by pixel
// centre, with the twin evaluated at the same UV. Thumbnails are 8-bit: floats and normals as data,
// colours sRGB-encoded, so values agree within a few 1/255; the few pixels that straddle a yarn's
// edge may pick the other yarn on one side (float rounding), which the budget below allows. Weaves
// and grains finer than the thumbnail's pixels check the footprint filtering (fwidth on the GPU,
// the twin's footprint on the CPU).
#include "core/graph/fabric.h"
#include "core/graph/graph.h"
#include "render/graph_preview.h"
#include "render_test_util.h"

#include <QtTest>
#include <cmath>
#include <functional>
#include <glm/common.hpp>

using namespace velvet;
using namespace velvet::graph;
namespace fab = velvet::graph::fabric;

namespace {

constexpr int kSide = 64;

float srgb(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

/// What a thumbnail of an output of type @p t shows for @p value (graph_compiler.h, previewRgba).
glm::vec3 shown(glm::vec3 value, PortType t) {
    switch (t) {
    case PortType::Color:
        return {srgb(value.x), srgb(value.y), srgb(value.z)};
    case PortType::Normal:
        return glm::clamp(value * 0.5f + 0.5f, 0.0f, 1.0f);
    default:
        return glm::clamp(value, 0.0f, 1.0f);
    }
}

/// One output of the twin at a UV, as a vec3 (floats splat to x only; compared on x).
using TwinFn = std::function<glm::vec3(glm::vec2 uv, std::string_view output)>;

void set(Graph& g, NodeId n, std::string_view input, glm::vec4 v) {
    const int i = g.node(n)->type->inputIndex(input);
    QVERIFY2(i >= 0, std::string(input).c_str());
    QVERIFY(g.setInputValue(n, PortIndex(i), v).ok);
}

glm::vec3 weaveOut(const fab::WeaveSample& s, std::string_view o) {
    if (o == "color")
        return s.color;
    if (o == "height")
        return glm::vec3(s.height);
    if (o == "normal")
        return s.normal;
    if (o == "roughness")
        return glm::vec3(s.roughness);
    if (o == "sheen")
        return glm::vec3(s.sheen);
    if (o == "direction")
        return {s.direction, 0.0f};
    if (o == "thread")
        return glm::vec3(s.thread);
    if (o == "warp")
        return glm::vec3(s.warp);
    return glm::vec3(s.occlusion);
}

} // namespace

class TestRenderFabricNodes : public QObject {
    Q_OBJECT
    std::unique_ptr<render::GraphPreview> m_preview;

    /// Renders every output of node @p n of @p g and compares it with @p twin; returns the worst
    /// fraction of pixels off by more than 3/255 over the outputs.
    double compareAll(const Graph& g, NodeId n, const TwinFn& twin, const char* what) {
        const NodeType& type = *g.node(n)->type;
        double worst = 0.0;
        for (PortIndex o = 0; o < type.outputs.size(); ++o) {
            const render::PreviewRequest request{n, o};
            Problems problems;
            const std::vector<Image> images =
                m_preview->render(g, {&request, 1}, nullptr, &problems);
            if (images.empty() || images.front().empty()) {
                for (const Problem& p : problems.items)
                    qWarning("%s", p.toString().c_str());
                return 1.0;
            }
            const Image& img = images.front();
            const PortType t = type.outputs[o].type;
            const int channels = t == PortType::Float ? 1 : t == PortType::Vec2 ? 2 : 3;
            int off = 0;
            float worstPixel = 0.0f;
            for (int y = 0; y < kSide; ++y)
                for (int x = 0; x < kSide; ++x) {
                    const glm::vec2 uv((x + 0.5f) / kSide, (y + 0.5f) / kSide);
                    const glm::vec3 want = shown(twin(uv, type.outputs[o].name), t);
                    const glm::vec4 got = img.rgba(x, y);
                    float d = 0.0f;
                    for (int k = 0; k < channels; ++k)
                        d = std::max(d, std::abs(got[k] - want[k]) * 255.0f);
                    worstPixel = std::max(worstPixel, d);
                    off += d > 3.0f ? 1 : 0;
                }
            const double fraction = double(off) / (kSide * kSide);
            qInfo("%s %s: %.2f %% of pixels off by > 3/255 (worst %.0f/255)", what,
                  std::string(type.outputs[o].name).c_str(), 100.0 * fraction, worstPixel);
            worst = std::max(worst, fraction);
        }
        return worst;
    }

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        m_preview = std::make_unique<render::GraphPreview>(kSide);
    }
    void cleanupTestCase() { m_preview.reset(); }

    void weaveMatchesTwin_data() {
        QTest::addColumn<int>("pattern");
        QTest::addColumn<float>("densityU");
        QTest::addColumn<float>("densityV");
        QTest::newRow("plain") << 0 << 8.0f << 8.0f;
        QTest::newRow("twill 3/1") << 1 << 10.0f << 12.0f;
        QTest::newRow("satin 5, step 2") << 2 << 12.0f << 20.0f;
        QTest::newRow("basket 2x2") << 3 << 16.0f << 16.0f;
        QTest::newRow("herringbone") << 4 << 16.0f << 10.0f;
        // Finer than the thumbnail's pixels: half-way to the mean (half a thread a pixel), and
        // the mean itself (two threads a pixel), as the GPU's fwidth(uv) footprint decides.
        QTest::newRow("plain, half filtered") << 0 << 32.0f << 32.0f;
        QTest::newRow("twill 3/1, filtered") << 1 << 128.0f << 96.0f;
    }
    void weaveMatchesTwin() {
        QFETCH(int, pattern);
        QFETCH(float, densityU);
        QFETCH(float, densityV);
        fab::WeaveParams p;
        p.pattern = float(pattern);
        p.over = 3;
        p.under = 1;
        p.step = pattern == 2 ? 2.0f : 1.0f;
        p.group = pattern == 4 ? 4.0f : 2.0f;
        p.density = {densityU, densityV};
        p.width = 0.8f;
        p.roundness = 1.3f;
        p.warpColor = {0.05f, 0.1f, 0.4f};
        p.weftColor = {0.8f, 0.78f, 0.7f};
        p.crossingHeight = 0.35f;
        p.roughness = 0.7f;
        p.footprint = glm::vec2(1.0f / kSide); // a thumbnail pixel's UV extent (fwidth(uv))
        Graph g;
        const NodeId n = g.addNode("fabric.weave").node;
        set(g, n, "pattern", glm::vec4(p.pattern, 0, 0, 0));
        set(g, n, "over", glm::vec4(p.over, 0, 0, 0));
        set(g, n, "under", glm::vec4(p.under, 0, 0, 0));
        set(g, n, "step", glm::vec4(p.step, 0, 0, 0));
        set(g, n, "group", glm::vec4(p.group, 0, 0, 0));
        set(g, n, "density", glm::vec4(p.density, 0, 0));
        set(g, n, "width", glm::vec4(p.width, 0, 0, 0));
        set(g, n, "roundness", glm::vec4(p.roundness, 0, 0, 0));
        set(g, n, "warpColor", glm::vec4(p.warpColor, 0));
        set(g, n, "weftColor", glm::vec4(p.weftColor, 0));
        set(g, n, "crossingHeight", glm::vec4(p.crossingHeight, 0, 0, 0));
        set(g, n, "roughness", glm::vec4(p.roughness, 0, 0, 0));
        const double worst = compareAll(
            g, n, [&](glm::vec2 uv, std::string_view o) { return weaveOut(fab::weave(uv, p), o); },
            QTest::currentDataTag());
        QVERIFY2(worst <= 0.01, "more than 1 % of a Weave output's pixels differ from the twin");
    }

    void grainMatchesTwin_data() {
        QTest::addColumn<float>("scale");
        QTest::addColumn<float>("irregularity");
        QTest::addColumn<float>("dome");
        QTest::newRow("default (12 cells)")
            << fab::GrainParams{}.scale << fab::GrainParams{}.irregularity
            << fab::GrainParams{}.dome;
        QTest::newRow("square grid, flat tops") << 6.0f << 0.0f << 0.0f;
        // Finer than the thumbnail's pixels: 3/8 of a cell a pixel (a quarter of the way to the
        // mean) and a whole cell a pixel (the mean).
        QTest::newRow("irregular, part filtered") << 24.0f << 1.0f << 0.5f;
        QTest::newRow("filtered") << 64.0f << 0.85f << 0.8f;
    }
    void grainMatchesTwin() {
        QFETCH(float, scale);
        QFETCH(float, irregularity);
        QFETCH(float, dome);
        fab::GrainParams p;
        p.scale = scale;
        p.irregularity = irregularity;
        p.dome = dome;
        p.creaseWidth = 0.25f;
        p.depth = 0.3f;
        p.footprint = glm::vec2(1.0f / kSide);
        Graph g;
        const NodeId n = g.addNode("fabric.grain").node;
        set(g, n, "scale", glm::vec4(p.scale, 0, 0, 0));
        set(g, n, "irregularity", glm::vec4(p.irregularity, 0, 0, 0));
        set(g, n, "dome", glm::vec4(p.dome, 0, 0, 0));
        set(g, n, "creaseWidth", glm::vec4(p.creaseWidth, 0, 0, 0));
        set(g, n, "depth", glm::vec4(p.depth, 0, 0, 0));
        const double worst = compareAll(
            g, n,
            [&](glm::vec2 uv, std::string_view o) {
                const fab::GrainSample s = fab::grain(uv, p);
                return o == "color"       ? s.color
                       : o == "height"    ? glm::vec3(s.height)
                       : o == "normal"    ? s.normal
                       : o == "roughness" ? glm::vec3(s.roughness)
                       : o == "cavity"    ? glm::vec3(s.cavity)
                       : o == "occlusion" ? glm::vec3(s.occlusion)
                                          : glm::vec3(s.cell);
            },
            QTest::currentDataTag());
        QVERIFY2(worst <= 0.01, "more than 1 % of a Grain output's pixels differ from the twin");
    }

    // The nodes' defaults are the twin's defaults (the node table reads them from fabric.h), so
    // an untouched node matches a default-constructed twin.
    void knitFuzzPileMatchTwins() {
        Graph g;
        const NodeId knit = g.addNode("fabric.knit").node;
        const fab::KnitParams kp;
        QVERIFY(compareAll(
                    g, knit,
                    [&](glm::vec2 uv, std::string_view o) {
                        const fab::KnitSample s = fab::knit(uv, kp);
                        return o == "color"       ? s.color
                               : o == "height"    ? glm::vec3(s.height)
                               : o == "normal"    ? s.normal
                               : o == "direction" ? glm::vec3(s.direction, 0.0f)
                                                  : glm::vec3(s.occlusion);
                    },
                    "knit") <= 0.01);

        const NodeId fuzz = g.addNode("fabric.fuzz").node;
        fab::FuzzParams fp;
        fp.density = 40.0f;
        fp.direction = {0.6f, 0.8f};
        fp.amount = 0.9f;
        set(g, fuzz, "density", glm::vec4(fp.density, 0, 0, 0));
        set(g, fuzz, "direction", glm::vec4(fp.direction, 0, 0));
        set(g, fuzz, "amount", glm::vec4(fp.amount, 0, 0, 0));
        QVERIFY(compareAll(
                    g, fuzz,
                    [&](glm::vec2 uv, std::string_view o) {
                        const fab::FuzzSample s = fab::fuzz(uv, fp);
                        return o == "color"       ? s.color
                               : o == "roughness" ? glm::vec3(s.roughness)
                               : o == "sheen"     ? glm::vec3(s.sheen)
                                                  : glm::vec3(s.mask);
                    },
                    "fuzz") <= 0.01);

        const NodeId pile = g.addNode("fabric.pile").node;
        fab::PileParams pp;
        pp.crush = 0.8f;
        pp.scale = 4.0f;
        pp.angle = 30.0f;
        set(g, pile, "crush", glm::vec4(pp.crush, 0, 0, 0));
        set(g, pile, "scale", glm::vec4(pp.scale, 0, 0, 0));
        set(g, pile, "angle", glm::vec4(pp.angle, 0, 0, 0));
        QVERIFY(compareAll(
                    g, pile,
                    [&](glm::vec2 uv, std::string_view o) {
                        const fab::PileSample s = fab::pile(uv, pp);
                        return o == "normal"      ? s.normal
                               : o == "sheen"     ? glm::vec3(s.sheen)
                               : o == "roughness" ? glm::vec3(s.roughness)
                                                  : glm::vec3(s.crush);
                    },
                    "pile") <= 0.01);
    }
};

QTEST_GUILESS_MAIN(TestRenderFabricNodes)
#include "test_render_fabric_nodes.moc"
