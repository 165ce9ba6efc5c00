// A structural material-graph edit builds its G-buffer program without holding up frames
// (render/renderer.h, "Material graph"; GL_KHR_parallel_shader_compile): until the new program is
// adopted every frame is the old image, bit for bit; then the new image; a build that fails keeps
// the old image and says why (file:line). Mesa's shader disk cache is off (set before the context
// exists) so each build really compiles. The timings are logged, never asserted (DESIGN.md: no
// absolute times). Runs on a copy of resources/shaders (VELVET_RESOURCES) so one case can break
// gbuffer.frag on disk, as test_render_shader_reload does.
#include "core/graph/graph.h"
#include "core/image.h"
#include "core/resources.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render/shader_program.h"
#include "render_test_util.h"
#include "tests/core/graph_test_util.h"

#include <QElapsedTimer>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace velvet;
using namespace velvet::graph;
using velvet::test::link;
namespace fs = std::filesystem;

namespace {

constexpr int kSize = 64;
constexpr int kMaxFrames = 20000; // a build still pending after this many frames is a failure

float centreRed(const Image& img) {
    return img.rgba(kSize / 2, kSize / 2).r;
}

/// constant.float @p v -> output.material roughness (ids 1 and 2).
Graph roughnessFrom(float v) {
    Graph g;
    const NodeId k = g.addNode("constant.float").node;
    const NodeId out = g.addNode(kOutputTypeId).node;
    g.setInputValue(k, 0, glm::vec4(v));
    if (!g.connect(link(g, k, "value", out, "roughness")))
        qFatal("connect failed");
    return g;
}

/// A structural edit of roughnessFrom(): the constant through @p multiplies "× 1" nodes (a
/// new shader text for each count), the roughness still @p v.
Graph roughnessThroughMultiplies(float v, int multiplies) {
    Graph g;
    const NodeId k = g.addNode("constant.float").node;
    const NodeId out = g.addNode(kOutputTypeId).node;
    g.setInputValue(k, 0, glm::vec4(v));
    NodeId previous = k;
    std::string_view output = "value";
    for (int i = 0; i < multiplies; ++i) {
        const NodeId mul = g.addNode("math.multiply").node; // b defaults to 1
        if (!g.connect(link(g, previous, output, mul, "a")))
            qFatal("connect failed");
        previous = mul;
        output = "result";
    }
    if (!g.connect(link(g, previous, output, out, "roughness")))
        qFatal("connect failed");
    return g;
}

Scene withGraph(const Graph& g) {
    Scene scene;
    scene.material.setScalar(ParamId::Roughness, 0.9f); // what the graph overrides
    scene.material.graph = SharedGraph(g);
    return scene;
}

using velvet::test::readText;
using velvet::test::writeText;

} // namespace

class TestRenderGraphAsync : public QObject {
    Q_OBJECT
    std::unique_ptr<QTemporaryDir> m_dir;
    fs::path m_shaders;
    std::unique_ptr<render::Renderer> m_renderer;
    std::unique_ptr<render::OffscreenTarget> m_target;

    /// One Roughness-view frame (the G-buffer's roughness, unlit); @p ms its render() time.
    Image frame(double* ms = nullptr) {
        render::FrameSettings fs;
        fs.width = fs.height = kSize;
        fs.view = render::DebugView::Roughness;
        std::string error;
        QElapsedTimer timer;
        timer.start();
        if (!m_renderer->render(fs, m_target->framebuffer(), &error))
            qFatal("render failed: %s", error.c_str());
        if (ms)
            *ms = double(timer.nsecsElapsed()) / 1e6;
        return m_renderer->readLinear(); // reads back: the frame's GL work has finished
    }

