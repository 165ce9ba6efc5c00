// Renderer::update takes a ScenePart mask and re-uploads only those parts (DESIGN.md, "Changes";
// render/renderer.h, "Scene updates"). Each case counts the uploads an edit causes with
// Renderer::uploadStats() and checks that the picture still follows the edit. One renderer for
// the whole file, 64x64 frames of the shipped default scene.
#include "core/image.h"
#include "core/scene_parts.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QtTest>
#include <memory>

using namespace velvet;
using render::UploadStats;

namespace {

constexpr int kSize = 64;

/// The uploads between two counts, field by field.
UploadStats delta(const UploadStats& after, const UploadStats& before) {
    UploadStats d;
    d.meshSelections = after.meshSelections - before.meshSelections;
    d.textureSlotRefreshes = after.textureSlotRefreshes - before.textureSlotRefreshes;
    d.materialUploads = after.materialUploads - before.materialUploads;
    d.graphCompiles = after.graphCompiles - before.graphCompiles;
    d.graphValueUploads = after.graphValueUploads - before.graphValueUploads;
    d.lightUploads = after.lightUploads - before.lightUploads;
    d.environmentRequests = after.environmentRequests - before.environmentRequests;
    return d;
}

QString describe(const UploadStats& s) {
    return QString("mesh %1, texture slots %2, material %3, graph compiles %4, graph values %5, "
                   "lights %6, environment %7")
        .arg(s.meshSelections)
        .arg(s.textureSlotRefreshes)
        .arg(s.materialUploads)
        .arg(s.graphCompiles)
        .arg(s.graphValueUploads)
        .arg(s.lightUploads)
        .arg(s.environmentRequests);
}

int total(const UploadStats& s) {
    return s.meshSelections + s.textureSlotRefreshes + s.materialUploads + s.graphCompiles +
           s.graphValueUploads + s.lightUploads + s.environmentRequests;
}

/// The default camera orbited by 30 degrees and raised, as the editor's orbit does.
Camera orbited(const Camera& c) {
    Camera o = c;
    o.yawDeg += 30.0f;
    o.pitchDeg += 15.0f;
    return o;
}

} // namespace

class TestRenderSceneUpdates : public QObject {
    Q_OBJECT
    std::unique_ptr<render::Renderer> m_renderer;
    std::unique_ptr<render::OffscreenTarget> m_target;
    Scene m_scene;

