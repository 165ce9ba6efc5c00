// The display step inside the lighting pass (FrameSettings::displayOnly, issue 16): the post
// chain's one fused pass, or the built-in curve, compiled into the background and surface
// programs draws the same pixels as the path through the scene-linear target, with one
// full-screen pass fewer and no linear image; frames it cannot draw take the old path; value
// edits still compile nothing. And the lobe-channel targets only when something reads them.
#include "core/post_effects.h"
#include "render_test_util.h"

#include <QtTest>
#include <algorithm>
#include <cmath>
#include <glm/trigonometric.hpp>

using namespace velvet;

namespace {

constexpr int kWidth = 256, kHeight = 144; // not square: a swapped axis would show

struct Comparison {
    int maxDifference = 0; ///< in 1/255 steps, any channel
    int differing = 0;     ///< pixels with any channel different
};

double sum(const Image& image) {
    double s = 0.0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            s += image.at(x, y)[0] + image.at(x, y)[1] + image.at(x, y)[2];
    return s;
}

Comparison compare(const Image& a, const Image& b) {
    Comparison c;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            int worst = 0;
            for (int k = 0; k < 3; ++k)
                worst = std::max(
                    worst, int(std::lround(std::abs(a.at(x, y)[k] - b.at(x, y)[k]) * 255.0f)));
            c.maxDifference = std::max(c.maxDifference, worst);
            c.differing += worst > 0;
        }
    return c;
}

} // namespace

class TestRenderInlineDisplay : public QObject {
    Q_OBJECT
    std::unique_ptr<render::Renderer> m_renderer;
    std::unique_ptr<render::OffscreenTarget> m_target;
    render::FrameSettings m_fs;

    Image draw(bool displayOnly) {
        m_fs.displayOnly = displayOnly;
        std::string error;
        if (!m_renderer->render(m_fs, m_target->framebuffer(), &error))
            qFatal("render failed: %s", error.c_str());
        return m_renderer->readDisplay();
    }

    /// The scene drawn both ways (the inline path twice: its first frame builds its programs).
    /// Verifies the same pixels and the passes; returns the inline image.
    Image checkSame(const Scene& scene) {
        m_renderer->setScene(scene);
        m_renderer->finishEnvironment();
        m_renderer->finishGraph();
        const Image linearPath = draw(false);
        const render::FramePasses before = m_renderer->lastFramePasses();
        draw(true);
        const render::FramePasses first = m_renderer->lastFramePasses();
        const Image inlinePath = draw(true);
        const render::FramePasses after = m_renderer->lastFramePasses();
        // Before: background, surfaces, the display step (the chain's fused pass or the
        // display pass), the linear image kept. Inline: background and surfaces, one copy; the
        // same frame again keeps the background's pixels (render/frame_reuse.h), so the
        // comparison below also checks the kept pixels.
        if (!before.linear || before.inlineDisplay || before.fullScreen != 3 || before.copies != 0)
            QTest::qFail("the linear path's passes", __FILE__, __LINE__);
        if (!first.inlineDisplay || first.backgroundKept || first.fullScreen != 2)
            QTest::qFail("the first inline frame's passes", __FILE__, __LINE__);
        if (!after.inlineDisplay || after.linear || !after.backgroundKept ||
            after.fullScreen != 1 || after.copies != 1)
            QTest::qFail("the inline path's passes", __FILE__, __LINE__);
        if (!m_renderer->readLinear().empty())
            QTest::qFail("readLinear after a display-only frame", __FILE__, __LINE__);
        // The same computation, except that the linear path stores the lit colour as half
        // floats (11 significant bits) before the tone map: a value within that rounding of an
        // 8-bit step may land on the other side (measured: 1.4-1.7 % of the pixels), never
        // further.
        const Comparison c = compare(linearPath, inlinePath);
        qInfo("inline against linear path: max %d/255, %d of %d pixels differ", c.maxDifference,
              c.differing, kWidth * kHeight);
        if (c.maxDifference > 1 || c.differing > kWidth * kHeight / 20)
            QTest::qFail("the inline path's pixels differ", __FILE__, __LINE__);
        // Opaque like the display pass's output, the sphere's pixels too.
        for (const Image* image : {&linearPath, &inlinePath})
            if (image->at(kWidth / 2, kHeight / 2)[3] != 1.0f || image->at(1, 1)[3] != 1.0f)
                QTest::qFail("alpha is not 1", __FILE__, __LINE__);
        return inlinePath;
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
    }
    void cleanupTestCase() {
        m_target.reset();
        m_renderer.reset();
    }

