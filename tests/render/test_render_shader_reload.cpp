// Renderer::reloadShaders() (the editor's T) recompiles every program from disk: G-buffer,
// lighting, tone map, the three light paths, the IBL bake's compute programs and the cached OCIO
// display program. The test runs on a copy of resources/shaders (VELVET_RESOURCES, set before the
// renderer exists), breaks each file in turn: reload fails naming file:line, frames still render
// with the last good programs on every light path and through OCIO; mended, reload succeeds.
// The post chain's programs (one-pass, multi-pass and fused effects) reload the same way, and
// the frame drawn with a broken post shader is the frame drawn before (the last good programs).
#include "core/post_effects.h"
#include "core/resources.h"
#include "render/offscreen.h"
#include "render/post_chain.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QtTest>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

using namespace velvet;
namespace fs = std::filesystem;

namespace {

using velvet::test::readText;
using velvet::test::writeText;

} // namespace

class TestRenderShaderReload : public QObject {
    Q_OBJECT

    std::unique_ptr<QTemporaryDir> m_dir;
    fs::path m_shaders;

    bool renderAllPaths(render::Renderer& renderer, render::OffscreenTarget& target,
                        std::string* error) {
        render::FrameSettings frame;
        frame.width = frame.height = 48;
        for (auto path :
             {render::LightPath::Tiled, render::LightPath::Volumes, render::LightPath::Brute}) {
            frame.lightPath = path;
            if (!renderer.render(frame, target.framebuffer(), error))
                return false;
        }
        frame.displayView = "ACES"; // the OCIO display program
        return renderer.render(frame, target.framebuffer(), error);
    }

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        // A resources root whose shaders are a copy (the rest links to the real files).
        m_dir = std::make_unique<QTemporaryDir>();
        QVERIFY(m_dir->isValid());
        m_shaders = test::useShaderCopy(m_dir->path().toStdString());
        QCOMPARE(resources::path("shaders"), m_shaders);
    }

    void reloadBreaksAndMendsEveryProgram_data() {
        QTest::addColumn<QString>("file");
        for (const char* f :
             {"gbuffer.frag", "lighting.frag", "display_output.frag", "light_tiled.comp",
              "light_volume.vert", "light_volume.frag", "light_brute.frag",
              "ibl_equirect_to_cube.comp", "ibl_downsample.comp", "ibl_prefilter.comp",
              "ibl_dfg.comp", "display_transform.frag", "light_common.glsl"})
            QTest::newRow(f) << QString(f);
    }

    void reloadBreaksAndMendsEveryProgram() {
        QFETCH(QString, file);
        std::string error;
        render::Renderer renderer;
        QVERIFY2(renderer.initialize(&error), error.c_str());
        Scene scene;
        Light spot;
        spot.type = LightType::Spot;
        spot.position = {0.0f, 0.0f, 2.0f};
        spot.direction = {0.0f, 0.0f, -1.0f};
        spot.range = 4.0f;
        spot.outerConeDeg = 30.0f;
        scene.lights = {spot};
        renderer.setScene(scene);
        render::OffscreenTarget target;
        QVERIFY2(target.resize(48, 48, &error), error.c_str());
        QVERIFY2(renderAllPaths(renderer, target, &error), error.c_str());

        const fs::path path = m_shaders / file.toStdString();
        const std::string good = readText(path);
        QVERIFY(!good.empty());
        const int badLine = int(std::count(good.begin(), good.end(), '\n')) + 1;
        writeText(path, good + "this is not GLSL;\n");
        const int before = renderer.shaderCompileCount();
        const bool ok = renderer.reloadShaders(&error);
        writeText(path, good); // mend first, so a failing check leaves the copy whole
        QVERIFY(!ok);
        const std::string where = file.toStdString() + ":" + std::to_string(badLine);
        QVERIFY2(
            error.find(where) != std::string::npos,
            qPrintable(QString("expected %1 in: %2")
                           .arg(QString::fromStdString(where), QString::fromStdString(error))));
        // The last good programs keep drawing, on every path and through OCIO.
        QVERIFY2(renderAllPaths(renderer, target, &error), error.c_str());

        QVERIFY2(renderer.reloadShaders(&error), error.c_str());
        QVERIFY(renderer.shaderCompileCount() > before);
        QVERIFY2(renderAllPaths(renderer, target, &error), error.c_str());
    }

    // The post chain's programs are built on first use; T recompiles them too. Pixelate is one
    // pass, bloom four programs of one file, vignette and tone map one fused pass.
    void reloadBreaksAndMendsPostChainPrograms_data() {
        QTest::addColumn<QString>("file");
        for (const char* f : {"post_pixelate.frag", "post_bloom.frag", "post_vignette.glsl",
                              "post_tonemap.glsl", "post_common.glsl"})
            QTest::newRow(f) << QString(f);
    }

    void reloadBreaksAndMendsPostChainPrograms() {
        QFETCH(QString, file);
        std::string error;
        render::Renderer renderer;
        QVERIFY2(renderer.initialize(&error), error.c_str());
        Scene scene;
        scene.post.effects = {makeEffect("bloom"), makeEffect("pixelate"), makeEffect("tonemap"),
                              makeEffect("vignette")};
        renderer.setScene(scene);
        render::OffscreenTarget target;
        QVERIFY2(target.resize(48, 48, &error), error.c_str());
        render::FrameSettings frame;
        frame.width = frame.height = 48;
        QVERIFY2(renderer.render(frame, target.framebuffer(), &error), error.c_str());
        const Image before = renderer.readDisplay();
        const int postCompiles = renderer.postChain().compileCount();
        QVERIFY(postCompiles >= 3);

        const fs::path path = m_shaders / file.toStdString();
        const std::string good = readText(path);
        QVERIFY(!good.empty());
        const int badLine = int(std::count(good.begin(), good.end(), '\n')) + 1;
        writeText(path, good + "this is not GLSL;\n");
        const bool ok = renderer.reloadShaders(&error);
        writeText(path, good);
        QVERIFY(!ok);
        const std::string where = file.toStdString() + ":" + std::to_string(badLine);
        QVERIFY2(
            error.find(where) != std::string::npos,
            qPrintable(QString("expected %1 in: %2")
                           .arg(QString::fromStdString(where), QString::fromStdString(error))));
        // The reload did rebuild the post programs the broken file is not part of (every post
        // program includes post_common.glsl), and the frame still renders, identical to the one
        // before: the last good programs drew it.
        if (file != "post_common.glsl")
            QVERIFY(renderer.postChain().compileCount() > postCompiles);
        QVERIFY2(renderer.render(frame, target.framebuffer(), &error), error.c_str());
        const Image after = renderer.readDisplay();
        QCOMPARE(after.pixels.size(), before.pixels.size());
        QVERIFY(after.pixels == before.pixels);

        const int mended = renderer.postChain().compileCount();
        QVERIFY2(renderer.reloadShaders(&error), error.c_str());
        QVERIFY(renderer.postChain().compileCount() > mended);
        QVERIFY2(renderer.render(frame, target.framebuffer(), &error), error.c_str());
        QVERIFY(renderer.readDisplay().pixels == before.pixels);
    }
};

QTEST_GUILESS_MAIN(TestRenderShaderReload)
#include "test_render_shader_reload.moc"
