// Reflections sampled (FrameSettings::reflectionSamples, common_environment.glsl's
// sampledReflection): the frames of the viewport at rest and supersampled stills estimate the
// isotropic GGX lobe's environment light with visible-normal samples instead of the split sum.
// Known answers: the estimator keeps a white furnace white, and at grazing angles it agrees with
// a brute-force integral of the lobe over the same environment, computed here on the CPU, where
// the split sum's one lookup does not; the sheen's samples keep its albedo under uniform light.
#include "core/brdf.h"
#include "core/ibl.h"
#include "core/image.h"
#include "core/spherical_harmonics.h"
#include "render/camera.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <glm/geometric.hpp>

using namespace velvet;

namespace {

constexpr float kPi = 3.14159265358979f;

/// The lobe's reflected light for F = 1, single scattering: 4096 GGX half vectors per pixel,
/// each weighted by f n.l / pdf = V 4 (n.l)(v.h) / (n.h) (glTF's separable Smith, the default
/// visibility term).
float bruteForceReflection(glm::vec3 n, glm::vec3 v, float alpha) {
    const glm::vec3 up = std::abs(n.y) < 0.999f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 t = glm::normalize(glm::cross(up, n)), b = glm::cross(n, t);
    const float NdotV = std::max(glm::dot(n, v), 1e-4f);
    constexpr int kSamples = 4096;
    double sum = 0.0;
    for (int i = 0; i < kSamples; ++i) {
        const glm::vec3 ht = ibl::importanceSampleGgx(ibl::hammersley(i, kSamples), alpha);
        const glm::vec3 h = t * ht.x + b * ht.y + n * ht.z;
        const glm::vec3 l = glm::reflect(-v, h);
        const float NdotL = glm::dot(n, l);
        if (NdotL <= 0.0f)
            continue;
        const float VdotH = std::max(glm::dot(v, h), 1e-4f);
        sum += double(brdf::visibilitySmithGGXSeparable(NdotL, NdotV, alpha) * 4.0f * NdotL *
                      VdotH / std::max(ht.z, 1e-4f) * test::lampRadiance(l));
    }
    return float(sum / kSamples);
}

/// The sheen lobe's reflected light for a white sheen colour: 4096 cosine-distributed directions
/// per pixel, each weighted by f n.l / pdf = pi D V (Charlie D and the material's visibility).
float bruteForceSheen(glm::vec3 n, glm::vec3 v, float sheenRoughness, SheenModel model) {
    const glm::vec3 up = std::abs(n.y) < 0.999f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 t = glm::normalize(glm::cross(up, n)), b = glm::cross(n, t);
    const float NdotV = std::max(glm::dot(n, v), 1e-4f);
    constexpr int kSamples = 4096;
    double sum = 0.0;
    for (int i = 0; i < kSamples; ++i) {
        const glm::vec2 u = ibl::hammersley(i, kSamples);
        const float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
        const glm::vec3 l = t * (r * std::cos(phi)) + b * (r * std::sin(phi)) +
                            n * std::sqrt(std::max(1.0f - u.x, 0.0f));
        const float NdotL = glm::dot(n, l);
        if (NdotL <= 1e-4f)
            continue;
        const float NdotH = glm::dot(n, glm::normalize(l + v));
        sum += double(kPi * brdf::distributionCharlie(NdotH, sheenRoughness) *
                      brdf::visibilitySheen(model, NdotL, NdotV, sheenRoughness) *
                      test::lampRadiance(l));
    }
    return float(sum / kSamples);
}

using Rendered = test::ImageWithNormals;

Rendered renderSphere(const Scene& scene, int size, render::FrameSettings fs) {
    fs.width = fs.height = size;
    return test::renderWithNormals(scene, fs);
}

float mean3(glm::vec4 c) {
    return (c.x + c.y + c.z) / 3.0f;
}

/// A sphere under the bright lamp (test::lampEnvironment, written to @p envPath), no lights,
/// seen by an orthographic camera from the front.
Scene lampScene(const std::string& envPath) {
    Scene scene;
    scene.lights.clear();
    scene.environment.hdri = envPath;
    scene.camera.orthographic = true;
    scene.camera.yawDeg = 0.0f;
    scene.camera.pitchDeg = 0.0f;
    return scene;
}

/// A white sheen of @p sheenRoughness alone: a black base with no specular.
Material sheenOnlyMaterial(float sheenRoughness) {
    Material m = test::whiteMaterial(0.0f, 0.9f, 0.0f);
    m.setColor(ParamId::BaseColor, glm::vec3(0.0f));
    m.setScalar(ParamId::SheenWeight, 1.0f);
    m.setColor(ParamId::SheenColor, glm::vec3(1.0f));
    m.setScalar(ParamId::SheenRoughness, sheenRoughness);
    return m;
}

} // namespace

