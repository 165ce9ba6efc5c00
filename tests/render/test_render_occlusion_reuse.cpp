// The screen-space occlusion and shadow mask kept across frames (render/ao_pass.h,
// render/stage.h): a frame whose camera, depth and normals are the last frame's keeps the last
// occlusion instead of drawing it again, and its image is the one a frame drawing the occlusion
// gives, to the bit; a moved camera, another mesh, or a value edit of a material that bends its
// normals (a fabric's weave) draws it again. The shadow mask likewise, and a moved or resized
// light draws it again too.
#include "core/document_io.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QtTest>

using namespace velvet;

namespace {

constexpr int kSize = 96;

/// The shader ball on a plain ground with occlusion, no lights but the studio environment.
Scene stage() {
    Scene scene;
    scene.mesh.kind = PreviewMeshKind::ShaderBall;
    scene.environment.ground = GroundMode::Plain;
    scene.environment.ambientOcclusion = true;
    scene.lights.clear();
    return scene;
}

} // namespace

class TestRenderOcclusionReuse : public QObject {
    Q_OBJECT
    test::OffscreenRenderer* m_rig = nullptr;
    render::FrameSettings m_fs;

    /// Draws the next frame of the renderer's scene; whether it kept the occlusion.
    bool draw(Image* image = nullptr, render::DebugView view = render::DebugView::Final) {
        std::string error;
        m_fs.view = view;
        if (!m_rig->renderer->render(m_fs, m_rig->target->framebuffer(), &error))
            qFatal("render failed: %s", error.c_str());
        if (image)
            *image = m_rig->renderer->readLinear();
        return m_rig->renderer->lastTimings().occlusionKept;
    }

private slots:
    void initTestCase() {
        std::string error;
        m_rig = test::startProcessRenderer(kSize, kSize, &error);
        QVERIFY2(m_rig, error.c_str());
        m_fs.width = m_fs.height = kSize;
    }

    void cleanupTestCase() {
        test::stopProcessRenderer(); // while the context is current
    }

    void init() {
        m_fs.camera.reset();
        m_rig->renderer->setScene(stage());
        m_rig->renderer->finishEnvironment();
    }

    // A colour edit leaves the depth and the normals: the occlusion is kept, and the frame is
    // the one drawn with the occlusion drawn again (the mesh re-selected invalidates it).
    void keptAcrossAColourEditAndTheSameImage() {
        QVERIFY(!draw());
        Scene edited = stage();
        edited.material.setColor(ParamId::BaseColor, glm::vec3(0.7f, 0.2f, 0.1f));
        m_rig->renderer->update(edited, ScenePart::MaterialValues);
        Image kept, keptOcclusion, drawn, drawnOcclusion;
        QVERIFY(draw(&kept));
        QVERIFY(draw(&keptOcclusion, render::DebugView::Occlusion));
        m_rig->renderer->update(edited, ScenePart::Mesh);
        QVERIFY(!draw(&drawn));
        m_rig->renderer->update(edited, ScenePart::Mesh);
        QVERIFY(!draw(&drawnOcclusion, render::DebugView::Occlusion));
        QVERIFY(test::samePixels(kept, drawn));
        QVERIFY(test::samePixels(keptOcclusion, drawnOcclusion));
        // The occlusion is there at all: some pixel of the ball's crevices is below 0.9.
        float least = 1.0f;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                least = std::min(least, keptOcclusion.rgba(x, y).r);
        QVERIFY2(least < 0.9f, qPrintable(QString::number(least)));
    }

    // A light or the environment's intensity leaves them too; the camera does not.
    void drawnAgainWhenTheCameraMoves() {
        QVERIFY(!draw());
        Scene lit = stage();
        lit.environment.intensity = 0.5f;
        m_rig->renderer->update(lit, ScenePart::Environment);
        QVERIFY(draw());
        Camera turned = lit.camera;
        turned.yawDeg += 10.0f;
        m_fs.camera = turned;
        QVERIFY(!draw());
        QVERIFY(draw()); // still again
        m_rig->renderer->update(lit, ScenePart::Mesh);
        QVERIFY(!draw());
    }

