// Shadowed look-dev scenes against reference images (docs/shadows.md): the shader ball on a shadow
// catcher under the key light, the cloth drape on a plain ground under the three-point rig, a spot
// light's shadow through each local-light path, and more shadow-casting lights than the cap. The
// references show the half-resolution shadow mask (2026-12-03). They were re-recorded from the
// full-resolution mask's on purpose: at this test's 128 pixels the half-resolution mask moves
// 1.1-1.7 % of the pixels by more than 5/255 (hard shadow edges land on 2-pixel steps), while
// at 1280x720 the shader ball on its catcher moves 0.08 % (within this rule), reviewed by eye
// (BENCHMARKS.md, "The shadow mask at half resolution"). The drape's was re-recorded on
// 2026-12-06 when the three-point rig's fill and rim began to cast shadows (the rim's shadow now
// falls on the ground in front of the drape; BENCHMARKS.md, "Every light of the three-point rig
// casts its shadow").
//
// Regenerating them (only after a deliberate change to the shadows, reviewed by eye):
//   VELVET_UPDATE_GOLDENS=1 ctest --test-dir build -R test_render_shadow_golden
// rewrites tests/render/golden/shadow_*.png and passes; commit the new PNGs.
#include "core/image.h"
#include "core/light_rigs.h"
#include "render/stage_interface.h"
#include "render_test_util.h"

#include <QtTest>
#include <cstdlib>
#include <memory>

using namespace velvet;

namespace {

constexpr int kSize = 128;

std::unique_ptr<test::OffscreenRenderer> fx;
test::OffscreenRenderer* rig() {
    if (!fx) {
        fx = std::make_unique<test::OffscreenRenderer>();
        const std::string error = fx->start(kSize);
        if (!error.empty())
            qFatal("renderer: %s", error.c_str());
    }
    return fx.get();
}

/// @p scene's display image through light path @p path.
Image drawDisplay(const Scene& scene, render::LightPath path = render::LightPath::Auto) {
    test::OffscreenRenderer* r = rig();
    Problems problems;
    r->renderer->setScene(scene, &problems);
    // The finished bake, whether or not the environment and the DFG LUT came from the disk
    // cache: a frame drawn while they bake shows the approximate path (render/ibl_bake.h), so
    // without this the images depended on what the cache held (a warm one moved 2-14 % of the
    // pixels against references drawn cold).
    r->renderer->finishEnvironment();
    render::FrameSettings fs;
    fs.width = fs.height = kSize;
    fs.lightPath = path;
    std::string error;
    if (!r->renderer->render(fs, r->target->framebuffer(), &error))
        qFatal("render failed: %s", error.c_str());
    return r->renderer->readDisplay();
}

/// DESIGN.md's golden rule: a pixel differs when a channel differs by more than 5/255, the test
/// fails when more than 0.1 % differ.
void compareWithReference(const Image& display, const std::string& name) {
    const std::string file = VELVET_SOURCE_DIR "/tests/render/golden/shadow_" + name + ".png";
    std::string error;
    if (test::updateGoldens()) {
        QVERIFY2(writeImage(file, display, PixelFormat::UInt8, &error), error.c_str());
        qWarning("VELVET_UPDATE_GOLDENS=1: rewrote %s", file.c_str());
        return;
    }
    Image golden;
    QVERIFY2(readImage(file, golden, &error), error.c_str());
    QCOMPARE(golden.width, display.width);
    QCOMPARE(golden.height, display.height);
    int differing = 0;
    float worst = 0.0f;
    for (int y = 0; y < golden.height; ++y)
        for (int x = 0; x < golden.width; ++x) {
            const glm::vec4 a = golden.rgba(x, y), b = display.rgba(x, y);
            float d = 0.0f;
            for (int k = 0; k < 3; ++k)
                d = std::max(d, std::abs(std::round(a[k] * 255.0f) - std::round(b[k] * 255.0f)));
            worst = std::max(worst, d);
            differing += d > 5.0f;
        }
    const double fraction = double(differing) / (golden.width * golden.height);
    qInfo("%s: %d pixels differ (%.3f %%), worst channel difference %.0f/255", name.c_str(),
          differing, 100.0 * fraction, worst);
    if (fraction > 0.001) {
        const std::string actual =
            QDir::tempPath().toStdString() + "/shadow_" + name + "_actual.png";
        writeImage(actual, display, PixelFormat::UInt8, nullptr);
        QFAIL(qPrintable(QString("%1 % of pixels differ from the reference; this run's image is %2")
                             .arg(100.0 * fraction)
                             .arg(QString::fromStdString(actual))));
    }
}

/// The shipped default scene (its HDRI and background) with @p mesh on @p ground under @p rigId.
Scene stage(PreviewMeshKind mesh, GroundMode ground, const char* rigId) {
    Scene scene = test::shippedDefaultScene();
    scene.mesh.kind = mesh;
    scene.environment.ground = ground;
    scene.lights = *lightRigLights(rigId);
    return scene;
}

/// The unit sphere on a plain grey ground, a black environment, seen from above at a slant.
Scene sphereOnGround() {
    Scene scene = test::blackOrthographicScene();
    scene.mesh.kind = PreviewMeshKind::Sphere;
    scene.camera.pitchDeg = 55.0f;
    scene.camera.yawDeg = 20.0f;
    scene.camera.orthoHeight = 6.0f;
    scene.camera.target = {0.0f, -1.0f, 0.0f};
    scene.environment.ground = GroundMode::Plain;
    scene.environment.groundColor = glm::vec3(0.5f);
    scene.environment.groundRoughness = 1.0f;
    return scene;
}

/// kMaxShadowLights + 1 shadow-casting directional lights around the sphere, the first the
/// weakest (the one the cap leaves out).
Scene overTheCap() {
    Scene scene = sphereOnGround();
    for (int i = 0; i < render::kMaxShadowLights + 1; ++i) {
        Light l = test::analyticKeyLight();
        const float a = 6.2831853f * float(i) / float(render::kMaxShadowLights + 1);
        l.direction = {std::cos(a), -1.6f, std::sin(a)};
        l.intensity = 0.4f + 0.1f * float(i);
        l.castShadows = true;
        l.sourceAngleDeg = 1.0f;
        scene.lights.push_back(l);
    }
    return scene;
}

} // namespace

