// core/turntable, core/frame_pattern, core/default_stage: the turntable's frame scenes are the
// world turned about +Y (known answers through the renderer's own camera and environment
// conventions), numbered output patterns, and the HDRI default rotation on synthetic maps.
#include "core/default_stage.h"
#include "core/frame_pattern.h"
#include "core/turntable.h"
#include "render/camera.h"

#include <QtTest>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

using namespace velvet;

namespace {

/// R_y(angle), right-handed (+X towards -Z), as a matrix built by GLM, not by turntable.cpp.
glm::vec3 turned(const glm::vec3& v, float angleDeg) {
    return glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(angleDeg), glm::vec3(0, 1, 0)) *
                     glm::vec4(v, 0.0f));
}

/// The environment direction a world direction samples: toEnvironment in
/// common_environment.glsl, line for line.
glm::vec3 toEnvironment(const glm::vec3& d, float rotationDeg) {
    const float c = std::cos(glm::radians(rotationDeg)), s = std::sin(glm::radians(rotationDeg));
    return {c * d.x - s * d.z, d.y, s * d.x + c * d.z};
}

bool near(const glm::vec3& a, const glm::vec3& b, float eps = 1e-4f) {
    return glm::length(a - b) < eps;
}

Scene sampleScene() {
    Scene scene;
    scene.camera.yawDeg = 20.0f;
    scene.camera.pitchDeg = 15.0f;
    scene.camera.target = {0.1f, 0.2f, -0.3f};
    scene.environment.rotationDeg = 30.0f;
    Light key;
    key.type = LightType::Spot;
    key.position = {1.0f, 2.0f, 3.0f};
    key.direction = {-0.2f, -0.6f, -0.7f};
    scene.lights = {key};
    return scene;
}

/// An equirectangular map, dark (0.02) everywhere but for what @p paint adds.
Image syntheticMap(int w, int h) {
    Image map(w, h, 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = map.at(x, y);
            p[0] = p[1] = p[2] = 0.02f;
            p[3] = 1.0f;
        }
    return map;
}
/// Column of azimuth @p phiDeg (0 = -Z, as equirectDirection lays the map out).
int columnOf(float phiDeg, int w) {
    return int(std::floor((phiDeg / 360.0f + 0.5f) * float(w))) % w;
}
void fill(Image& map, float phiDeg, float widthDeg, float elevLowDeg, float elevHighDeg,
          float value) {
    for (int y = 0; y < map.height; ++y) {
        const float elevation = 90.0f - (float(y) + 0.5f) / float(map.height) * 180.0f;
        if (elevation < elevLowDeg || elevation > elevHighDeg)
            continue;
        const int half = int(widthDeg / 360.0f * float(map.width) / 2.0f);
        for (int dx = -half; dx <= half; ++dx) {
            float* p =
                map.at(((columnOf(phiDeg, map.width) + dx) % map.width + map.width) % map.width, y);
            p[0] = p[1] = p[2] = value;
        }
    }
}

float angularDistance(float a, float b) {
    const float d = std::fmod(std::abs(a - b), 360.0f);
    return std::min(d, 360.0f - d);
}

} // namespace

class TestCoreTurntable : public QObject {
    Q_OBJECT
private slots:
    void patternsParse() {
        std::string why;
        auto p = parseFramePattern("out/%03d.png", &why);
        QVERIFY2(p, why.c_str());
        QCOMPARE(framePath(*p, 0), std::string("out/000.png"));
        QCOMPARE(framePath(*p, 42), std::string("out/042.png"));
        QCOMPARE(framePath(*p, 1234), std::string("out/1234.png"));
        p = parseFramePattern("frame_%d.exr", &why);
        QVERIFY(p);
        QCOMPARE(framePath(*p, 7), std::string("frame_7.exr"));
        p = parseFramePattern("100%%_%4d.png", &why);
        QVERIFY(p);
        QCOMPARE(framePath(*p, 7), std::string("100%_   7.png"));
    }

    void badPatternsAreRefused_data() {
        QTest::addColumn<QString>("pattern");
        QTest::newRow("no number") << "out/frame.png";
        QTest::newRow("string") << "out/%s.png";
        QTest::newRow("hex") << "out/%x.png";
        QTest::newRow("two numbers") << "out/%d_%03d.png";
        QTest::newRow("left-aligned") << "out/%-3d.png";
        QTest::newRow("lone percent") << "out/50%.png";
        QTest::newRow("zero without width") << "out/%0d.png";
        QTest::newRow("width too large") << "out/%012d.png";
        QTest::newRow("number in a folder") << "out_%02d/frame.png";
    }
    void badPatternsAreRefused() {
        QFETCH(QString, pattern);
        std::string why;
        QVERIFY(!parseFramePattern(pattern.toStdString(), &why));
        QVERIFY2(why.find(pattern.toStdString()) != std::string::npos, why.c_str());
        qInfo("%s", why.c_str());
    }

