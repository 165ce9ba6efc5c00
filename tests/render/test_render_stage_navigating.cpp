// The look-dev stage in frames drawn while the camera moves (FrameSettings::navigating): the
// shadow masks and the occlusion at a quarter of the frame's size each way instead of half
// (render/stage_interface.h). Their texels are a quarter as many; the picture stays close to the
// frame at rest's; a frame at rest never keeps a navigating frame's masks or occlusion (nor the
// other way round), so the view at rest after an orbit is the still frame to the bit. The known
// answers at a quarter are test_render_shadows' "navigating" rows.
#include "core/document_io.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QtTest>

using namespace velvet;

namespace {

constexpr int kWidth = 384, kHeight = 256;

/// The shader ball on a shadow catcher under a shadowed key light, with occlusion: issue 14's
/// stage (render/stage_bench.cpp).
Scene shadowedStage() {
    Scene scene;
    scene.mesh.kind = PreviewMeshKind::ShaderBall;
    scene.environment.ground = GroundMode::ShadowCatcher;
    scene.environment.ambientOcclusion = true;
    Light key = test::analyticKeyLight();
    key.castShadows = true;
    scene.lights = {key};
    return scene;
}

} // namespace

class TestRenderStageNavigating : public QObject {
    Q_OBJECT
    test::OffscreenRenderer* m_rig = nullptr;
    render::FrameSettings m_fs;

    /// The next frame, navigating or at rest; its linear image.
    Image draw(bool navigating) {
        std::string error;
        m_fs.navigating = navigating;
        if (!m_rig->renderer->render(m_fs, m_rig->target->framebuffer(), &error))
            qFatal("render failed: %s", error.c_str());
        return m_rig->renderer->readLinear();
    }
    render::FrameTimings timings() const { return m_rig->renderer->lastTimings(); }

private slots:
    void initTestCase() {
        std::string error;
        m_rig = test::startProcessRenderer(kWidth, kHeight, &error);
        QVERIFY2(m_rig, error.c_str());
        m_fs.width = kWidth;
        m_fs.height = kHeight;
    }

    void cleanupTestCase() {
        test::stopProcessRenderer(); // while the context is current
    }

    void init() {
        m_fs.camera.reset();
        m_rig->renderer->setScene(shadowedStage());
        m_rig->renderer->finishEnvironment();
    }

    // A quarter of the mask's texels, and a picture that differs from the frame at rest's only
    // about the shadows' and the occlusion's edges.
    void aQuarterOfTheTexelsAndAClosePicture() {
        const Image rest = draw(false);
        const render::FrameTimings atRest = timings();
        const Image moving = draw(true);
        const render::FrameTimings navigating = timings();
        QVERIFY(!navigating.shadowMaskKept && !navigating.occlusionKept);
        QVERIFY(atRest.shadowMaskTexels > 0);
        const double texels = double(navigating.shadowMaskTexels) / double(atRest.shadowMaskTexels);
        const int differ = test::differingPixels(rest, moving, 8);
        const int far = test::differingPixels(rest, moving, 32);
        double sum = 0.0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x)
                for (int k = 0; k < 3; ++k)
                    sum += std::abs(rest.at(x, y)[k] - moving.at(x, y)[k]);
        const double mean = sum / (3.0 * kWidth * kHeight);
        qInfo("mask texels %lld at rest, %lld navigating (%.3f); of %d pixels %d 8/255 apart, %d "
              "32/255; mean difference %.5f",
              atRest.shadowMaskTexels, navigating.shadowMaskTexels, texels, kWidth * kHeight,
              differ, far, mean);
        QVERIFY2(texels > 0.15 && texels < 0.35, qPrintable(QString::number(texels)));
        QVERIFY(differ > 0); // the passes did change: coarser edges
        // Measured at 384 x 256: 3.2 % of the pixels 8/255 apart, 0.5 % 32/255 (the thin shadows
        // in the rings' gaps, a texel or two high at a quarter), a mean of 0.0045.
        QVERIFY2(differ * 20 < kWidth * kHeight, qPrintable(QString::number(differ)));
        QVERIFY2(far * 100 < kWidth * kHeight, qPrintable(QString::number(far)));
        QVERIFY2(mean < 0.01, qPrintable(QString::number(mean)));
    }

    // An orbit's frames, then the view at rest: the masks and the occlusion drawn again at half,
    // and the picture the still frame at that view gives, to the bit.
    void theViewAtRestAfterAnOrbitIsTheStillFrame() {
        Camera camera = shadowedStage().camera;
        for (int i = 0; i < 3; ++i) {
            camera.yawDeg += 4.0f;
            m_fs.camera = camera;
            draw(true);
        }
        const Image settled = draw(false);
        QVERIFY(!timings().shadowMaskKept && !timings().occlusionKept);
        m_rig->renderer->update(shadowedStage(), ScenePart::Mesh); // nothing kept
        const Image still = draw(false);
        QVERIFY(test::samePixels(settled, still));
    }

    // The same view navigating after at rest (and back) draws the masks and the occlusion again
    // at the other size; two navigating frames of one view keep them.
    void neitherKeepsTheOthersPasses() {
        draw(false);
        draw(true);
        QVERIFY(!timings().shadowMaskKept && !timings().occlusionKept);
        draw(true);
        QVERIFY(timings().shadowMaskKept && timings().occlusionKept);
        draw(false);
        QVERIFY(!timings().shadowMaskKept && !timings().occlusionKept);
    }
};

QTEST_GUILESS_MAIN(TestRenderStageNavigating)
#include "test_render_stage_navigating.moc"