    // A shadowed key light over the ball on a catcher: a colour edit keeps the masks and the
    // frame is the one drawn with them drawn again; a light moved or made larger (a softer
    // penumbra), a camera moved, draw them again.
    void shadowMaskKeptAcrossAColourEdit() {
        Scene shadowed = stage();
        shadowed.environment.ground = GroundMode::ShadowCatcher;
        shadowed.environment.ambientOcclusion = false;
        Light key = test::analyticKeyLight();
        key.castShadows = true;
        shadowed.lights = {key};
        m_rig->renderer->setScene(shadowed);
        const auto maskKept = [&](Image* image = nullptr) {
            draw(image);
            const render::FrameTimings t = m_rig->renderer->lastTimings();
            if (t.shadowMaskPasses < 1)
                qFatal("the key light cast no shadow");
            return t.shadowMaskKept;
        };
        QVERIFY(!maskKept());
        QVERIFY(maskKept()); // nothing changed
        Scene edited = shadowed;
        edited.material.setColor(ParamId::BaseColor, glm::vec3(0.7f, 0.2f, 0.1f));
        m_rig->renderer->update(edited, ScenePart::MaterialValues);
        Image kept, drawn;
        QVERIFY(maskKept(&kept));
        QCOMPARE(m_rig->renderer->lastTimings().shadowMaskMs, 0.0);
        m_rig->renderer->update(edited, ScenePart::Mesh);
        QVERIFY(!maskKept(&drawn));
        QVERIFY(test::samePixels(kept, drawn));
        Scene moved = edited;
        moved.lights[0].direction = glm::vec3(0.6f, -0.5f, 0.2f);
        m_rig->renderer->update(moved, ScenePart::Lights);
        QVERIFY(!maskKept());
        QVERIFY(maskKept());
        Scene softer = moved;
        softer.lights[0].sourceAngleDeg *= 4.0f;
        m_rig->renderer->update(softer, ScenePart::Lights);
        QVERIFY(!maskKept());
        Camera turned = softer.camera;
        turned.yawDeg += 10.0f;
        m_fs.camera = turned;
        QVERIFY(!maskKept());
        QVERIFY(maskKept());
    }

    // A fabric bends its normals by its weave, which its values (the weave's scale among them)
    // drive: a value edit draws the occlusion again.
    void drawnAgainAfterAValueEditOfABentNormal() {
        const std::optional<Material> denim = test::libraryPreset("denim");
        QVERIFY(denim);
        Scene fabric = stage();
        fabric.material = *denim;
        m_rig->renderer->update(fabric, ScenePart::Material);
        m_rig->renderer->finishGraph();
        QVERIFY(!draw());
        QVERIFY(draw()); // nothing changed
        fabric.material.setScalar(ParamId::Roughness, 0.3f);
        m_rig->renderer->update(fabric, ScenePart::MaterialValues);
        QVERIFY(!draw());
    }

    // The A/B split draws B's G-buffer into the right of the frame (here a fabric's bent
    // normals): neither the split frame nor the first frame after it keeps the occlusion, and
    // that frame is the one before the split, to the bit.
    void splitFramesDrawItAgain() {
        const std::optional<Material> denim = test::libraryPreset("denim");
        QVERIFY(denim);
        Image before, after;
        QVERIFY(!draw());
        QVERIFY(draw(&before));
        m_fs.splitMaterial = *denim;
        QVERIFY(!draw());
        QVERIFY(!draw()); // still split
        m_fs.splitMaterial.reset();
        QVERIFY(!draw(&after));
        QVERIFY(test::samePixels(before, after));
        QVERIFY(draw());
    }
};

QTEST_GUILESS_MAIN(TestRenderOcclusionReuse)
#include "test_render_occlusion_reuse.moc"
