// The inline frame keeps the last frame's background pixels when nothing they depend on changed
// (render/frame_reuse.h, issue 16): after a material value edit the background pass does not
// run and the image is the one a frame drawing every pixel gives, to the bit; a camera move, an
// environment rotation, an exposure, a texture slot, a time that film grain reads, a size or a
// frame off the inline path each draw the background again.
#include "core/post_effects.h"
#include "render_test_util.h"

#include <QtTest>
#include <algorithm>
#include <cmath>

using namespace velvet;

namespace {

constexpr int kWidth = 160, kHeight = 96;

} // namespace

class TestRenderFrameReuse : public QObject {
    Q_OBJECT
    std::unique_ptr<render::Renderer> m_renderer;
    std::unique_ptr<render::OffscreenTarget> m_target;
    render::FrameSettings m_fs;
    Scene m_scene;

    Image draw() {
        std::string error;
        if (!m_renderer->render(m_fs, m_target->framebuffer(), &error))
            qFatal("render failed: %s", error.c_str());
        return m_renderer->readDisplay();
    }
    bool kept() const {
        const render::FramePasses p = m_renderer->lastFramePasses();
        if (!p.inlineDisplay)
            qFatal("the frame did not take the inline path");
        return p.backgroundKept;
    }
    /// The scene as a whole (every part changed), drawn until the background is kept once: the
    /// specialised programs built and the inline path steady.
    void settle(const Scene& scene) {
        m_scene = scene;
        m_renderer->setScene(scene);
        m_renderer->finishEnvironment();
        m_renderer->finishGraph();
        for (int i = 0; i < 4; ++i)
            draw();
        QVERIFY2(kept(), "a frame that repeats the last one keeps the background");
    }

private slots:
    void initTestCase() {
        std::string error;
        if (!test::headlessContext(&error))
            QSKIP(qPrintable(QString::fromStdString("no headless context: " + error)));
        m_renderer = std::make_unique<render::Renderer>();
        m_target = std::make_unique<render::OffscreenTarget>();
        QVERIFY2(m_renderer->initialize(&error), error.c_str());
        QVERIFY2(m_target->resize(kWidth, kHeight, &error), error.c_str());
        m_fs.width = kWidth;
        m_fs.height = kHeight;
        m_fs.displayOnly = true;
    }
    void cleanupTestCase() {
        m_target.reset();
        m_renderer.reset();
    }
    void init() {
        m_fs = render::FrameSettings{};
        m_fs.width = kWidth;
        m_fs.height = kHeight;
        m_fs.displayOnly = true;
    }

    /// A value edit keeps the background, and the frame is the one drawn in full.
    void valueEditKeepsBackgroundSamePixels() {
        settle(forwardPeerScene());
        const Image before = draw();
        Scene edited = m_scene;
        edited.material.setColor(ParamId::BaseColor, {0.1f, 0.6f, 0.2f});
        edited.material.setScalar(ParamId::Roughness, 0.2f);
        m_renderer->update(edited, ScenePart::MaterialValues);
        const Image kept = draw();
        QVERIFY2(this->kept(), "a value edit keeps the background");
        QVERIFY2(test::maxDifference(before, kept) > 10, "the edit shows on the sphere");
        // The same scene with every part changed: the background drawn again.
        m_renderer->update(edited, ScenePart::All);
        const Image full = draw();
        QVERIFY(!this->kept());
        QCOMPARE(test::maxDifference(kept, full), 0);
        // The background's pixels themselves: the corner is the backdrop, not black.
        QVERIFY(full.at(1, 1)[0] + full.at(1, 1)[1] + full.at(1, 1)[2] > 0.0f);
    }

    /// Everything the background's pixels depend on draws them again.
    void changesDrawBackground() {
        settle(forwardPeerScene());
        const Image still = draw();
        QVERIFY(kept());

        Camera orbit = m_scene.camera;
        orbit.yawDeg += 10.0f;
        m_fs.camera = orbit;
        const Image orbited = draw();
        QVERIFY2(!kept(), "a camera move");
        QVERIFY(test::maxDifference(still, orbited) > 0);
        draw();
        QVERIFY2(kept(), "the orbit's camera, held");
        m_fs.camera.reset();
        draw();
        QVERIFY(!kept());

        m_fs.exposureEv = 1.0f;
        const Image brighter = draw();
        QVERIFY2(!kept(), "an exposure change");
        QVERIFY2(test::maxDifference(still, brighter) > 10, "the exposure shows");
        m_fs.exposureEv = 0.0f;
        draw();

        Scene rotated = m_scene;
        rotated.environment.rotationDeg += 90.0f;
        m_renderer->update(rotated, ScenePart::Environment);
        m_renderer->finishEnvironment();
        draw();
        QVERIFY2(!kept(), "an environment rotation");

        m_renderer->update(m_scene, ScenePart::MaterialStructure);
        draw();
        QVERIFY2(!kept(), "a texture slot (its cut-out may change the coverage)");

        // The time: read by nothing in this scene, so kept; read by film grain, drawn.
        draw();
        m_fs.time = 1.0f;
        draw();
        QVERIFY2(kept(), "the time, which nothing reads");
        Scene grainy = m_scene;
        EffectInstance grain = makeEffect("film_grain");
        grainy.post.effects.push_back(grain);
        m_renderer->update(grainy, ScenePart::PostChain);
        draw();
        draw();
        m_fs.time = 2.0f;
        draw();
        QVERIFY2(!m_renderer->lastFramePasses().inlineDisplay || !kept(),
                 "the time, which the grain reads");
        m_renderer->update(m_scene, ScenePart::PostChain);
        draw();

        // A frame off the inline path (the scene-linear target) leaves nothing to keep.
        m_fs.displayOnly = false;
        draw();
        m_fs.displayOnly = true;
        draw();
        QVERIFY2(!kept(), "after a frame through the scene-linear target");
    }
};

QTEST_GUILESS_MAIN(TestRenderFrameReuse)
#include "test_render_background_reuse.moc"
