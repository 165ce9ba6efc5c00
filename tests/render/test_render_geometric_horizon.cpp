// Light from below the surface (gbuffer_read.glsl's geometricHorizon): a normal map bends the
// shading normal, not the surface, so a light under the surface's geometric horizon must not
// light it even where the bent normal faces it (the reference path tracer's rule,
// reference/light_sampling.cpp). Known answers through the real pipeline: a flat plane seen from
// above with a normal map tilted 60 degrees towards +X, lit only by one light at a time, the
// environment dark. A light 15 degrees below the plane on the tilt's side (n.l = 0.71 with the
// bent normal) leaves every pixel black, for a directional, a point and an area light; the same
// directional light 15 degrees above lights the plane with the Lambert value of the bent normal.
#include "core/image.h"
#include "render_test_util.h"

#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

using namespace velvet;
namespace fs = std::filesystem;

namespace {

constexpr int kSize = 64;
constexpr float kAlbedo = 0.5f;
constexpr float kTiltDeg = 60.0f;

/// The tangent-space normal tilted towards the tangent (+X on the plane), as 8 bits store it.
glm::vec3 storedTiltedNormal(glm::vec3* colour) {
    const float t = glm::radians(kTiltDeg);
    const glm::vec3 n(std::sin(t), 0.0f, std::cos(t));
    glm::vec3 c;
    for (int k = 0; k < 3; ++k)
        c[k] = std::round((n[k] * 0.5f + 0.5f) * 255.0f) / 255.0f;
    if (colour)
        *colour = c;
    return glm::normalize(c * 2.0f - 1.0f);
}

float maxValue(const Image& image) {
    float m = 0.0f;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int k = 0; k < 3; ++k)
                m = std::max(m, image.at(x, y)[k]);
    return m;
}

} // namespace

class TestRenderGeometricHorizon : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;
    Scene m_scene;

    Image draw(const Light& light) {
        Scene scene = m_scene;
        scene.lights = {light};
        return velvet::test::processRenderer(kSize)->draw(&scene);
    }

    static Light directional(float elevationDeg) {
        const float e = glm::radians(elevationDeg);
        Light l;
        l.type = LightType::Directional;
        l.intensity = 2.0f;
        l.direction = -glm::vec3(std::cos(e), std::sin(e), 0.0f); // travels towards the plane
        return l;
    }

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(velvet::test::headlessContext(&error), error.c_str());
        QVERIFY(m_dir.isValid());
        glm::vec3 colour;
        storedTiltedNormal(&colour);
        Image normal(4, 4, 4);
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) {
                float* p = normal.at(x, y);
                p[0] = colour.r, p[1] = colour.g, p[2] = colour.b, p[3] = 1.0f;
            }
        const fs::path file = fs::path(m_dir.path().toStdString()) / "tilted_normal.png";
        QVERIFY2(writeImage(file, normal, PixelFormat::UInt8, &error), error.c_str());

        m_scene.mesh.kind = PreviewMeshKind::Plane;
        m_scene.camera.pitchDeg = 60.0f;
        m_scene.camera.distance = 2.0f;
        m_scene.environment.intensity = 0.0f; // only the light under test
        m_scene.environment.background = BackgroundMode::SolidColor;
        m_scene.environment.backgroundColor = glm::vec3(0.0f);
        Material& m = m_scene.material;
        m.setColor(ParamId::BaseColor, glm::vec3(kAlbedo));
        m.setScalar(ParamId::Metallic, 0.0f);
        m.setScalar(ParamId::Roughness, 1.0f);
        m.setScalar(ParamId::SpecularWeight, 0.0f);
        m.setScalar(ParamId::SheenWeight, 0.0f);
        m.setScalar(ParamId::ClearcoatWeight, 0.0f);
        m.setChoice(ParamId::Diffuse, int(Diffuse::Lambert));
        TextureRef ref;
        ref.file = file.string();
        ref.colorSpace = "Raw";
        m.setTexture(TextureSlot::Normal, ref);
    }
    void cleanupTestCase() { velvet::test::stopProcessRenderer(); }

    // The control: above the horizon the bent normal is lit as Lambert's law says, so the plane
    // and its tilt are what the other cases assume (a tilt the other way would leave it dark).
    void aboveTheHorizonLitByTheBentNormal() {
        const Light light = directional(15.0f);
        const Image image = draw(light);
        const glm::vec3 nt = storedTiltedNormal(nullptr);
        // Tangent +X, normal +Y, bitangent cross(n, t) = -Z (render/gbuffer.frag's frame).
        const glm::vec3 n = glm::normalize(glm::vec3(nt.x, nt.z, -nt.y));
        const float expected =
            kAlbedo / 3.14159265f * light.intensity * std::max(glm::dot(n, -light.direction), 0.0f);
        const float centre = image.at(kSize / 2, kSize / 2)[1];
        qInfo("lit above the horizon: %.4f (Lambert with the bent normal: %.4f)", centre, expected);
        QVERIFY(expected > 0.25f);
        QVERIFY2(std::abs(centre - expected) < 0.02f * expected,
                 qPrintable(QString::number(centre)));
    }

    // Below it nothing arrives, though the bent normal faces the light.
    void belowTheHorizonDirectionalLightsNothing() {
        const Image image = draw(directional(-15.0f));
        qInfo("brightest pixel under a directional light below the horizon: %.6f", maxValue(image));
        QVERIFY(maxValue(image) < 1e-4f);
    }

    void belowTheHorizonPointLightLightsNothing() {
        Light point;
        point.type = LightType::Point;
        point.position = {1.6f, -0.35f, 0.0f}; // n.l about 0.75 at the plane's centre
        point.intensity = 8.0f;
        point.range = 10.0f;
        const Image below = draw(point);
        qInfo("brightest pixel under a point light below the horizon: %.6f", maxValue(below));
        QVERIFY(maxValue(below) < 1e-4f);
        point.position.y = 0.35f; // the control, mirrored above the plane
        QVERIFY(maxValue(draw(point)) > 0.05f);
    }

    void belowTheHorizonAreaLightLightsNothing() {
        Light area;
        area.type = LightType::Area;
        area.shape = AreaShape::Rectangle;
        area.size = {0.3f, 0.3f};
        area.position = {1.8f, -0.6f, 0.0f};
        area.direction = glm::normalize(-area.position); // facing the plane's centre
        area.intensity = 20.0f;
        area.range = 10.0f;
        const Image below = draw(area);
        qInfo("brightest pixel under an area light below the horizon: %.6f", maxValue(below));
        QVERIFY(maxValue(below) < 1e-4f);
        area.position.y = 0.6f;
        area.direction = glm::normalize(-area.position);
        QVERIFY(maxValue(draw(area)) > 0.05f);
    }
};

QTEST_GUILESS_MAIN(TestRenderGeometricHorizon)
#include "test_render_geometric_horizon.moc"