    /// The bench's frame: the chain's tone map inside the lighting pass.
    void chainToneMapSamePixels() {
        const Image image = checkSame(forwardPeerScene());
        const float* centre = image.at(kWidth / 2, kHeight / 2);
        QVERIFY2(centre[0] > centre[1] && centre[0] > 0.2f, "the sphere's centre");
        // Not a blank frame: the sphere's centre is lit crimson; the studio's dark backdrop is
        // not black.
        QVERIFY(image.at(2, 2)[2] > 0.0f);
    }

    /// Several pointwise effects in the one fused pass: HDR colour grading, the tone map (ACES),
    /// a vignette reading the pixel's position from the frame block.
    void fusedChainSamePixels() {
        Scene scene = forwardPeerScene();
        EffectInstance grading = makeEffect("color_grading");
        grading.params["saturation"] = {1.4f};
        grading.params["exposure"] = {0.5f};
        scene.post.effects.insert(scene.post.effects.begin(), grading);
        scene.post.effects[1].params["operator"] = {float(toneMapOperatorIndex("aces"))};
        EffectInstance vignette = makeEffect("vignette");
        vignette.params["intensity"] = {1.0f}; // a white border, read from its parameters
        vignette.params["blend"] = {1.0f};
        vignette.params["color"] = {1.0f, 1.0f, 1.0f};
        scene.post.effects.push_back(vignette);
        const Image image = checkSame(scene);
        // The vignette is there: the white border brightens the dark studio.
        scene.post.effects.pop_back();
        const Image without = checkSame(scene);
        qInfo("with the vignette %.0f, without %.0f", sum(image), sum(without));
        QVERIFY(sum(image) > 1.5 * sum(without));
    }

    /// No chain: the built-in curve and the display encoding (display_output.frag's path), with
    /// an exposure and another curve.
    void builtInCurveSamePixels() {
        Scene scene = forwardPeerScene();
        scene.post = PostChain{};
        m_fs.exposureEv = 0.7f;
        m_fs.toneMapper = render::ToneMapper::AcesFitted;
        checkSame(scene);
        m_fs.exposureEv = 0.0f;
        m_fs.toneMapper = render::ToneMapper::KhronosPbrNeutral;
    }

    /// Frames the inline path cannot draw keep the linear target and the old passes.
    // render/background_downsample.h: a picture without fine detail under a smooth display step
    // is drawn smaller and upsampled; the linear path draws it at full size. The blurred level
    // at a quarter, the shipped 1024-wide HDRI through a narrow lens (about 9 pixels a texel) at
    // a half; grain and the sharp HDRI at this size (1.4 pixels a texel) at full size.
    void backgroundDrawnSmallerLooksTheSame_data() {
        QTest::addColumn<int>("background");
        QTest::addColumn<float>("fovY");
        QTest::addColumn<bool>("grain");
        QTest::addColumn<int>("factor");
        QTest::addColumn<int>("tolerance");    // in 1/255: measured 2, 3, 1, 1
        QTest::addColumn<int>("differingPct"); // of the pixels: measured 38, 10, 2, 6
        QTest::newRow("blurred") << int(BackgroundMode::Blurred) << 35.0f << false << 4 << 2 << 45;
        QTest::newRow("sharp, 6 degrees")
            << int(BackgroundMode::Sharp) << 6.0f << false << 2 << 4 << 15;
        QTest::newRow("sharp, 35 degrees")
            << int(BackgroundMode::Sharp) << 35.0f << false << 1 << 1 << 15;
        QTest::newRow("blurred, grain")
            << int(BackgroundMode::Blurred) << 35.0f << true << 1 << 1 << 15;
    }
    void backgroundDrawnSmallerLooksTheSame() {
        QFETCH(int, background);
        QFETCH(float, fovY);
        QFETCH(bool, grain);
        QFETCH(int, factor);
        QFETCH(int, tolerance);
        QFETCH(int, differingPct);
        Scene scene = forwardPeerScene();
        scene.environment.background = BackgroundMode(background);
        scene.camera.fovYDeg = fovY;
        // The sphere the same size in the frame.
        scene.camera.distance =
            4.5f * std::tan(glm::radians(17.5f)) / std::tan(glm::radians(fovY * 0.5f));
        if (grain)
            scene.post.effects.push_back(makeEffect("film_grain"));
        m_renderer->setScene(scene);
        m_renderer->finishEnvironment();
        m_renderer->finishGraph();
        // Frames at rest (sampled reflections, none for this rough velvet): a moving frame would
        // draw the HDRI as a dome (test_render_background_dome).
        m_fs.reflectionSamples = render::kRefinementReflectionSamples;
        const Image linearPath = draw(false);
        draw(true);                                   // builds the inline programs
        m_renderer->update(scene, ScenePart::Camera); // not a value edit: the background is drawn
        const Image inlinePath = draw(true);
        m_fs.reflectionSamples = 0;
        QCOMPARE(m_renderer->lastFramePasses().backgroundDownsample, factor);
        QVERIFY(!m_renderer->lastFramePasses().backgroundDome);
        QVERIFY(m_renderer->lastFramePasses().inlineDisplay);
        const Comparison c = compare(linearPath, inlinePath);
        qInfo("downsampled %d: max %d/255, %d of %d pixels differ", factor, c.maxDifference,
              c.differing, kWidth * kHeight);
        // The linear path's half-float rounding moves 1.5 % of the pixels by 1/255 already
        // (checkSame); a smaller background, whose 8-bit texels are rounded before the upsample
        // and again after it, moves 38 % by 1 or 2 255ths (the blurred level: a smooth ramp
        // rounded twice), and a sharp HDRI's texel edges by a few 255ths in 10 % of the pixels.
        QVERIFY2(c.maxDifference <= tolerance, qPrintable(QString::number(c.maxDifference)));
        QVERIFY2(c.differing <= kWidth * kHeight * differingPct / 100,
                 qPrintable(QString::number(c.differing)));
    }

