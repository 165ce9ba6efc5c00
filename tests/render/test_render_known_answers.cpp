// Known answers of the deferred renderer: what each case proves is stated on the case.
#include "core/brdf.h"
#include "core/brdf_energy.h"
#include "core/mesh.h"
#include "render/camera.h"
#include "render/gbuffer_layout.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QtTest>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/trigonometric.hpp>
#include <random>

using namespace velvet;

namespace {

struct Frame {
    Image linear, display;
};

Frame renderScene(const Scene& scene, int size, render::DebugView view = render::DebugView::Final,
                  bool multiScatter = true) {
    render::FrameSettings fs;
    fs.width = fs.height = size;
    fs.view = view;
    fs.specularMultiScatter = multiScatter;
    Frame f;
    std::string error;
    Problems problems;
    if (!render::renderSceneOffscreen(scene, fs, &f.linear, &f.display, &error, &problems))
        qFatal("render failed: %s", error.c_str());
    return f;
}

Material greyLambert() {
    Material m;
    m.setColor(ParamId::BaseColor, glm::vec3(0.5f));
    m.setScalar(ParamId::Metallic, 0.0f);
    m.setScalar(ParamId::SpecularWeight, 0.0f);
    m.setScalar(ParamId::SheenWeight, 0.0f);
    m.setScalar(ParamId::ClearcoatWeight, 0.0f);
    return m;
}

/// A lit pixel against the C++ twin: "" when every channel is within max(@p relative x expected,
/// @p absolute), else what differs. @p worstRel keeps the largest relative difference seen.
QString compareWithTwin(glm::vec3 got, glm::vec3 expected, double relative, double absolute, int x,
                        int y, double& worstRel) {
    for (int k = 0; k < 3; ++k) {
        const double err = std::abs(double(got[k]) - expected[k]);
        worstRel = std::max(worstRel, err / std::max(double(expected[k]), 1e-3));
        if (err > std::max(relative * expected[k], absolute))
            return QString("pixel (%1,%2) channel %3: GPU %4, CPU %5")
                .arg(x)
                .arg(y)
                .arg(k)
                .arg(got[k])
                .arg(expected[k]);
    }
    return {};
}

double angleDeg(glm::dvec3 a, glm::dvec3 b) {
    return glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

} // namespace

class TestRenderKnownAnswers : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        std::string error;
        auto* ctx = test::headlessContext(&error);
        QVERIFY2(ctx, error.c_str());
        qInfo("GL: %s | %s | %s | EGL platform: %s", ctx->vendor().c_str(), ctx->renderer().c_str(),
              ctx->version().c_str(), ctx->platform().c_str());
        QCOMPARE(render::gbufferBytesPerPixel(), 24); // 16 common + 8 lobe channels
    }

    // (a) White furnace, diffuse only: a grey Lambertian sphere (no specular, sheen or coat) under
    // a uniform white environment reflects exactly its albedo, since SH9 of a constant is exact.
    void uniformEnvironmentGivesAlbedo() {
        Scene scene;
        scene.material = greyLambert();
        scene.environment.hdri.clear();
        scene.environment.color = glm::vec3(1.0f);
        scene.environment.intensity = 1.0f;
        const Frame f = renderScene(scene, 128);
        const Frame depth = renderScene(scene, 128, render::DebugView::Depth);
        int count = 0;
        float worst = 0.0f;
        QString where;
        for (int y = 0; y < 128; ++y)
            for (int x = 0; x < 128; ++x) {
                if (depth.linear.rgba(x, y).x <= 0.0f)
                    continue;
                const glm::vec4 c = f.linear.rgba(x, y);
                for (int k = 0; k < 3; ++k)
                    if (std::abs(c[k] - 0.5f) > worst) {
                        worst = std::abs(c[k] - 0.5f);
                        where = QString("(%1,%2) = %3 %4 %5 depth %6")
                                    .arg(x)
                                    .arg(y)
                                    .arg(c.x)
                                    .arg(c.y)
                                    .arg(c.z)
                                    .arg(depth.linear.rgba(x, y).x);
                    }
                ++count;
            }
        qInfo("furnace: %d sphere pixels, worst |value - 0.5| = %.5f at %s", count, worst,
              qPrintable(where));
        QVERIFY(count >
                128 * 128 * 3 / 10); // the default camera frames the sphere at ~39 % of the image
        QVERIFY2(worst <= 0.005f, qPrintable(QString("worst deviation %1").arg(worst)));
    }

    // (b) Analytic sphere: orthographic camera, one directional light, no environment. Each lit
    // pixel equals the C++ twin of the BRDF evaluated with that pixel's G-buffer values (normal,
    // base colour, roughness, metallic read back through the debug views).
    void directionalLightMatchesCpuTwin_data() {
        QTest::addColumn<int>("which");
        QTest::newRow("dielectric rough") << 0;
        QTest::newRow("dielectric smooth") << 1;
        QTest::newRow("metal") << 2;
        QTest::newRow("sheen") << 3;
        QTest::newRow("clearcoat") << 4;
    }
    void directionalLightMatchesCpuTwin() {
        QFETCH(int, which);
        Scene scene = test::blackOrthographicScene();
        const Light light = test::analyticKeyLight();
        scene.lights = {light};
        Material& m = scene.material;
        m.setColor(ParamId::BaseColor, {0.8f, 0.3f, 0.2f});
        m.setScalar(ParamId::Roughness, 0.5f);
        if (which == 1)
            m.setScalar(ParamId::Roughness, 0.25f);
        if (which == 2) {
            m.setScalar(ParamId::Metallic, 1.0f);
            m.setScalar(ParamId::Roughness, 0.35f);
        }
        if (which == 3) {
            m.setScalar(ParamId::SheenWeight, 1.0f);
            m.setColor(ParamId::SheenColor, {1.0f, 0.6f, 0.7f});
            m.setScalar(ParamId::SheenRoughness, 0.4f);
        }
        if (which == 4) {
            m.setScalar(ParamId::ClearcoatWeight, 1.0f);
            m.setScalar(ParamId::ClearcoatRoughness, 0.2f);
        }

        const int size = 96;
        const Frame f = renderScene(scene, size);
        const Frame normal = renderScene(scene, size, render::DebugView::Normal);
        const Frame albedo = renderScene(scene, size, render::DebugView::Albedo);
        const Frame rough = renderScene(scene, size, render::DebugView::Roughness);
        const Frame metal = renderScene(scene, size, render::DebugView::Metallic);

        const glm::vec3 v = glm::normalize(render::cameraEye(scene.camera) - scene.camera.target);
        const glm::vec3 l = -glm::normalize(light.direction);
        const glm::vec3 E = light.color * light.intensity;
        int checked = 0;
        double worstRel = 0.0;
        for (int y = 4; y < size; y += 7)
            for (int x = 4; x < size; x += 7) {
                const glm::vec3 n = glm::vec3(normal.linear.rgba(x, y));
                if (glm::length(n) < 0.5f || glm::dot(n, l) < 0.1f || glm::dot(n, v) < 0.1f)
                    continue;
                brdf::Surface s = brdf::surfaceFromMaterial(m);
                s.baseColor = glm::vec3(albedo.linear.rgba(x, y));
                s.roughness = rough.linear.rgba(x, y).x;
                s.metallic = metal.linear.rgba(x, y).x;
                const glm::vec3 expected = brdf::evalDirectional(s, glm::normalize(n), v, l) * E;
                const QString mismatch = compareWithTwin(glm::vec3(f.linear.rgba(x, y)), expected,
                                                         0.02, 1.0 / 255.0, x, y, worstRel);
                if (!mismatch.isEmpty())
                    QFAIL(qPrintable(mismatch));
                ++checked;
            }
        qInfo("%d lit pixels match the CPU twin; worst relative difference %.4f", checked,
              worstRel);
        QVERIFY(checked >= 20);
    }

    // (b'') Direct light's multiple-scattering compensation (Turquin 2019, core/brdf_energy.h) on
    // a white metal at roughness 1 under the analytic key light: with FrameSettings::
    // specularMultiScatter on, each lit pixel is the compensated twin; off, the single-scattering
    // twin (the image before the compensation). Their ratio is 1 + F0 (1 - E) / E = 1 / E(n.v)
    // for F0 = 1, which head-on is 1 / (1 - ln 2) = 3.26 (E = 1 - ln 2 at alpha = 1, analytic).
    void directLightMultipleScattering() {
        Scene scene = test::blackOrthographicScene();
        const Light light = test::analyticKeyLight();
        scene.lights = {light};
        Material& m = scene.material;
        m.setColor(ParamId::BaseColor, glm::vec3(1.0f));
        m.setScalar(ParamId::Metallic, 1.0f);
        m.setScalar(ParamId::Roughness, 1.0f);
        m.setScalar(ParamId::SheenWeight, 0.0f);
        m.setScalar(ParamId::ClearcoatWeight, 0.0f);
        const int size = 64;
        const Frame on = renderScene(scene, size);
        const Frame off = renderScene(scene, size, render::DebugView::Final, false);
        const Frame normal = renderScene(scene, size, render::DebugView::Normal);
        const glm::vec3 v = glm::normalize(render::cameraEye(scene.camera) - scene.camera.target);
        const glm::vec3 l = -glm::normalize(light.direction);
        const glm::vec3 E = light.color * light.intensity;
        int checked = 0;
        double worstRel = 0.0, worstRatio = 0.0;
        for (int y = 2; y < size; y += 5)
            for (int x = 2; x < size; x += 5) {
                const glm::vec3 n = glm::vec3(normal.linear.rgba(x, y));
                if (glm::length(n) < 0.5f || glm::dot(n, l) < 0.1f || glm::dot(n, v) < 0.1f)
                    continue;
                const glm::vec3 nn = glm::normalize(n);
                brdf::Surface s = brdf::surfaceFromMaterial(m);
                const glm::vec3 compensated = brdf::evalDirectional(s, nn, v, l) * E;
                s.multipleScattering = false;
                const glm::vec3 single = brdf::evalDirectional(s, nn, v, l) * E;
                for (const auto& [frame, expected] :
                     {std::pair{&on, compensated}, std::pair{&off, single}}) {
                    const QString mismatch =
                        compareWithTwin(glm::vec3(frame->linear.rgba(x, y)), expected, 0.02,
                                        1.0 / 255.0, x, y, worstRel);
                    if (!mismatch.isEmpty())
                        QFAIL(qPrintable(mismatch));
                }
                // The ratio the GPU shows is the analytic factor 1 / E(n.v) of the table.
                const double ratio = on.linear.rgba(x, y).x / off.linear.rgba(x, y).x;
                const double factor = 1.0 / brdf::specularDirectionalAlbedo(glm::dot(nn, v), 1.0f);
                worstRatio = std::max(worstRatio, std::abs(ratio / factor - 1.0));
                ++checked;
            }
        // Head-on (n = v): ratio 1 / (1 - ln 2).
        const double headOn = 1.0 / brdf::specularDirectionalAlbedo(1.0f, 1.0f);
        qInfo("%d lit pixels match both twins (worst relative %.4f); on / off = 1 / E(n.v) within "
              "%.4f; head-on factor %.3f (analytic %.3f)",
              checked, worstRel, worstRatio, headOn, 1.0 / (1.0 - std::log(2.0)));
        QVERIFY(checked >= 20);
        QVERIFY(worstRatio < 0.02);
        QVERIFY(std::abs(headOn - 1.0 / (1.0 - std::log(2.0))) < 0.02);

        // A point light (the many-light paths, light_lobes.glsl) follows the same switch: on / off
        // is the same 1 / E(n.v) whatever the light's falloff.
        Light point;
        point.type = LightType::Point;
        point.position = {-1.2f, 1.5f, 2.0f};
        point.intensity = 8.0f;
        point.range = 10.0f;
        scene.lights = {point};
        const Frame pointOn = renderScene(scene, size);
        const Frame pointOff = renderScene(scene, size, render::DebugView::Final, false);
        int pointChecked = 0;
        double pointWorst = 0.0;
        for (int y = 2; y < size; y += 5)
            for (int x = 2; x < size; x += 5) {
                const glm::vec3 n = glm::vec3(normal.linear.rgba(x, y));
                const float single = pointOff.linear.rgba(x, y).x;
                if (glm::length(n) < 0.5f || glm::dot(n, v) < 0.1f || single < 0.01f)
                    continue;
                const double factor =
                    1.0 / brdf::specularDirectionalAlbedo(glm::dot(glm::normalize(n), v), 1.0f);
                pointWorst = std::max(
                    pointWorst, std::abs(pointOn.linear.rgba(x, y).x / single / factor - 1.0));
                ++pointChecked;
            }
        qInfo("point light: %d lit pixels, on / off = 1 / E(n.v) within %.4f", pointChecked,
              pointWorst);
        QVERIFY(pointChecked >= 20);
        QVERIFY(pointWorst < 0.02);
    }

    // (b') KHR_materials_anisotropy on the analytic sphere, for several strengths and rotations:
    // the anisotropy view holds, per pixel, the mesh tangent (the UV sphere's, (cos phi, 0,
    // -sin phi)) turned by the rotation towards the bitangent n x t, times the strength; and each
    // lit pixel equals the C++ twin evaluated with that pixel's G-buffer values and direction.
    void anisotropicSphereMatchesCpuTwin_data() {
        QTest::addColumn<float>("strength");
        QTest::addColumn<float>("rotationDeg");
        QTest::newRow("0.3, 0 deg") << 0.3f << 0.0f;
        QTest::newRow("0.8, 0 deg") << 0.8f << 0.0f;
        QTest::newRow("0.8, 90 deg") << 0.8f << 90.0f;
        QTest::newRow("1.0, -45 deg") << 1.0f << -45.0f;
    }
    void anisotropicSphereMatchesCpuTwin() {
        QFETCH(float, strength);
        QFETCH(float, rotationDeg);
        Scene scene = test::blackOrthographicScene();
        const Light light = test::analyticKeyLight();
        scene.lights = {light};
        Material& m = scene.material;
        m.setColor(ParamId::BaseColor, {0.9f, 0.85f, 0.8f});
        m.setScalar(ParamId::Metallic, 1.0f);
        m.setScalar(ParamId::Roughness, 0.3f);
        m.setScalar(ParamId::AnisotropyStrength, strength);
        m.setScalar(ParamId::AnisotropyRotation, rotationDeg);
        const int size = 96;
        const Frame f = renderScene(scene, size);
        const Frame normal = renderScene(scene, size, render::DebugView::Normal);
        const Frame albedo = renderScene(scene, size, render::DebugView::Albedo);
        const Frame aniso = renderScene(scene, size, render::DebugView::Anisotropy);

        const glm::vec3 v = glm::normalize(render::cameraEye(scene.camera) - scene.camera.target);
        const glm::vec3 l = -glm::normalize(light.direction);
        const glm::vec3 E = light.color * light.intensity;
        const float r = glm::radians(rotationDeg);
        int checked = 0;
        double worstRel = 0.0, worstAngle = 0.0, worstStrength = 0.0;
        for (int y = 4; y < size; y += 5)
            for (int x = 4; x < size; x += 5) {
                const glm::vec3 n = glm::vec3(normal.linear.rgba(x, y));
                if (glm::length(n) < 0.5f || glm::dot(n, v) < 0.2f || std::abs(n.y) > 0.9f)
                    continue; // background, grazing, or near a pole (where u is degenerate)
                const glm::vec3 nn = glm::normalize(n);
                const glm::vec3 a = glm::vec3(aniso.linear.rgba(x, y));
                worstStrength =
                    std::max(worstStrength, double(std::abs(glm::length(a) - strength)));
                const float phi = std::atan2(nn.x, nn.z);
                const glm::vec3 t0(std::cos(phi), 0.0f, -std::sin(phi));
                const glm::vec3 expectedT = std::cos(r) * t0 + std::sin(r) * glm::cross(nn, t0);
                const glm::vec3 t = glm::normalize(a);
                // t and -t are the same stretch
                worstAngle =
                    std::max(worstAngle, std::min(angleDeg(t, expectedT), angleDeg(-t, expectedT)));
                if (glm::dot(nn, l) < 0.1f)
                    continue;
                brdf::Surface s = brdf::surfaceFromMaterial(m);
                s.baseColor = glm::vec3(albedo.linear.rgba(x, y));
                s.anisotropyStrength = glm::length(a);
                s.anisotropyDirection = t;
                const glm::vec3 expected = brdf::evalDirectional(s, nn, v, l) * E;
                // 3 %: the direction and strength went through 8 bits each.
                const QString mismatch = compareWithTwin(glm::vec3(f.linear.rgba(x, y)), expected,
                                                         0.03, 2.0 / 255.0, x, y, worstRel);
                if (!mismatch.isEmpty())
                    QFAIL(qPrintable(mismatch));
                ++checked;
            }
        qInfo("%d lit pixels match the CPU twin (worst relative %.4f); direction within %.2f deg, "
              "strength within %.4f",
              checked, worstRel, worstAngle, worstStrength);
        QVERIFY(checked >= 20);
        QVERIFY2(worstAngle < 2.0, "the stretch follows the tangent and the rotation");
        QVERIFY2(worstStrength < 0.01, "the strength is stored per pixel");
    }

    // (c) Octahedral normals in 2 x 16 bits (precise variant): worst angular error over 10^6
    // random unit vectors (CPU twin of the GLSL; the encode/decode code is the same line for line).
    // One renderer through size changes (the editor resizes at every reduced-resolution frame and
    // window resize): each size gives the furnace's known answer, albedo on the sphere and the
    // environment behind it. ctest runs this with Mesa's force_gl_names_reuse, so a framebuffer
    // cached by texture name instead of allocation would keep drawing into deleted textures.
    void resizingKeepsTheKnownAnswer() {
        Scene scene;
        scene.material = greyLambert();
        scene.lights.clear();
        scene.environment.hdri.clear();
        scene.environment.color = glm::vec3(1.0f);
        render::Renderer renderer;
        std::string error;
        QVERIFY2(renderer.initialize(&error), error.c_str());
        renderer.setScene(scene);
        for (const int size : {64, 32, 96, 64}) {
            render::OffscreenTarget target;
            QVERIFY2(target.resize(size, size, &error), error.c_str());
            render::FrameSettings fs;
            fs.width = fs.height = size;
            QVERIFY2(renderer.render(fs, target.framebuffer(), &error), error.c_str());
            const Image linear = renderer.readLinear();
            QCOMPARE(linear.width, size);
            const glm::vec4 centre = linear.rgba(size / 2, size / 2);
            const glm::vec4 corner = linear.rgba(1, 1);
            QVERIFY2(std::abs(centre.x - 0.5f) < 0.01f && std::abs(corner.x - 1.0f) < 0.01f,
                     qPrintable(QStringLiteral("%1: centre %2, corner %3")
                                    .arg(size)
                                    .arg(double(centre.x))
                                    .arg(double(corner.x))));
        }
    }

    void octahedralEncodingError() {
        std::mt19937 rng(12345);
        std::normal_distribution<float> g;
        double worst = 0.0, worstPlain = 0.0;
        for (int i = 0; i < 1000000; ++i) {
            glm::vec3 n(g(rng), g(rng), g(rng));
            if (glm::length(n) < 1e-6f)
                continue;
            n = glm::normalize(n);
            const glm::vec3 d = render::octDecodeUnorm16(render::octEncodeUnorm16(n));
            worst = std::max(worst, angleDeg(glm::dvec3(n), glm::dvec3(d)));
            // Plain rounding, for the record.
            const glm::vec2 e = glm::round((render::octEncode(n) * 0.5f + 0.5f) * 65535.0f);
            const glm::vec3 p = render::octDecodeUnorm16(glm::uvec2(e));
            worstPlain = std::max(worstPlain, angleDeg(glm::dvec3(n), glm::dvec3(p)));
        }
        qInfo("octahedral 2x16-bit: worst angular error %.6f deg (precise), %.6f deg (rounded)",
              worst, worstPlain);
        QVERIFY2(worst <= 0.005, qPrintable(QString("worst error %1 deg").arg(worst)));
    }

    // (d) Position from depth: the view depth reconstructed on the GPU from the depth buffer and
    // the inverse projection equals the depth of the same ray's hit on the mesh (CPU ray casting
    // against the very triangles drawn) within 1e-3 relative.
    void positionFromDepth() {
        Scene scene;
        scene.camera.distance = 4.0f;
        scene.camera.pitchDeg = 20.0f;
        scene.camera.yawDeg = 30.0f;
        const int size = 96;
        const Frame f = renderScene(scene, size, render::DebugView::Depth);
        const MeshData mesh = makeSphere();
        const glm::mat4 view = render::viewMatrix(scene.camera);
        const glm::mat4 invViewProj =
            glm::inverse(render::projectionMatrix(scene.camera, 1.0f) * view);
        const glm::vec3 eye = render::cameraEye(scene.camera);
        const glm::vec3 forward = -glm::vec3(glm::inverse(view)[2]);
        int checked = 0;
        double worst = 0.0;
        for (int y = 2; y < size; y += 3)
            for (int x = 2; x < size; x += 3) {
                const float gpu = f.linear.rgba(x, y).x;
                if (gpu <= 0.0f)
                    continue;
                // Pixel centre -> world ray (image row 0 is the top).
                const glm::vec2 ndc((x + 0.5f) / size * 2.0f - 1.0f,
                                    1.0f - (y + 0.5f) / size * 2.0f);
                glm::vec4 far = invViewProj * glm::vec4(ndc, 1.0f, 1.0f);
                const glm::vec3 dir = glm::normalize(glm::vec3(far) / far.w - eye);
                double tBest = 1e30;
                for (size_t i = 0; i < mesh.indices.size(); i += 3) {
                    // Möller-Trumbore
                    const glm::dvec3 a = mesh.vertices[mesh.indices[i]].position;
                    const glm::dvec3 b = mesh.vertices[mesh.indices[i + 1]].position;
                    const glm::dvec3 c = mesh.vertices[mesh.indices[i + 2]].position;
                    const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(glm::dvec3(dir), e2);
                    const double det = glm::dot(e1, p);
                    if (std::abs(det) < 1e-12)
                        continue;
                    const glm::dvec3 t0 = glm::dvec3(eye) - a;
                    const double u = glm::dot(t0, p) / det;
                    if (u < 0 || u > 1)
                        continue;
                    const glm::dvec3 q = glm::cross(t0, e1);
                    const double w = glm::dot(glm::dvec3(dir), q) / det;
                    if (w < 0 || u + w > 1)
                        continue;
                    const double t = glm::dot(e2, q) / det;
                    if (t > 0 && t < tBest)
                        tBest = t;
                }
                if (tBest > 1e29)
                    continue; // silhouette pixel the rasteriser covered and the ray missed
                const double expected = tBest * glm::dot(dir, forward);
                worst = std::max(worst, std::abs(gpu - expected) / expected);
                ++checked;
            }
        qInfo("position from depth: %d pixels, worst relative view-depth error %.2e (half-float "
              "readback)",
              checked, worst);
        QVERIFY(checked > 200);
        QVERIFY2(worst <= 1e-3, qPrintable(QString("worst %1").arg(worst)));
    }

    // (e) Value edits: 100 roughness changes through setScene compile no shader and change the
    // image.
    void valueEditsDoNotRecompile() {
        render::Renderer renderer;
        std::string error;
        QVERIFY2(renderer.initialize(&error), error.c_str());
        render::OffscreenTarget target;
        QVERIFY2(target.resize(64, 64, &error), error.c_str());
        Scene scene = test::shippedDefaultScene();
        scene.environment.hdri.clear();
        scene.material.setScalar(ParamId::SheenWeight, 0.0f);
        render::FrameSettings fs;
        fs.width = fs.height = 64;
        // The first frame builds the lighting variant of the scene's features
        // (render/lighting_features.h); then roughness edits change none of them.
        renderer.setScene(scene);
        renderer.finishEnvironment(); // a bake completing mid-loop would build its variant
        QVERIFY2(renderer.render(fs, target.framebuffer(), &error), error.c_str());
        const int compiles = renderer.shaderCompileCount();
        QVERIFY(compiles > 0);
        glm::vec4 first{}, last{};
        for (int i = 0; i < 100; ++i) {
            scene.material.setScalar(ParamId::Roughness, float(i) / 99.0f);
            renderer.setScene(scene);
            QVERIFY2(renderer.render(fs, target.framebuffer(), &error), error.c_str());
            if (i == 0 || i == 99) {
                const Image img = renderer.readLinear();
                (i == 0 ? first : last) = img.rgba(40, 26);
            }
        }
        const render::FrameTimings t = renderer.lastTimings();
        qInfo(
            "64x64 frame on this GL: G-buffer %.2f ms, lighting %.2f ms, post %.2f ms, total %.2f "
            "ms (logged, not asserted)",
            t.gbufferMs, t.lightingMs, t.postMs, t.totalMs);
        QCOMPARE(renderer.shaderCompileCount(), compiles);
        QVERIFY2(glm::length(glm::vec3(first - last)) > 1e-3f, "roughness edits changed nothing");
    }
};

QTEST_GUILESS_MAIN(TestRenderKnownAnswers)
#include "test_render_known_answers.moc"