    Image frame(const std::optional<Camera>& camera = std::nullopt) {
        render::FrameSettings fs;
        fs.width = fs.height = kSize;
        fs.camera = camera;
        std::string error;
        if (!m_renderer->render(fs, m_target->framebuffer(), &error))
            qFatal("render failed: %s", error.c_str());
        return m_renderer->readLinear();
    }

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        m_renderer = std::make_unique<render::Renderer>();
        QVERIFY2(m_renderer->initialize(&error), error.c_str());
        m_target = std::make_unique<render::OffscreenTarget>();
        QVERIFY2(m_target->resize(kSize, kSize, &error), error.c_str());
        m_scene = test::shippedDefaultScene();
        m_scene.lights = {Light{}}; // one directional light, so a light edit shows
        m_renderer->setScene(m_scene);
        m_renderer->finishEnvironment();
        m_renderer->finishGraph();
        frame();
    }
    void cleanupTestCase() {
        m_target.reset();
        m_renderer.reset();
    }

    // setScene is update(All): it uploads every part once (the baseline the other cases cut).
    void setSceneUploadsEveryPart() {
        const UploadStats before = m_renderer->uploadStats();
        m_renderer->setScene(m_scene);
        const UploadStats d = delta(m_renderer->uploadStats(), before);
        qInfo("setScene: %s", qPrintable(describe(d)));
        QCOMPARE(d.meshSelections, 1);
        QCOMPARE(d.textureSlotRefreshes, 1);
        QCOMPARE(d.materialUploads, 1);
        QCOMPARE(d.graphCompiles, 1);
        QCOMPARE(d.lightUploads, 1);
        QCOMPARE(d.environmentRequests, 1);
    }

    // An orbit is a per-frame camera: frames drawn from other cameras, and an update that names
    // only the camera, upload nothing — while the picture does move.
    void orbitUploadsNothing() {
        const Image still = frame();
        const UploadStats before = m_renderer->uploadStats();
        Camera c = m_scene.camera;
        Image moved;
        for (int i = 0; i < 5; ++i) {
            c = orbited(c);
            moved = frame(c);
        }
        Scene withCamera = m_scene;
        withCamera.camera = c;
        m_renderer->update(withCamera, ScenePart::Camera);
        frame();
        const UploadStats d = delta(m_renderer->uploadStats(), before);
        qInfo("five orbit frames + a camera update: %s", qPrintable(describe(d)));
        QCOMPARE(total(d), 0);
        QVERIFY(!test::samePixels(moved, still));
        m_renderer->update(m_scene, ScenePart::Camera); // back to the saved view
    }

    // A frame drawn with FrameSettings::camera is the frame of a scene whose camera is that
    // camera, pixel for pixel.
    void frameCameraEqualsSceneCamera() {
        const Camera c = orbited(orbited(m_scene.camera));
        const Image fromSettings = frame(c);
        Scene moved = m_scene;
        moved.camera = c;
        m_renderer->update(moved, ScenePart::Camera);
        const Image fromScene = frame();
        m_renderer->update(m_scene, ScenePart::Camera);
        const Image original = frame();
        QVERIFY(test::samePixels(fromSettings, fromScene));
        QVERIFY(!test::samePixels(fromScene, original));
    }

    // A roughness edit is a value edit: one material record, no texture, mesh, light, graph or
    // environment upload, and the pixels change.
    void roughnessEditUploadsOneMaterialRecord() {
        const Image before = frame();
        const UploadStats counts = m_renderer->uploadStats();
        Scene edited = m_scene;
        edited.material.setScalar(ParamId::Roughness,
                                  m_scene.material.scalar(ParamId::Roughness) < 0.5f ? 0.8f : 0.2f);
        m_renderer->update(edited, ScenePart::MaterialValues);
        const Image after = frame();
        const UploadStats d = delta(m_renderer->uploadStats(), counts);
        qInfo("roughness edit: %s", qPrintable(describe(d)));
        QCOMPARE(d.materialUploads, 1);
        QCOMPARE(total(d), 1);
        QVERIFY(!test::samePixels(after, before));
        m_renderer->update(m_scene, ScenePart::MaterialValues);
    }

    // A light edit uploads the lights and nothing else, and the pixels change.
    void lightEditUploadsLightsOnly() {
        const Image before = frame();
        const UploadStats counts = m_renderer->uploadStats();
        Scene edited = m_scene;
        edited.lights[0].intensity *= 3.0f;
        m_renderer->update(edited, ScenePart::Lights);
        const Image after = frame();
        const UploadStats d = delta(m_renderer->uploadStats(), counts);
        qInfo("light edit: %s", qPrintable(describe(d)));
        QCOMPARE(d.lightUploads, 1);
        QCOMPARE(total(d), 1);
        QVERIFY(!test::samePixels(after, before));
        m_renderer->update(m_scene, ScenePart::Lights);
    }

    // A part the mask does not name is not taken: the stored scene keeps its own.
    void unnamedPartsAreNotTaken() {
        const Image before = frame();
        Scene edited = m_scene;
        edited.lights[0].intensity *= 3.0f;
        edited.camera = orbited(m_scene.camera);
        m_renderer->update(edited, ScenePart::MaterialValues);
        QVERIFY(test::samePixels(frame(), before));
    }
};

QTEST_GUILESS_MAIN(TestRenderSceneUpdates)
#include "test_render_scene_updates.moc"