class TestRenderShadowGolden : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
    }
    void cleanupTestCase() {
        if (fx)
            fx->stop();
    }

    void shaderBallOnCatcherUnderKeyLight() {
        const Image image =
            drawDisplay(stage(PreviewMeshKind::ShaderBall, GroundMode::ShadowCatcher, "key"));
        QCOMPARE(rig()->renderer->lastTimings().shadowMaskPasses, 1); // the key light's
        compareWithReference(image, "ball_catcher_key");
    }

    void drapeOnPlainGroundUnderThreePoint() {
        compareWithReference(
            drawDisplay(stage(PreviewMeshKind::ClothDrape, GroundMode::Plain, "three-point")),
            "drape_plain_three_point");
    }

    // A spot light's perspective map through the three local-light paths.
    void spotShadowThroughEachPath_data() {
        QTest::addColumn<int>("path");
        QTest::addColumn<QString>("name");
        QTest::newRow("brute") << int(render::LightPath::Brute) << "spot_brute";
        QTest::newRow("tiled") << int(render::LightPath::Tiled) << "spot_tiled";
        QTest::newRow("volumes") << int(render::LightPath::Volumes) << "spot_volumes";
    }
    void spotShadowThroughEachPath() {
        QFETCH(int, path);
        QFETCH(QString, name);
        Scene scene = sphereOnGround();
        Light spot;
        spot.type = LightType::Spot;
        spot.position = {1.2f, 3.5f, 0.8f};
        spot.direction = -spot.position;
        spot.intensity = 40.0f;
        spot.range = 20.0f;
        spot.innerConeDeg = 40.0f;
        spot.outerConeDeg = 50.0f;
        spot.sourceRadius = 0.05f;
        spot.castShadows = true;
        scene.lights = {spot};
        compareWithReference(drawDisplay(scene, render::LightPath(path)), name.toStdString());
    }

    // More shadow-casting lights than the cap: the frame draws one shadow-mask pass per kept
    // light (render/shadow_mask.h), the image is the reference's, and the weakest light, left
    // out by the cap, casts no shadow (the frame equals one where it asks for none).
    void shadowCapHolds() {
        const Scene scene = overTheCap();
        const Image capped = drawDisplay(scene);
        QCOMPARE(rig()->renderer->lastTimings().shadowMaskPasses, render::kMaxShadowLights);
        compareWithReference(capped, "over_the_cap");
        Scene weakestOff = scene;
        weakestOff.lights[0].castShadows = false;
        const Image without = drawDisplay(weakestOff);
        QCOMPARE(rig()->renderer->lastTimings().shadowMaskPasses, render::kMaxShadowLights);
        float worst = 0.0f;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                worst = std::max(worst, glm::length(capped.rgba(x, y) - without.rgba(x, y)));
        QVERIFY2(worst < 1e-6f,
                 qPrintable(QString("the weakest light still casts a shadow: %1").arg(worst)));
        // ... while each kept light does.
        for (int i = 1; i <= render::kMaxShadowLights; ++i) {
            Scene keptOff = scene;
            keptOff.lights[size_t(i)].castShadows = false;
            const Image image = drawDisplay(keptOff);
            float d = 0.0f;
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x)
                    d = std::max(d, glm::length(capped.rgba(x, y) - image.rgba(x, y)));
            QVERIFY2(d > 0.05f, qPrintable(QString("light %1's shadow is missing").arg(i)));
        }
    }
};

QTEST_GUILESS_MAIN(TestRenderShadowGolden)
#include "test_render_shadow_golden.moc"