class TestRenderSampledReflections : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;

private slots:
    void initTestCase() {
        const std::string error = test::startWithCacheIn(m_dir);
        QVERIFY2(error.empty(), error.c_str());
    }

    // Under a uniform white environment a white metal reflects all the light (the split sum's
    // multiple-scattering energy included): the sampled lobe too, at every roughness and view
    // angle, so its weights and the multiple-scattering gain are normalised alike (256 samples:
    // each pixel within 3 %, the mean within 2 %).
    void sampledReflectionKeepsTheFurnaceWhite() {
        Scene scene = test::uniformEnvironmentScene(glm::vec3(1.0f));
        for (float roughness : {0.1f, 0.35f, 0.7f}) { // up to kSampledReflectionMaxRoughness
            scene.material = test::whiteMaterial(1.0f, roughness);
            render::FrameSettings fs;
            const Rendered split = renderSphere(scene, 48, fs);
            fs.reflectionSamples = 256;
            const Rendered r = renderSphere(scene, 48, fs);
            double sum = 0.0, worst = 0.0, worstSplit = 0.0;
            int count = 0;
            for (int y = 0; y < 48; ++y)
                for (int x = 0; x < 48; ++x)
                    if (glm::length(glm::vec3(r.normal.rgba(x, y))) > 0.5f) {
                        const double v = mean3(r.color.rgba(x, y));
                        sum += v;
                        worst = std::max(worst, std::abs(v - 1.0));
                        worstSplit =
                            std::max(worstSplit, std::abs(mean3(split.color.rgba(x, y)) - 1.0));
                        ++count;
                    }
            qInfo("furnace, white metal roughness %.2f, sampled: %d pixels, mean %.4f, worst "
                  "|value - 1| %.4f (split sum %.4f)",
                  roughness, count, sum / count, worst, worstSplit);
            QVERIFY(count > 900);
            QVERIFY2(std::abs(sum / count - 1.0) <= 0.02, qPrintable(QString::number(sum / count)));
            QVERIFY2(worst <= 0.03, qPrintable(QString::number(worst)));
        }
    }

    // A glossy white metal (roughness 0.3) under a bright lamp, orthographic: per pixel the
    // brute-force integral of the lobe over the same radiance is the answer. On the pixels seen
    // at grazing angles (n.v < 0.5) the sampled lobe must agree with it within a few per cent
    // and be at least twice as close as the split sum, whose lookup assumes n = v = r.
    void sampledReflectionMatchesTheLobeIntegralAtGrazingAngles() {
        std::string error;
        const std::string envPath = (m_dir.path() + "/lamp.exr").toStdString();
        QVERIFY2(writeImage(envPath, test::lampEnvironment(), PixelFormat::Float, &error),
                 error.c_str());
        Scene scene = lampScene(envPath);
        const float roughness = 0.3f, alpha = roughness * roughness;
        scene.material = test::whiteMaterial(1.0f, roughness);
        render::FrameSettings fs;
        fs.specularMultiScatter = false; // single scattering, as the integral below
        const Rendered splitSum = renderSphere(scene, 64, fs);
        fs.reflectionSamples = 256;
        const Rendered sampled = renderSphere(scene, 64, fs);
        const glm::vec3 v = glm::normalize(render::cameraEye(scene.camera) - scene.camera.target);

        double errSampled = 0.0, errSplit = 0.0;
        int count = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                const glm::vec3 n(sampled.normal.rgba(x, y));
                if (glm::length(n) < 0.5f)
                    continue;
                const glm::vec3 nn = glm::normalize(n);
                const float NdotV = glm::dot(nn, v);
                if (NdotV < 0.1f || NdotV > 0.5f)
                    continue;
                const float expected = bruteForceReflection(nn, v, alpha);
                errSampled += std::abs(mean3(sampled.color.rgba(x, y)) - expected) / expected;
                errSplit += std::abs(mean3(splitSum.color.rgba(x, y)) - expected) / expected;
                ++count;
            }
        errSampled /= count;
        errSplit /= count;
        qInfo("grazing pixels (0.1 < n.v < 0.5): %d; mean relative error against the lobe's "
              "integral: sampled %.4f, split sum %.4f",
              count, errSampled, errSplit);
        QVERIFY(count > 200);
        QVERIFY2(errSampled < 0.05, qPrintable(QString::number(errSampled)));
        QVERIFY2(errSampled * 2.0 < errSplit,
                 qPrintable(QString::number(errSampled) + " " + QString::number(errSplit)));
    }

    // The sheen sampled at rest (common_environment.glsl's sampledSheenLight) under a uniform
    // white environment: its samples weighted by 2 pi D V n.l must add up to the sheen's
    // directional albedo, which the interactive frames' irradiance path gives exactly there
    // (sheenColor E(n.v) times 1). A black base with no specular leaves the sheen alone. At every
    // sheen roughness the means agree within 1 %, and each pixel within 10 % and 0.0005: where
    // the smooth sheen's albedo (roughness 0.3) is small and steep in n.v, facing the camera, the
    // samples read up to 7 % off the fit of E that the shaders tabulate (sheenDirectionalAlbedo),
    // and a wrong weight, pdf or normalisation is off by far more.
    void sampledSheenKeepsTheFurnacesAlbedo() {
        Scene scene = test::uniformEnvironmentScene(glm::vec3(1.0f));
        for (float sheenRoughness : {0.3f, 0.6f, 0.9f}) {
            scene.material = sheenOnlyMaterial(sheenRoughness);
            render::FrameSettings fs;
            const Rendered irradiance = renderSphere(scene, 48, fs);
            fs.reflectionSamples = 256;
            const Rendered sampled = renderSphere(scene, 48, fs);
            double sum = 0.0, sumIrradiance = 0.0, worst = 0.0;
            int count = 0;
            for (int y = 0; y < 48; ++y)
                for (int x = 0; x < 48; ++x)
                    if (glm::length(glm::vec3(sampled.normal.rgba(x, y))) > 0.5f) {
                        const double a = mean3(sampled.color.rgba(x, y));
                        const double b = mean3(irradiance.color.rgba(x, y));
                        sum += a;
                        sumIrradiance += b;
                        worst = std::max(worst, std::abs(a - b) / (b + 0.005));
                        ++count;
                    }
            qInfo("furnace, sheen roughness %.1f: %d pixels, sampled mean %.4f, irradiance path "
                  "%.4f, worst |difference| / (value + 0.005) %.4f",
                  sheenRoughness, count, sum / count, sumIrradiance / count, worst);
            QVERIFY(count > 900);
            QVERIFY(sumIrradiance / count > 0.05); // the sheen is there to compare
            QVERIFY2(std::abs(sum / sumIrradiance - 1.0) <= 0.01,
                     qPrintable(QString::number(sum / sumIrradiance)));
            QVERIFY2(worst <= 0.1, qPrintable(QString::number(worst)));
        }
    }

    // A sheen alone (black base, no specular; roughness 0.5) under the bright lamp behind the
    // sphere, orthographic: per pixel the brute-force integral of the lobe over the same radiance
    // is the answer. The sampled sheen must agree with it within a few per cent on average and be
    // at least twice as close as the irradiance about the lobe's one mean direction, which the
    // interactive frames keep.
    void sampledSheenMatchesTheLobeIntegral() {
        std::string error;
        const std::string envPath = (m_dir.path() + "/lamp_sheen.exr").toStdString();
        QVERIFY2(writeImage(envPath, test::lampEnvironment(), PixelFormat::Float, &error),
                 error.c_str());
        Scene scene = lampScene(envPath);
        const Material m = sheenOnlyMaterial(0.5f);
        scene.material = m;
        render::FrameSettings fs;
        const Rendered irradiance = renderSphere(scene, 64, fs);
        fs.reflectionSamples = 256;
        const Rendered sampled = renderSphere(scene, 64, fs);
        const glm::vec3 v = glm::normalize(render::cameraEye(scene.camera) - scene.camera.target);

        double errSampled = 0.0, errIrradiance = 0.0, sumExpected = 0.0;
        int count = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                const glm::vec3 n(sampled.normal.rgba(x, y));
                if (glm::length(n) < 0.5f)
                    continue;
                const float expected = bruteForceSheen(glm::normalize(n), v, 0.5f, m.sheenModel());
                errSampled += std::abs(mean3(sampled.color.rgba(x, y)) - expected);
                errIrradiance += std::abs(mean3(irradiance.color.rgba(x, y)) - expected);
                sumExpected += expected;
                ++count;
            }
        errSampled /= sumExpected;
        errIrradiance /= sumExpected;
        qInfo("sheen under a lamp: %d pixels; mean |error| over the mean of the lobe's integral: "
              "sampled %.4f, irradiance about one direction %.4f",
              count, errSampled, errIrradiance);
        QVERIFY(count > 1500);
        QVERIFY2(errSampled < 0.05, qPrintable(QString::number(errSampled)));
        QVERIFY2(errSampled * 2.0 < errIrradiance,
                 qPrintable(QString::number(errSampled) + " " + QString::number(errIrradiance)));
    }

    // Only a frame whose material has a lobe the frames at rest sample compiles the sampling in
    // (LightingFeatures::sampledReflections: a base glossy enough, kSampledReflectionMaxRoughness,
    // or a sheen): a rough plain dielectric's refinement frames draw with its interactive program
    // and compile nothing; a glossy metal's first one builds its sampled program once, and its
    // next ones reuse it; the crimson velvet's sheen is sampled too.
    void onlyASampledLobeCompilesTheSampling() {
        test::OffscreenRenderer r;
        const std::string started = r.start(32);
        QVERIFY2(started.empty(), started.c_str());
        Scene scene = test::shippedDefaultScene();
        const Material velvet = scene.material; // the crimson velvet, roughness 0.8, a sheen
        QVERIFY(velvet.scalar(ParamId::Roughness) > render::kSampledReflectionMaxRoughness);
        QVERIFY(velvet.scalar(ParamId::SheenWeight) > 0.0f);
        scene.material = test::whiteMaterial(0.0f, 0.9f);
        r.renderer->setScene(scene);
        r.renderer->finishEnvironment();
        render::FrameSettings fs;
        fs.width = fs.height = 32;
        std::string error;
        const auto drawCompiles = [&](int samples) {
            fs.reflectionSamples = samples;
            const int before = r.renderer->shaderCompileCount();
            if (!r.renderer->render(fs, r.target->framebuffer(), &error))
                qFatal("render failed: %s", error.c_str());
            return r.renderer->shaderCompileCount() - before;
        };
        drawCompiles(0);
        drawCompiles(0); // the specialised interactive program is built
        QCOMPARE(drawCompiles(0), 0);
        QCOMPARE(drawCompiles(render::kRefinementReflectionSamples), 0);
        scene.material = test::whiteMaterial(1.0f, 0.3f);
        r.renderer->update(scene, ScenePart::Material);
        drawCompiles(0);
        drawCompiles(0);
        QCOMPARE(drawCompiles(0), 0);
        QVERIFY(drawCompiles(render::kRefinementReflectionSamples) > 0);
        QCOMPARE(drawCompiles(render::kRefinementReflectionSamples), 0);
        QCOMPARE(drawCompiles(0), 0);
        scene.material = velvet;
        r.renderer->update(scene, ScenePart::Material);
        drawCompiles(0);
        drawCompiles(0);
        QCOMPARE(drawCompiles(0), 0);
        QVERIFY(drawCompiles(render::kRefinementReflectionSamples) > 0);
        QCOMPARE(drawCompiles(render::kRefinementReflectionSamples), 0);
        r.stop();
    }
};

QTEST_GUILESS_MAIN(TestRenderSampledReflections)
#include "test_render_sampled_reflections.moc"
