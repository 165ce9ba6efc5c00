// The look-dev stage's known answers (docs/shadows.md): shadow maps against shadows computed on
// the CPU (a ray from each ground point to the light, against the sphere), no self-shadowing of
// a flat plane, and the screen-space occlusion term: 1 on an open plane, below 1 in a crease.
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render/stage_interface.h"
#include "render_test_util.h"

#include <QtTest>
#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <memory>

using namespace velvet;

namespace {

struct Rig {
    render::Renderer renderer;
    render::OffscreenTarget target;
};
Rig* rig() {
    static std::unique_ptr<Rig> r;
    if (!r) {
        r = std::make_unique<Rig>();
        std::string error;
        if (!r->renderer.initialize(&error))
            qFatal("renderer: %s", error.c_str());
    }
    return r.get();
}

Image renderLinear(const Scene& scene, int size, render::DebugView view = render::DebugView::Final,
                   render::LightPath path = render::LightPath::Auto) {
    Rig* r = rig();
    std::string error;
    if (!r->target.resize(size, size, &error))
        qFatal("target: %s", error.c_str());
    render::FrameSettings fs;
    fs.width = fs.height = size;
    fs.view = view;
    fs.lightPath = path;
    Problems problems;
    r->renderer.setScene(scene, &problems);
    for (const Problem& p : problems.items)
        qWarning("%s", p.toString().c_str());
    if (!r->renderer.render(fs, r->target.framebuffer(), &error))
        qFatal("render failed: %s", error.c_str());
    return r->renderer.readLinear();
}

/// A black environment, an orthographic camera looking down on the origin at 55°.
Scene stageScene(PreviewMeshKind mesh) {
    Scene scene = test::blackOrthographicScene();
    scene.mesh.kind = mesh;
    scene.camera.pitchDeg = 55.0f;
    scene.camera.yawDeg = 20.0f;
    scene.camera.orthoHeight = 6.0f;
    scene.camera.target = {0.0f, -1.0f, 0.0f};
    scene.environment.groundColor = glm::vec3(0.5f);
    scene.environment.groundRoughness = 1.0f;
    return scene;
}

float luminance(glm::vec4 c) {
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

/// Distance from the unit sphere's centre to the segment from @p p towards the light (direction
/// @p toLight, length @p length; infinite for a directional light); infinity when the closest
/// point is behind @p p.
float rayMissDistance(glm::vec3 p, glm::vec3 toLight, float length) {
    const float t = -glm::dot(p, toLight);
    if (t <= 0.0f || t >= length)
        return 1e9f;
    return glm::length(p + t * toLight);
}

/// Ground pixels of @p withShadows / @p without, classified by the CPU: in the umbra (the ray to
/// the light passes the sphere's centre closer than 0.9) the ratio must be below 0.05, clearly
/// outside (farther than 1.1) above 0.98.
void checkGroundShadow(const Scene& lit, const std::function<float(glm::vec3)>& missDistance,
                       render::LightPath path = render::LightPath::Auto) {
    const int size = 128;
    Scene unshadowed = lit;
    for (Light& l : unshadowed.lights)
        l.castShadows = false;
    const Image pos = renderLinear(lit, size, render::DebugView::Position);
    const Image with = renderLinear(lit, size, render::DebugView::Final, path);
    const Image without = renderLinear(unshadowed, size, render::DebugView::Final, path);
    int umbra = 0, open = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const glm::vec3 p = glm::vec3(pos.rgba(x, y));
            if (p.y > -1.0f || p.y < -1.01f) // the ground lies just under the sphere, y = -1
                continue;
            const float full = luminance(without.rgba(x, y));
            if (full < 1e-3f)
                continue; // outside the spot's cone
            const float ratio = luminance(with.rgba(x, y)) / full;
            const float miss = missDistance(p);
            if (miss < 0.9f) {
                ++umbra;
                if (ratio > 0.05f)
                    QFAIL(qPrintable(QString("ground (%1, %2, %3) should be in the umbra: %4 of "
                                             "the unshadowed light")
                                         .arg(p.x)
                                         .arg(p.y)
                                         .arg(p.z)
                                         .arg(ratio)));
            } else if (miss > 1.1f) {
                ++open;
                if (ratio < 0.98f)
                    QFAIL(qPrintable(QString("ground (%1, %2, %3) should be lit: %4 of the "
                                             "unshadowed light")
                                         .arg(p.x)
                                         .arg(p.y)
                                         .arg(p.z)
                                         .arg(ratio)));
            }
        }
    qInfo("%d umbra and %d lit ground pixels checked", umbra, open);
    QVERIFY(umbra >= 40);
    QVERIFY(open >= 200);
}

} // namespace