    void anglesCoverOneTurnWithoutRepeating() {
        QCOMPARE(turntableAngleDeg(0, 8), 0.0f);
        QCOMPARE(turntableAngleDeg(2, 8), 90.0f);
        QCOMPARE(turntableAngleDeg(7, 8), 315.0f);
        QCOMPARE(parseTurntableMode("mesh"), std::optional(TurntableMode::Mesh));
        QCOMPARE(parseTurntableMode("light"), std::optional(TurntableMode::Light));
        QVERIFY(!parseTurntableMode("camera"));
    }

    // Mesh mode: what the camera sees of a mesh point p turned by +theta is what frame theta's
    // camera sees of p unturned, for the view matrix, every light and every environment lookup.
    void meshModeIsTheMeshTurned() {
        const Scene scene = sampleScene();
        for (float theta : {15.0f, 90.0f, 200.0f}) {
            const Scene frame = turntableScene(scene, TurntableMode::Mesh, theta);
            const glm::mat4 v0 = render::viewMatrix(scene.camera);
            const glm::mat4 vk = render::viewMatrix(frame.camera);
            for (glm::vec3 p : {glm::vec3(0.5f, 0.1f, 0.2f), glm::vec3(-0.3f, 0.8f, -0.6f)}) {
                const glm::vec3 a = glm::vec3(v0 * glm::vec4(turned(p, theta), 1.0f));
                const glm::vec3 b = glm::vec3(vk * glm::vec4(p, 1.0f));
                QVERIFY2(near(a, b), qPrintable(QString("theta %1").arg(theta)));
            }
            // Lights relative to the mesh: frame k's light is frame 0's turned back by theta.
            QVERIFY(near(frame.lights[0].position, turned(scene.lights[0].position, -theta)));
            QVERIFY(near(frame.lights[0].direction, turned(scene.lights[0].direction, -theta)));
            // The environment seen along mesh-space direction d in frame k is what frame 0 sees
            // along d turned with the mesh.
            const glm::vec3 d = glm::normalize(glm::vec3(0.3f, 0.2f, -0.9f));
            QVERIFY(near(toEnvironment(d, frame.environment.rotationDeg),
                         toEnvironment(turned(d, theta), scene.environment.rotationDeg)));
            QCOMPARE(frame.mesh, scene.mesh);
        }
    }

    // Light mode: the camera stays; the lights and the environment turn by +theta.
    void lightModeTurnsTheLightsAndTheEnvironment() {
        const Scene scene = sampleScene();
        const float theta = 70.0f;
        const Scene frame = turntableScene(scene, TurntableMode::Light, theta);
        QCOMPARE(frame.camera, scene.camera);
        QVERIFY(near(frame.lights[0].position, turned(scene.lights[0].position, theta)));
        QVERIFY(near(frame.lights[0].direction, turned(scene.lights[0].direction, theta)));
        // A feature of the map seen along d in frame 0 is seen along d turned by theta.
        const glm::vec3 d = glm::normalize(glm::vec3(0.3f, 0.2f, -0.9f));
        QVERIFY(near(toEnvironment(turned(d, theta), frame.environment.rotationDeg),
                     toEnvironment(d, scene.environment.rotationDeg)));
    }

    // A bright backdrop patch at azimuth phi: the rotation puts it where the camera looks (-Z),
    // through the shader's own lookup; a brighter but tiny sun elsewhere, and a bright patch
    // overhead (outside the backdrop band), do not win.
    void backdropRotationFindsTheBrightPatch() {
        for (float phi : {-120.0f, 0.0f, 45.0f, 100.0f, 170.0f}) {
            Image map = syntheticMap(512, 256);
            fill(map, phi, 50.0f, -20.0f, 10.0f, 2.0f);          // a wide softbox
            fill(map, phi + 150.0f, 2.0f, 5.0f, 7.0f, 500.0f);   // a tiny sun
            fill(map, phi - 90.0f, 120.0f, 60.0f, 90.0f, 50.0f); // bright sky overhead
            const float rotation = backdropRotationDeg(map);
            const glm::vec3 e = toEnvironment(glm::vec3(0, 0, -1), rotation);
            const float seenPhi = glm::degrees(std::atan2(e.x, -e.z)); // equirectUv
            QVERIFY2(angularDistance(seenPhi, phi) <= 1.5f,
                     qPrintable(QString("patch at %1, rotation %2 looks at %3")
                                    .arg(phi)
                                    .arg(rotation)
                                    .arg(seenPhi)));
            QVERIFY(rotation >= 0.0f && rotation < 360.0f);
        }
    }

    void framingFillsTheRequestedShare() {
        Camera c;
        c.target = {1, 2, 3};
        const Camera framed = framedCamera(c, 1.0f, 0.8f);
        QCOMPARE(framed.target, glm::vec3(0.0f));
        // The unit sphere's silhouette half-angle asin(1/d): tan of it over tan(fov/2) = 0.8.
        const float fill = std::tan(std::asin(1.0f / framed.distance)) /
                           std::tan(glm::radians(framed.fovYDeg * 0.5f));
        QVERIFY(std::abs(fill - 0.8f) < 1e-4f);
        QVERIFY(std::abs(framed.orthoHeight - 2.5f) < 1e-5f);
    }
};

QTEST_GUILESS_MAIN(TestCoreTurntable)
#include "test_core_turntable.moc"