    void otherFramesKeepTheLinearPath() {
        // A chain that reads neighbouring pixels.
        Scene bloom = forwardPeerScene();
        bloom.post.effects.insert(bloom.post.effects.begin(), makeEffect("bloom"));
        m_renderer->setScene(bloom);
        draw(true);
        draw(true);
        QVERIFY(!m_renderer->lastFramePasses().inlineDisplay);
        QVERIFY(m_renderer->lastFramePasses().linear);
        // Emission is added in the linear target.
        Scene glowing = forwardPeerScene();
        glowing.material.setColor(ParamId::EmissiveColor, {0.2f, 0.1f, 0.0f});
        glowing.material.setScalar(ParamId::EmissiveStrength, 1.0f);
        m_renderer->setScene(glowing);
        draw(true);
        draw(true);
        QVERIFY(!m_renderer->lastFramePasses().inlineDisplay);
        // A debug view.
        m_renderer->setScene(forwardPeerScene());
        m_fs.view = render::DebugView::Normal;
        draw(true);
        m_fs.view = render::DebugView::Final;
        QVERIFY(!m_renderer->lastFramePasses().inlineDisplay);
        QVERIFY(!m_renderer->readLinear().empty());
    }

    /// The lobe-channel targets are cleared and written only when a drawn material has a lobe
    /// map: crimson velvet has none (3 of 5 targets); a split frame keeps them (B may have one).
    void lobeTargetsOnlyWhenRead() {
        m_renderer->setScene(forwardPeerScene());
        draw(true);
        QCOMPARE(m_renderer->lastFramePasses().gbufferTargets, 3);
        m_fs.splitMaterial = forwardPeerScene().material;
        draw(true);
        m_fs.splitMaterial.reset();
        QCOMPARE(m_renderer->lastFramePasses().gbufferTargets, 5);
    }

    /// A material value edit and a tone-map parameter edit compile nothing on the inline path
    /// and show at once.
    void valueEditsCompileNothing() {
        Scene scene = forwardPeerScene();
        m_renderer->setScene(scene);
        draw(true);
        const Image before = draw(true);
        QVERIFY(m_renderer->lastFramePasses().inlineDisplay);
        const int compiles = m_renderer->shaderCompileCount();
        scene.material.setScalar(ParamId::Roughness, 0.6f);
        m_renderer->update(scene, ScenePart::MaterialValues);
        const Image edited = draw(true);
        QVERIFY(m_renderer->lastFramePasses().inlineDisplay);
        scene.post.effects[0].params["exposure"] = {1.0f};
        m_renderer->update(scene, ScenePart::PostChain);
        const Image brighter = draw(true);
        QVERIFY(m_renderer->lastFramePasses().inlineDisplay);
        QCOMPARE(m_renderer->shaderCompileCount(), compiles);
        QVERIFY(compare(before, edited).differing > 0);
        const float* a = edited.at(kWidth / 2, kHeight / 2);
        const float* b = brighter.at(kWidth / 2, kHeight / 2);
        QVERIFY(b[0] > a[0]);
    }
};

QTEST_GUILESS_MAIN(TestRenderInlineDisplay)
#include "test_render_inline_display.moc"