class TestRenderShadows : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
    }

    void directionalShadowOfSphereOnGround() {
        Scene scene = stageScene(PreviewMeshKind::Sphere);
        scene.environment.ground = GroundMode::Plain;
        Light sun = test::analyticKeyLight();
        sun.direction = {0.45f, -1.0f, 0.3f};
        sun.castShadows = true;
        sun.sourceAngleDeg = 1.0f;
        scene.lights = {sun};
        const glm::vec3 toLight = -glm::normalize(sun.direction);
        checkGroundShadow(scene,
                          [toLight](glm::vec3 p) { return rayMissDistance(p, toLight, 1e9f); });
    }

    // A spot light's perspective map, through the point-lights paths (brute force and tiled).
    void spotShadowOfSphereOnGround_data() {
        QTest::addColumn<int>("path");
        QTest::newRow("brute") << int(render::LightPath::Brute);
        QTest::newRow("tiled") << int(render::LightPath::Tiled);
        QTest::newRow("volumes") << int(render::LightPath::Volumes);
    }
    void spotShadowOfSphereOnGround() {
        QFETCH(int, path);
        Scene scene = stageScene(PreviewMeshKind::Sphere);
        scene.environment.ground = GroundMode::Plain;
        Light spot;
        spot.type = LightType::Spot;
        spot.position = {1.2f, 3.5f, 0.8f};
        spot.direction = -spot.position;
        spot.intensity = 40.0f;
        spot.range = 20.0f;
        spot.innerConeDeg = 40.0f;
        spot.outerConeDeg = 50.0f;
        spot.sourceRadius = 0.02f;
        spot.castShadows = true;
        scene.lights = {spot};
        checkGroundShadow(
            scene,
            [spot](glm::vec3 p) {
                const glm::vec3 d = spot.position - p;
                return rayMissDistance(p, glm::normalize(d), glm::length(d));
            },
            render::LightPath(path));
    }

    // A flat plane lit at a slant, shadows on and off: the same image (no acne).
    void flatPlaneHasNoSelfShadowing_data() {
        QTest::addColumn<float>("elevationDeg");
        QTest::newRow("45 degrees") << 45.0f;
        QTest::newRow("15 degrees") << 15.0f;
    }
    void flatPlaneHasNoSelfShadowing() {
        QFETCH(float, elevationDeg);
        Scene scene = stageScene(PreviewMeshKind::Plane);
        scene.camera.target = {0.0f, 0.0f, 0.0f};
        scene.camera.orthoHeight = 2.5f;
        Light sun = test::analyticKeyLight();
        const float e = elevationDeg * 3.14159265f / 180.0f;
        sun.direction = {-std::cos(e) * 0.8f, -std::sin(e), -std::cos(e) * 0.6f};
        sun.castShadows = true;
        scene.lights = {sun};
        Scene unshadowed = scene;
        unshadowed.lights[0].castShadows = false;
        const int size = 96;
        const Image with = renderLinear(scene, size);
        const Image without = renderLinear(unshadowed, size);
        int checked = 0;
        float worst = 1.0f;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const float full = luminance(without.rgba(x, y));
                if (full < 1e-4f)
                    continue;
                ++checked;
                worst = std::min(worst, luminance(with.rgba(x, y)) / full);
            }
        qInfo("%d plane pixels, least shadowed / unshadowed %.4f", checked, double(worst));
        QVERIFY(checked > 1000);
        QVERIFY2(worst > 0.995f, qPrintable(QString("self-shadowing: %1").arg(worst)));
    }

    // More shadow-casting lights than the cap: a warning names each one left out.
    void shadowCapWarnsAboutTheWeakest() {
        Scene scene = stageScene(PreviewMeshKind::Sphere);
        for (int i = 0; i < render::kMaxShadowLights + 1; ++i) {
            Light l = test::analyticKeyLight();
            l.intensity = 1.0f + float(i); // the first is the weakest
            l.castShadows = true;
            scene.lights.push_back(l);
        }
        Rig* r = rig();
        Problems problems;
        r->renderer.setScene(scene, &problems);
        QCOMPARE(problems.items.size(), size_t(1));
        QCOMPARE(problems.items[0].path, std::string("lights[0]"));
        qInfo("%s", problems.items[0].toString().c_str());
    }

    // The occlusion term alone (the occlusion view: material occlusion x GTAO).
    void occlusionIsOneOnAnOpenPlane() {
        Scene scene = stageScene(PreviewMeshKind::Plane);
        scene.camera.orthographic = false;
        scene.camera.target = {0.0f, 0.0f, 0.0f};
        scene.camera.distance = 3.0f;
        scene.environment.ambientOcclusion = true;
        scene.environment.occlusionRadius = 0.4f;
        const int size = 96;
        const Image ao = renderLinear(scene, size, render::DebugView::Occlusion);
        const Image normal = renderLinear(scene, size, render::DebugView::Normal);
        int checked = 0;
        float least = 1.0f;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                if (glm::length(glm::vec3(normal.rgba(x, y))) < 0.5f)
                    continue;
                ++checked;
                least = std::min(least, ao.rgba(x, y).r);
            }
        qInfo("%d plane pixels, least occlusion term %.4f", checked, double(least));
        QVERIFY(checked > 1000);
        QVERIFY2(least > 0.97f, qPrintable(QString("open plane occluded: %1").arg(least)));
    }

    void occlusionIsBelowOneInACrease() {
        Scene scene = stageScene(PreviewMeshKind::Cube); // half size 0.8, on the ground
        scene.camera.orthographic = false;
        scene.camera.target = {0.0f, -0.8f, 0.0f};
        scene.camera.distance = 5.0f;
        scene.environment.ground = GroundMode::Plain;
        scene.environment.ambientOcclusion = true;
        scene.environment.occlusionRadius = 0.3f;
        const int size = 128;
        const Image ao = renderLinear(scene, size, render::DebugView::Occlusion);
        const Image pos = renderLinear(scene, size, render::DebugView::Position);
        double creaseSum = 0.0, openSum = 0.0;
        int crease = 0, open = 0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const glm::vec3 p = glm::vec3(pos.rgba(x, y));
                if (p.y > -0.8f || p.y < -0.81f) // the ground
                    continue;
                // Distance from the cube's footprint (|x|, |z| <= 0.8).
                const float dx = std::max(std::abs(p.x) - 0.8f, 0.0f);
                const float dz = std::max(std::abs(p.z) - 0.8f, 0.0f);
                const float d = std::sqrt(dx * dx + dz * dz);
                const float a = ao.rgba(x, y).r;
                if (d > 0.01f && d < 0.06f) {
                    creaseSum += a;
                    ++crease;
                } else if (d > 0.8f) {
                    openSum += a;
                    ++open;
                    QVERIFY2(a > 0.95f, qPrintable(QString("open ground occluded: %1").arg(a)));
                }
            }
        qInfo("crease: %d pixels, mean %.3f; open ground: %d pixels, mean %.3f", crease,
              creaseSum / std::max(crease, 1), open, openSum / std::max(open, 1));
        QVERIFY(crease >= 10 && open >= 100);
        QVERIFY(creaseSum / crease < 0.9);
        QVERIFY(openSum / open > 0.98);
    }
};

QTEST_GUILESS_MAIN(TestRenderShadows)
#include "test_render_shadows.moc"