    /// Renders until the pending structure is adopted or fails; every frame before that must be
    /// @p old. Returns the frames drawn while pending (after the one that started the build).
    struct Wait {
        int pendingFrames = 0;
        double startMs = 0, worstPendingMs = 0, adoptMs = 0, nextMs = 0;
        Image adopted;
    };
    Wait renderUntilAdopted(const Image& old) {
        Wait w;
        Image img = frame(&w.startMs);
        while (m_renderer->graphPending() && w.pendingFrames < kMaxFrames) {
            if (!test::samePixels(img, old))
                qFatal("a frame while the build was pending is not the old image");
            double ms = 0;
            img = frame(&ms);
            if (m_renderer->graphPending())
                w.worstPendingMs = std::max(w.worstPendingMs, ms);
            else
                w.adoptMs = ms;
            ++w.pendingFrames;
        }
        w.adopted = img;
        frame(&w.nextMs);
        return w;
    }

private slots:
    void initTestCase() {
        // Before any context: Mesa reads it when the screen is created.
        QVERIFY(qputenv("MESA_SHADER_CACHE_DISABLE", "true"));
        m_dir = std::make_unique<QTemporaryDir>();
        QVERIFY(m_dir->isValid());
        m_shaders = test::useShaderCopy(m_dir->path().toStdString());
        QCOMPARE(resources::path("shaders"), m_shaders);
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        m_renderer = std::make_unique<render::Renderer>();
        QVERIFY2(m_renderer->initialize(&error), error.c_str());
        m_target = std::make_unique<render::OffscreenTarget>();
        QVERIFY2(m_target->resize(kSize, kSize, &error), error.c_str());
        m_renderer->finishEnvironment(); // no bake slices in the frames timed below
        // The compiles counted here are the graph's G-buffer programs alone; the specialised
        // programs built after an adoption are test_render_lighting_features' subject.
        m_renderer->setSpecialisedPrograms(false);
        qInfo("GL_KHR_parallel_shader_compile: %s",
              m_renderer->parallelShaderCompile() ? "yes" : "no");
    }
    void cleanupTestCase() {
        m_target.reset();
        m_renderer.reset();
    }

    // The old image (roughness 0.5 from the graph) in every frame until the new program is
    // adopted, then the new one (0.25), exactly one compile; the synchronous path (finishGraph,
    // today's headless rendering and the build before this change) is measured beside it.
    void oldImageUntilTheNewProgramIsAdopted() {
        m_renderer->setScene(withGraph(roughnessFrom(0.5f)));
        m_renderer->finishGraph();
        QVERIFY(!m_renderer->graphPending());
        const Image old = frame();
        QVERIFY2(std::abs(centreRed(old) - 0.5f) < 0.01f,
                 qPrintable(QString::number(centreRed(old))));
        const int compiles = m_renderer->shaderCompileCount();

        m_renderer->setScene(withGraph(roughnessThroughMultiplies(0.25f, 3)));
        QVERIFY(m_renderer->graphPending());
        QCOMPARE(m_renderer->shaderCompileCount(), compiles); // nothing built in setScene
        const Wait w = renderUntilAdopted(old);
        QVERIFY(!m_renderer->graphPending());
        QVERIFY2(m_renderer->graphError().empty(), m_renderer->graphError().c_str());
        QCOMPARE(m_renderer->shaderCompileCount(), compiles + 1);
        const float r = centreRed(w.adopted);
        QVERIFY2(std::abs(r - 0.25f) < 0.01f, qPrintable(QString::number(r)));
        if (!m_renderer->parallelShaderCompile())
            QCOMPARE(w.pendingFrames, 0); // the fallback builds in the first frame

        // The same kind of edit built synchronously before the frame (the behaviour before
        // this change): one render() holds compile, link and the first draw.
        m_renderer->setScene(withGraph(roughnessThroughMultiplies(0.75f, 4)));
        QElapsedTimer timer;
        timer.start();
        m_renderer->finishGraph();
        double syncFrameMs = 0;
        const Image syncImage = frame(&syncFrameMs);
        const double syncMs = double(timer.nsecsElapsed()) / 1e6;
        const double syncBuildMs = syncMs - syncFrameMs;
        QVERIFY(!m_renderer->graphPending());
        QCOMPARE(m_renderer->shaderCompileCount(), compiles + 2);
        QVERIFY2(std::abs(centreRed(syncImage) - 0.75f) < 0.01f,
                 qPrintable(QString::number(centreRed(syncImage))));
        double nextMs = 0;
        frame(&nextMs);
        qInfo("structural edit, asynchronous: the render() that starts the build %.1f ms, %d "
              "frames pending (worst %.1f ms), the frame that adopts and first draws the new "
              "program %.1f ms, the next %.1f ms",
              w.startMs, w.pendingFrames, w.worstPendingMs, w.pendingFrames ? w.adoptMs : w.startMs,
              w.nextMs);
        qInfo("structural edit, synchronous (finishGraph + render, as before): %.1f ms: compile "
              "and link %.1f ms, the first frame with the new program (llvmpipe JITs its "
              "fragment code at the first draw) %.1f ms; the next frame %.1f ms",
              syncMs, syncBuildMs, syncFrameMs, nextMs);
    }

