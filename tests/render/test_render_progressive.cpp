// Progressive anti-aliasing (render/progressive_accumulation.h): the jitter sequence covers the
// pixel evenly; a jitter of one pixel moves the image by one pixel; the mean weighs every frame
// alike (frames of known, different exposures); it starts from the plain frame; and 16 jittered
// frames come much closer to the 4x4-supersampled picture than the plain frame does.
#include "core/image_ops.h"
#include "render/progressive_accumulation.h"
#include "render_test_util.h"

#include <QtTest>
#include <algorithm>
#include <cmath>
#include <epoxy/gl.h>

using namespace velvet;

namespace {

constexpr int kWidth = 96, kHeight = 64;

/// The mean absolute channel difference over the whole image.
double meanDifference(const Image& a, const Image& b) {
    double sum = 0.0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int k = 0; k < 3; ++k)
                sum += std::abs(a.at(x, y)[k] - b.at(x, y)[k]);
    return sum / double(a.width * a.height * 3);
}

} // namespace

class TestRenderProgressive : public QObject {
    Q_OBJECT
    test::OffscreenRenderer m_rig;

    Image draw(render::FrameSettings fs) {
        std::string error;
        if (!m_rig.target->resize(fs.width, fs.height, &error) ||
            !m_rig.renderer->render(fs, m_rig.target->framebuffer(), &error))
            qFatal("render failed: %s", error.c_str());
        return m_rig.renderer->readDisplay();
    }
    static render::FrameSettings plain(int scale = 1) {
        render::FrameSettings fs;
        fs.width = kWidth * scale;
        fs.height = kHeight * scale;
        fs.displayOnly = true;
        return fs;
    }

private slots:
    void initTestCase() {
        std::string error;
        if (!test::headlessContext(&error))
            QSKIP(qPrintable(QString::fromStdString("no headless context: " + error)));
        error = m_rig.start(kWidth); // each draw sizes the target to its frame
        QVERIFY2(error.empty(), error.c_str());
        // The sharp HDRI behind the sphere: silhouettes against a bright, detailed backdrop.
        Scene scene = forwardPeerScene();
        m_rig.renderer->setScene(scene);
        m_rig.renderer->finishEnvironment();
        m_rig.renderer->finishGraph();
        for (int i = 0; i < 3; ++i) // the specialised programs built
            draw(plain());
    }
    void cleanupTestCase() { m_rig.stop(); }

    /// The first frame sits at the pixel's centre; the first 16 spread over the whole pixel:
    /// none outside it, their mean near its centre, each quadrant holding three to five.
    void jitterCoversThePixel() {
        QCOMPARE(render::progressiveJitter(0), glm::vec2(0.0f));
        glm::vec2 mean(0.0f);
        int quadrant[4] = {};
        for (int i = 0; i < 16; ++i) {
            const glm::vec2 j = render::progressiveJitter(i);
            QVERIFY(j.x >= -0.5f && j.x < 0.5f && j.y >= -0.5f && j.y < 0.5f);
            mean += j / 16.0f;
            ++quadrant[(j.x >= 0.0f ? 1 : 0) + (j.y >= 0.0f ? 2 : 0)];
            for (int k = 0; k < i; ++k) // no two alike
                QVERIFY(render::progressiveJitter(k) != j);
        }
        QVERIFY2(std::abs(mean.x) < 0.05f && std::abs(mean.y) < 0.05f, "centred on the pixel");
        for (int q : quadrant)
            QVERIFY2(q >= 3 && q <= 5, "each quarter of the pixel sampled about as often");
    }

