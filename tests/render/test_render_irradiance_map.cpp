// The environment's irradiance the lighting reads in place of its SH9 (render/irradiance_map.h):
// against the irradiance integrated on the CPU over every texel of the full-resolution
// environment, a white Lambertian sphere is within a per cent at every normal, where the SH9 of
// the same environment is off by about ten; a uniform environment stays exact; the cube is
// integrated once per environment.
#include "core/spherical_harmonics.h"
#include "render_test_util.h"

#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <glm/geometric.hpp>

using namespace velvet;

namespace {

constexpr float kPi = 3.14159265358979f;

/// E(n) / pi of @p env: every texel's radiance weighed by its cosine and solid angle, normalised
/// by the weights as the cube is (a uniform environment gives its radiance exactly).
float integratedIrradianceOverPi(glm::vec3 n, const Image& env) {
    double sum = 0.0, weights = 0.0;
    for (int y = 0; y < env.height; ++y) {
        const float v = (float(y) + 0.5f) / float(env.height);
        const float sinTheta = std::sin(kPi * v);
        for (int x = 0; x < env.width; ++x) {
            const glm::vec3 d = equirectDirection((float(x) + 0.5f) / float(env.width), v);
            const double w = double(std::max(glm::dot(n, d), 0.0f) * sinTheta);
            sum += w * double(env.at(x, y)[0]);
            weights += w;
        }
    }
    return float(sum / weights);
}

/// A white Lambertian sphere (no specular lobe), orthographic, seen from the front: each pixel
/// is its albedo times E(n) / pi; its normal from the normal view.
test::ImageWithNormals renderWhiteSphere(const Scene& scene, int size) {
    render::FrameSettings fs;
    fs.width = fs.height = size;
    return test::renderWithNormals(scene, fs);
}

Scene whiteSphereScene() {
    Scene scene = test::uniformEnvironmentScene(glm::vec3(1.0f));
    scene.material = test::whiteMaterial(0.0f, 1.0f, 0.0f);
    scene.camera.orthographic = true;
    scene.camera.yawDeg = 0.0f;
    scene.camera.pitchDeg = 0.0f;
    return scene;
}

} // namespace

class TestRenderIrradianceMap : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;

private slots:
    void initTestCase() {
        const std::string error = test::startWithCacheIn(m_dir);
        QVERIFY2(error.empty(), error.c_str());
    }

    // A bright soft lamp over a dim sky (test::lampEnvironment): every fourth pixel of the sphere
    // against the CPU's integral over the 512 x 256 texels. The cube integrates the 64-wide mip
    // (render/irradiance_map.h); the SH9 of the same texels (core/spherical_harmonics.h), which
    // the lighting read before, cannot follow the lamp's falloff.
    void theIrradianceIsTheEnvironmentsIntegral() {
        const Image env = test::lampEnvironment();
        std::string error;
        const std::string path = (m_dir.path() + "/lamp.exr").toStdString();
        QVERIFY2(writeImage(path, env, PixelFormat::Float, &error), error.c_str());
        Scene scene = whiteSphereScene();
        scene.environment.hdri = path;
        const test::ImageWithNormals rest = renderWhiteSphere(scene, 48);
        const SH9 sh = projectEquirect(env);
        double errRest = 0.0, errSh = 0.0, worstRest = 0.0;
        int count = 0;
        for (int y = 0; y < 48; y += 4)
            for (int x = 0; x < 48; x += 4) {
                const glm::vec3 n(rest.normal.rgba(x, y));
                if (glm::length(n) < 0.5f)
                    continue;
                const float expected = integratedIrradianceOverPi(glm::normalize(n), env);
                const double e = std::abs(rest.color.rgba(x, y).g - expected) / expected;
                errRest += e;
                worstRest = std::max(worstRest, e);
                const float viaSh = evalIrradianceOverPi(sh, glm::normalize(n)).g;
                errSh += std::abs(viaSh - expected) / expected;
                ++count;
            }
        errRest /= count;
        errSh /= count;
        qInfo("%d pixels; mean relative error against the integral: the cube %.4f (worst %.4f), "
              "the SH9 %.4f",
              count, errRest, worstRest, errSh);
        QVERIFY(count > 80);
        QVERIFY2(errRest < 0.02 && worstRest < 0.05,
                 qPrintable(QString::number(errRest) + " " + QString::number(worstRest)));
        QVERIFY2(errRest * 5.0 < errSh,
                 qPrintable(QString::number(errRest) + " " + QString::number(errSh)));
    }

    // A uniform environment of radiance 0.7 lights the white Lambertian sphere to 0.7 (the
    // cube's weights are normalised; a uniform environment's one texel is read on a grid).
    void aUniformEnvironmentStaysExact() {
        Scene scene = whiteSphereScene();
        scene.environment.color = glm::vec3(0.7f);
        const test::ImageWithNormals rest = renderWhiteSphere(scene, 32);
        double worst = 0.0;
        int count = 0;
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x)
                if (glm::length(glm::vec3(rest.normal.rgba(x, y))) > 0.5f) {
                    worst = std::max(worst, double(std::abs(rest.color.rgba(x, y).g - 0.7f)));
                    ++count;
                }
        qInfo("%d pixels, worst |value - 0.7| %.5f", count, worst);
        QVERIFY(count > 500);
        QVERIFY2(worst < 0.7 * 0.005, qPrintable(QString::number(worst)));
    }

    // One integration per environment: the first frame integrates, the next ones, moving or at
    // rest, reuse the cube; a new environment integrates once more.
    void theCubeIsIntegratedOncePerEnvironment() {
        test::OffscreenRenderer r;
        const std::string started = r.start(16);
        QVERIFY2(started.empty(), started.c_str());
        Scene scene = whiteSphereScene();
        r.renderer->setScene(scene);
        r.renderer->finishEnvironment();
        render::FrameSettings fs;
        fs.width = fs.height = 16;
        std::string error;
        const auto draw = [&](int samples) {
            fs.reflectionSamples = samples;
            if (!r.renderer->render(fs, r.target->framebuffer(), &error))
                qFatal("render failed: %s", error.c_str());
            return r.renderer->irradianceIntegrations();
        };
        QCOMPARE(draw(0), 1);
        QCOMPARE(draw(0), 1);
        QCOMPARE(draw(render::kRefinementReflectionSamples), 1);
        scene.environment.color = glm::vec3(0.3f);
        r.renderer->update(scene, ScenePart::Environment);
        r.renderer->finishEnvironment();
        QCOMPARE(draw(0), 2);
        scene.environment.intensity = 2.0f; // applied by the lookup: the same cube
        r.renderer->update(scene, ScenePart::Environment);
        QCOMPARE(draw(0), 2);
        r.stop();
    }
};

QTEST_GUILESS_MAIN(TestRenderIrradianceMap)
#include "test_render_irradiance_map.moc"