    // A second structural edit while one is in flight replaces it: one compile, the second
    // structure's image, never the first's.
    void aNewerEditReplacesTheBuildInFlight() {
        m_renderer->setScene(withGraph(roughnessFrom(0.5f)));
        m_renderer->finishGraph();
        const Image old = frame();
        const int compiles = m_renderer->shaderCompileCount();
        m_renderer->setScene(withGraph(roughnessThroughMultiplies(0.25f, 5)));
        // Starts the first build (adopted at once where the driver compiles synchronously).
        const Image afterStart = frame();
        const int afterFirst = m_renderer->shaderCompileCount();
        QVERIFY(afterFirst == compiles || afterFirst == compiles + 1);
        QVERIFY(afterFirst == compiles + 1 || test::samePixels(afterStart, old));
        m_renderer->setScene(withGraph(roughnessThroughMultiplies(0.125f, 6)));
        const Wait w = renderUntilAdopted(afterStart);
        QCOMPARE(m_renderer->shaderCompileCount(), afterFirst + 1);
        const float r = centreRed(w.adopted);
        QVERIFY2(std::abs(r - 0.125f) < 0.01f, qPrintable(QString::number(r)));
    }

    // gbuffer.frag broken on disk: the structural edit's build fails when polled; every frame
    // stays the old image, graphError names gbuffer.frag:line, nothing is counted; mended, the
    // next structural edit is adopted.
    void aFailedBuildKeepsTheOldImage() {
        m_renderer->setScene(withGraph(roughnessFrom(0.5f)));
        m_renderer->finishGraph();
        const Image old = frame();
        const int compiles = m_renderer->shaderCompileCount();
        const fs::path file = m_shaders / "gbuffer.frag";
        const std::string good = readText(file);
        const size_t main = good.find("void main()");
        QVERIFY(main != std::string::npos);
        const int line = int(std::count(good.begin(), good.begin() + long(main), '\n')) + 1;
        writeText(file, good.substr(0, main) + "this is not glsl;\n" + good.substr(main));

        m_renderer->setScene(withGraph(roughnessThroughMultiplies(0.25f, 2)));
        const Wait w = renderUntilAdopted(old);
        writeText(file, good);
        QVERIFY(!m_renderer->graphPending());
        QVERIFY(test::samePixels(w.adopted, old));
        const std::string& message = m_renderer->graphError();
        qInfo("%s", message.c_str());
        QVERIFY2(message.find("gbuffer.frag:" + std::to_string(line)) != std::string::npos,
                 message.c_str());
        QCOMPARE(m_renderer->shaderCompileCount(), compiles);

        m_renderer->setScene(withGraph(roughnessThroughMultiplies(0.25f, 1)));
        const Wait mended = renderUntilAdopted(old);
        QVERIFY2(m_renderer->graphError().empty(), m_renderer->graphError().c_str());
        QVERIFY2(std::abs(centreRed(mended.adopted) - 0.25f) < 0.01f,
                 qPrintable(QString::number(centreRed(mended.adopted))));
        QCOMPARE(m_renderer->shaderCompileCount(), compiles + 1);
    }

    // ProgramBuild on its own: a broken generated include polls to completion without blocking
    // the caller's loop, then fails naming the include's file:line; the target keeps its program.
    void programBuildReportsFileAndLine() {
        render::ShaderProgram program;
        std::string error;
        render::ProgramBuild build;
        QVERIFY2(build.start("gbuffer.vert", "gbuffer.frag", {},
                             {{"material_graph.glsl", "\n\nnot glsl at all;\n"}}, &error),
                 error.c_str());
        QVERIFY(build.active());
        int polls = 0;
        while (!build.ready() && polls < 1000000)
            ++polls;
        QVERIFY(!build.finish(program, &error));
        QVERIFY(!build.active());
        QCOMPARE(program.id(), 0u);
        qInfo("polls until done %d: %s", polls, error.c_str());
        QVERIFY2(error.find("material_graph.glsl:3") != std::string::npos, error.c_str());
    }
};

QTEST_GUILESS_MAIN(TestRenderGraphAsync)
#include "test_render_graph_async.moc"