    /// A jitter of one whole pixel to the right moves the picture one pixel to the right (the
    /// offset's sign and scale), up to the background picture's resampling.
    void jitterOfOnePixelShiftsTheImage() {
        const Image still = draw(plain());
        render::FrameSettings fs = plain();
        fs.jitter = glm::vec2(1.0f, 0.0f);
        const Image moved = draw(fs);
        QVERIFY2(test::maxDifference(still, moved) > 20, "the silhouette moved");
        int off = 0, total = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x + 1 < kWidth; ++x, ++total)
                for (int k = 0; k < 3; ++k)
                    if (std::abs(moved.at(x + 1, y)[k] - still.at(x, y)[k]) > 3.0f / 255.0f) {
                        ++off;
                        break;
                    }
        qInfo("pixels off by more than 3/255 after the shift: %d of %d", off, total);
        QVERIFY2(off * 100 <= total, "the shifted image is the image one pixel over");
    }

    /// Starting a mean shows the frame as drawn; the mean of frames at known exposures is
    /// their average, each frame weighed alike (not the last one more).
    void meanWeighsEveryFrameAlike() {
        render::FrameSettings fs = plain();
        const Image dark = draw(fs);
        fs.exposureEv = 1.0f;
        const Image bright = draw(fs);

        fs = plain();
        fs.accumulation = 0;
        const Image started = draw(fs);
        QCOMPARE(m_rig.renderer->accumulatedSamples(), 1);
        QCOMPARE(test::maxDifference(started, dark), 0);

        fs.accumulation = 1;
        draw(fs);
        fs.accumulation = 2;
        fs.exposureEv = 1.0f;
        const Image mean = draw(fs); // (2 dark + bright) / 3
        QCOMPARE(m_rig.renderer->accumulatedSamples(), 3);
        int worst = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x)
                for (int k = 0; k < 3; ++k) {
                    const float expected = (2.0f * dark.at(x, y)[k] + bright.at(x, y)[k]) / 3.0f;
                    worst = std::max(
                        worst, int(std::lround(std::abs(mean.at(x, y)[k] - expected) * 255.0f)));
                }
        QVERIFY2(worst <= 1, qPrintable(QString("off by %1/255").arg(worst)));
        QVERIFY(test::maxDifference(mean, dark) > 10);

        // Accumulation 0 starts again: the plain frame.
        fs = plain();
        fs.accumulation = 0;
        QCOMPARE(test::maxDifference(draw(fs), dark), 0);
        QCOMPARE(m_rig.renderer->accumulatedSamples(), 1);
    }

    /// 16 jittered frames against the picture drawn 4x4 times larger and box-filtered down
    /// (`velvet render --supersample 4`): much closer than the plain frame, most of all along
    /// the silhouette.
    void sixteenFramesApproachTheSupersampledImage() {
        const Image reference = boxDownsample(draw(plain(4)), 4);
        const Image single = draw(plain());
        Image mean;
        for (int i = 0; i < 16; ++i) {
            render::FrameSettings fs = plain();
            fs.accumulation = i;
            fs.jitter = render::progressiveJitter(i);
            mean = draw(fs);
        }
        QCOMPARE(m_rig.renderer->accumulatedSamples(), 16);
        const double before = meanDifference(single, reference);
        const double after = meanDifference(mean, reference);
        qInfo("mean difference from the 4x4 supersampled picture: plain %.5f, 16 frames %.5f",
              before, after);
        QVERIFY2(after < 0.5 * before, "the mean is much nearer the supersampled picture");
        // The aliased pixels themselves: where the plain frame is off by more than 8/255.
        double edgeBefore = 0.0, edgeAfter = 0.0;
        int edges = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                double b = 0.0, a = 0.0;
                for (int k = 0; k < 3; ++k) {
                    b = std::max(b, double(std::abs(single.at(x, y)[k] - reference.at(x, y)[k])));
                    a = std::max(a, double(std::abs(mean.at(x, y)[k] - reference.at(x, y)[k])));
                }
                if (b > 8.0 / 255.0) {
                    edgeBefore += b;
                    edgeAfter += a;
                    ++edges;
                }
            }
        qInfo("%d aliased pixels: off by %.1f/255 on average, %.1f/255 after 16 frames", edges,
              255.0 * edgeBefore / std::max(edges, 1), 255.0 * edgeAfter / std::max(edges, 1));
        QVERIFY2(edges > 50, "the silhouette is aliased in the plain frame");
        QVERIFY2(edgeAfter < 0.35 * edgeBefore, "the aliased pixels settle");
        QVERIFY2(test::maxDifference(mean, reference) < test::maxDifference(single, reference),
                 "the worst edge pixel too");
    }

    /// A refinement frame, and a repaint of the settled mean, leave the GL state a plain frame
    /// leaves the host (Renderer::render's defaults): no program, no vertex array, blending
    /// off with the default factors.
    void leavesTheHostTheDefaultState() {
        render::FrameSettings fs = plain();
        for (int i = 0; i < 3; ++i) {
            fs.accumulation = i;
            fs.jitter = render::progressiveJitter(i);
            draw(fs);
        }
        QVERIFY(m_rig.renderer->showAccumulated(fs.width, fs.height, m_rig.target->framebuffer()));
        GLint program = -1, vao = -1, source = -1, destination = -1;
        glGetIntegerv(GL_CURRENT_PROGRAM, &program);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
        glGetIntegerv(GL_BLEND_SRC_RGB, &source);
        glGetIntegerv(GL_BLEND_DST_RGB, &destination);
        QCOMPARE(program, 0);
        QCOMPARE(vao, 0);
        QVERIFY(!glIsEnabled(GL_BLEND));
        QCOMPARE(source, GLint(GL_ONE));
        QCOMPARE(destination, GLint(GL_ZERO));
    }

    /// The refinement's sub-pixel offsets are no camera motion: with the camera still, the
    /// motion blur leaves a jittered frame as it is (it smeared each one along its offset).
    void jitterIsNoCameraMotion() {
        Scene scene = forwardPeerScene();
        EffectInstance blur = makeEffect("motion_blur");
        blur.params["strength"] = {4.0f};
        scene.post.effects = {blur};
        const auto jittered = [&](bool blurOn) {
            scene.post.effects[0].enabled = blurOn;
            m_rig.renderer->update(scene, ScenePart::PostChain);
            draw(plain()); // the last camera: this one, unjittered
            render::FrameSettings fs = plain();
            fs.jitter = glm::vec2(0.45f, -0.4f);
            return draw(fs);
        };
        const Image blurred = jittered(true), sharp = jittered(false);
        scene.post.effects.clear();
        m_rig.renderer->update(scene, ScenePart::PostChain);
        const int worst = test::maxDifference(blurred, sharp);
        qInfo("motion blur on a jittered frame of a still camera: %d/255 at most", worst);
        QVERIFY2(worst <= 2, qPrintable(QString::number(worst)));
    }
};

QTEST_GUILESS_MAIN(TestRenderProgressive)
#include "test_render_progressive.moc"
