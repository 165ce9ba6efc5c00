// The G-buffer kept after a value edit (Renderer::Impl::keepsGBuffer, render/material_table.h's
// kRecordValuesPerMaterial): a material whose base colour, metallic and roughness are the same at
// every pixel is lit from the table's values, quantised as the G-buffer holds them, so a slider's
// frame draws no geometry pass. The kept frame is the frame drawn with the G-buffer drawn again,
// to the bit, and the edit shows; a textured or graph-driven material, a mesh whose specular
// occlusion reads the roughness, a ground, a split or a moved camera draw the G-buffer again.
#include "core/document_io.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QtTest>

using namespace velvet;

namespace {

constexpr int kSize = 96;

} // namespace

class TestRenderGBufferReuse : public QObject {
    Q_OBJECT
    test::OffscreenRenderer* m_rig = nullptr;
    render::FrameSettings m_fs;

    /// Draws the next frame of the renderer's scene; whether it kept the G-buffer.
    bool draw(Image* image = nullptr) {
        std::string error;
        if (!m_rig->renderer->render(m_fs, m_rig->target->framebuffer(), &error))
            qFatal("render failed: %s", error.c_str());
        if (image)
            *image = m_rig->renderer->readLinear();
        return m_rig->renderer->lastFramePasses().gbufferKept;
    }
    /// Two frames of @p scene as set, then after a roughness edit: whether that frame kept it.
    bool keptAfterAnEdit(Scene scene) {
        m_rig->renderer->setScene(scene);
        m_rig->renderer->finishEnvironment();
        m_rig->renderer->finishGraph();
        m_rig->renderer->finishTextures();
        draw();
        draw();
        scene.material.setScalar(ParamId::Roughness, 0.35f);
        m_rig->renderer->update(scene, ScenePart::MaterialValues);
        return draw();
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
        m_fs = render::FrameSettings{};
        m_fs.width = m_fs.height = kSize;
    }

    // The default velvet on the sphere: a roughness and a base colour edit keep the G-buffer,
    // change the picture, and give the picture a frame that draws it again gives, to the bit.
    void keptAcrossValueEditsAndTheSameImage() {
        Scene scene = defaultScene();
        QVERIFY(keptAfterAnEdit(scene)); // a roughness edit
        Image before, kept, drawn;
        draw(&before);
        scene.material.setScalar(ParamId::Roughness, 0.3f);
        scene.material.setColor(ParamId::BaseColor, glm::vec3(0.1f, 0.3f, 0.6f));
        scene.material.setScalar(ParamId::Metallic, 0.4f);
        m_rig->renderer->update(scene, ScenePart::MaterialValues);
        QVERIFY(draw(&kept));
        QVERIFY(draw());                                 // nothing changed
        m_rig->renderer->update(scene, ScenePart::Mesh); // nothing kept
        QVERIFY(!draw(&drawn));
        QVERIFY(test::samePixels(kept, drawn));
        const int changed = test::differingPixels(before, kept, 8);
        qInfo("%d pixels changed by the edit", changed);
        QVERIFY2(changed > 500, "the edit did not show");
    }

    // What the geometry pass writes would change, or something else draws into the G-buffer.
    void drawnAgainWhereItsContentDependsOnTheEdit() {
        const Scene plain = defaultScene();
        QVERIFY(keptAfterAnEdit(plain));

        Scene ball = plain; // its specular occlusion reads the roughness (mesh visibility)
        ball.mesh.kind = PreviewMeshKind::ShaderBall;
        QVERIFY(!keptAfterAnEdit(ball));

        Scene grounded = plain;
        grounded.environment.ground = GroundMode::Plain;
        QVERIFY(!keptAfterAnEdit(grounded));

        const std::optional<Material> denim = test::libraryPreset("denim"); // a weave graph
        QVERIFY(denim);
        Scene woven = plain;
        woven.material = *denim;
        QVERIFY(!keptAfterAnEdit(woven));

        m_fs.splitMaterial = plain.material;
        QVERIFY(!keptAfterAnEdit(plain));
        m_fs.splitMaterial.reset();

        QVERIFY(keptAfterAnEdit(plain));
        Camera turned = plain.camera;
        turned.yawDeg += 5.0f;
        m_fs.camera = turned;
        QVERIFY(!draw());
        QVERIFY(draw()); // still again
    }
};

QTEST_GUILESS_MAIN(TestRenderGBufferReuse)
#include "test_render_gbuffer_reuse.moc"
