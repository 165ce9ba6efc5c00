// Point, spot, area and ambient lights against their C++ twins (render/light_passes.h; the
// many-light paths, the heat map and the debug-view goldens are test_render_light_paths'). What
// each case proves is stated on the case.
#include "core/brdf.h"
#include "core/lights.h"
#include "light_test_rig.h"
#include "render/camera.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QtTest>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

using namespace velvet;
using namespace velvet::test;

namespace {

/// What the C++ twins expect of one pixel: its radiance, and whether the light reaches it with
/// non-zero illuminance (else the GPU must give exactly 0).
struct Expected {
    glm::vec3 radiance{0.0f};
    bool lit = false;
};

/// Compares the GPU pixels of @p scene (brute-force path) on a 5-pixel grid against
/// @p expected(position, unit normal, unit view vector, surface with the pixel's albedo):
/// within 2 % (or 1/255) per channel; exactly 0 where the twin says unlit. Counts the lit pixels
/// whose normal faces @p towards (n.l > 0.1 for the direction @p towards(p)) and the unlit ones.
template <typename ExpectedFn, typename TowardsFn>
void compareWithCpu(const Scene& scene, ExpectedFn expected, TowardsFn towards, int& checked,
                    int& zeroChecked) {
    const int size = 96;
    const Frame f = renderFrame(scene, size, render::DebugView::Final, render::LightPath::Brute);
    const Frame pos = renderFrame(scene, size, render::DebugView::Position);
    const Frame normal = renderFrame(scene, size, render::DebugView::Normal);
    const Frame albedo = renderFrame(scene, size, render::DebugView::Albedo);
    const glm::vec3 v = glm::normalize(render::cameraEye(scene.camera) - scene.camera.target);
    for (int y = 2; y < size; y += 5)
        for (int x = 2; x < size; x += 5) {
            glm::vec3 n = glm::vec3(normal.linear.rgba(x, y));
            if (glm::length(n) < 0.5f)
                continue;
            n = glm::normalize(n);
            const glm::vec3 p = glm::vec3(pos.linear.rgba(x, y));
            brdf::Surface s = brdf::surfaceFromMaterial(scene.material);
            s.baseColor = glm::vec3(albedo.linear.rgba(x, y));
            const Expected e = expected(p, n, v, s);
            const glm::vec3 got = glm::vec3(f.linear.rgba(x, y));
            for (int k = 0; k < 3; ++k) {
                const double err = std::abs(double(got[k]) - e.radiance[k]);
                const double tol = std::max(0.02 * e.radiance[k], 1.0 / 255.0);
                if (err > tol)
                    QFAIL(qPrintable(QString("pixel (%1,%2) channel %3: GPU %4, CPU %5")
                                         .arg(x)
                                         .arg(y)
                                         .arg(k)
                                         .arg(got[k])
                                         .arg(e.radiance[k])));
            }
            if (!e.lit) {
                if (std::max({got.x, got.y, got.z}) != 0.0f)
                    QFAIL(qPrintable(
                        QString("pixel (%1,%2) outside the light is %3").arg(x).arg(y).arg(got.x)));
                ++zeroChecked;
            } else if (glm::dot(n, towards(p)) > 0.1f) {
                ++checked;
            }
        }
}

/// compareWithCpu() for a punctual light: @p factor gives the illuminance factor (lux per unit
/// colour x intensity) at a world position, unit direction to the light and distance.
template <typename Factor>
void compareWithTwin(const Scene& scene, const Light& light, Factor factor, int& checked,
                     int& zeroChecked) {
    auto toLight = [&](glm::vec3 p) { return glm::normalize(light.position - p); };
    compareWithCpu(
        scene,
        [&](glm::vec3 p, glm::vec3 n, glm::vec3 v, const brdf::Surface& s) {
            const float e = factor(p, toLight(p), glm::length(light.position - p));
            return Expected{brdf::evalDirectional(s, n, v, toLight(p)) * light.color *
                                light.intensity * e,
                            e != 0.0f};
        },
        toLight, checked, zeroChecked);
}

/// The C++ twin of an area light's contribution (shadeLocalLight() in light_common.glsl): the
/// diffuse and sheen lobes towards the centre, the specular lobes towards Karis 2013's
/// representative point with the widened-lobe normalization.
Expected areaLightTwin(const Light& light, glm::vec3 p, glm::vec3 n, glm::vec3 v,
                       const brdf::Surface& s) {
    const glm::vec3 toLight = light.position - p;
    const float dist = glm::length(toLight);
    const glm::vec3 l = toLight / dist;
    const glm::vec3 r = glm::reflect(-v, n);
    if (dist >= light.range)
        return {};
    float illuminance = 0.0f, widen = 0.0f;
    glm::vec3 lSpecular;
    if (light.shape == AreaShape::Sphere) {
        const float radius = light.size.x;
        const float d = std::max(dist, std::max(radius, lights::kMinLightDistance));
        illuminance = lights::sphereIlluminancePerNit(dist, radius, light.range);
        lSpecular = glm::normalize(lights::sphereRepresentativePoint(toLight, r, radius));
        widen = radius / (2.0f * d);
    } else {
        const glm::vec3 normal = glm::normalize(light.direction);
        glm::vec3 ax, ay;
        lights::rectangleAxes(normal, ax, ay);
        const float hx = 0.5f * light.size.x, hy = 0.5f * light.size.y;
        illuminance =
            lights::rectangleIlluminancePerNit(dist, glm::dot(normal, -l), hx, hy, light.range);
        lSpecular =
            glm::normalize(lights::rectangleRepresentativePoint(toLight, ax, ay, hx, hy, r));
        widen = std::sqrt(4.0f * hx * hy / 3.14159265f) /
                (2.0f * std::max(dist, lights::kMinLightDistance));
    }
    if (illuminance <= 0.0f)
        return {};
    return {brdf::evalLobes(s, n, v, l, lSpecular, widen).sum() * light.color * light.intensity *
                illuminance,
            true};
}

} // namespace

class TestRenderLights : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        rig();
    }

    // C++ twins of the light functions: the window is 1 at the light and 0 from the range on;
    // the cone is 0 outside the outer cone and 1 inside the inner one.
    void twinsKnownValues() {
        QCOMPARE(lights::windowFalloff(0.0f, 2.0f), 1.0f);
        QCOMPARE(lights::windowFalloff(2.0f, 2.0f), 0.0f);
        QCOMPARE(lights::windowFalloff(3.0f, 2.0f), 0.0f);
        QVERIFY(std::abs(lights::distanceAttenuation(0.5f, 100.0f) - 4.0f) < 1e-3f);
        const float co = std::cos(glm::radians(30.0f)), ci = std::cos(glm::radians(20.0f));
        QCOMPARE(lights::spotConeAttenuation(std::cos(glm::radians(31.0f)), co, ci), 0.0f);
        QCOMPARE(lights::spotConeAttenuation(std::cos(glm::radians(19.0f)), co, ci), 1.0f);
        // A representative point on a sphere hit by the ray is on the ray.
        const glm::vec3 rp = lights::sphereRepresentativePoint({0, 0, 5}, {0, 0, 1}, 1.0f);
        QVERIFY(glm::length(rp - glm::vec3(0, 0, 5)) < 1e-5f);
        QCOMPARE(lights::areaSpecularNormalization(0.5f, 0.0f), 1.0f);
        // The split lobes sum to the one-direction BRDF for one direction and no widening.
        brdf::Surface s;
        s.metallic = 0.3f;
        s.clearcoat = 0.6f;
        s.sheenColor = glm::vec3(0.5f);
        const glm::vec3 n(0, 0, 1), v = glm::normalize(glm::vec3(0.2f, 0.1f, 1.0f)),
                                    l = glm::normalize(glm::vec3(-0.5f, 0.3f, 0.8f));
        const glm::vec3 sum = brdf::evalLobes(s, n, v, l, l, 0.0f).sum();
        const glm::vec3 one = brdf::evalDirectional(s, n, v, l);
        QVERIFY(glm::length(sum - one) < 1e-5f * glm::length(one));
        // The rectangle frame is right-handed around the light's direction, x horizontal.
        glm::vec3 ax, ay;
        lights::rectangleAxes({0, 0, -1}, ax, ay);
        QVERIFY(std::abs(ax.y) < 1e-6f && std::abs(glm::dot(ax, ay)) < 1e-6f);
        QVERIFY(glm::length(glm::cross(ax, ay) - glm::vec3(0, 0, -1)) < 1e-5f);
        // 1 m^2 facing the point 2 m away: 1/4 lux per nit; 0 behind it.
        QVERIFY(std::abs(lights::rectangleIlluminancePerNit(2.0f, 1.0f, 0.5f, 0.5f, 1e6f) - 0.25f) <
                1e-5f);
        QCOMPARE(lights::rectangleIlluminancePerNit(2.0f, -0.5f, 0.5f, 0.5f, 1e6f), 0.0f);
    }

    // Analytic point light on the orthographic sphere: every lit pixel within 2 % (or 1/255) of
    // the C++ BRDF times the inverse-square law with the Karis window, in candela.
    void pointLightMatchesCpuTwin() {
        Scene scene = analyticScene();
        Light light;
        light.type = LightType::Point;
        light.position = {0.9f, 0.8f, 1.7f};
        light.range = 2.4f; // reaches part of the sphere only, so the window is exercised
        light.intensity = 4.0f;
        light.color = {1.0f, 0.9f, 0.8f};
        scene.lights = {light};
        int checked = 0, zeros = 0;
        compareWithTwin(
            scene, light,
            [&](glm::vec3, glm::vec3, float d) {
                return lights::distanceAttenuation(d, light.range);
            },
            checked, zeros);
        qInfo("point light: %d lit pixels and %d unreached pixels match the twin", checked, zeros);
        QVERIFY(checked >= 40);
        QVERIFY(zeros >= 10);
    }

    // Spot cone: exactly zero outside the outer cone, the full point-light value inside the inner
    // cone, the smoothstep twin in between.
    void spotConeZeroOutsideFullInside() {
        Scene scene = analyticScene();
        Light light;
        light.type = LightType::Spot;
        light.position = {0.0f, 0.0f, 3.0f};
        light.direction = {0.0f, 0.0f, -1.0f};
        light.innerConeDeg = 8.0f;
        light.outerConeDeg = 14.0f;
        light.range = 10.0f;
        light.intensity = 20.0f;
        scene.lights = {light};
        int checked = 0, zeros = 0;
        const float co = std::cos(glm::radians(14.0f)), ci = std::cos(glm::radians(8.0f));
        compareWithTwin(
            scene, light,
            [&](glm::vec3, glm::vec3 l, float d) {
                return lights::distanceAttenuation(d, light.range) *
                       lights::spotConeAttenuation(glm::dot(light.direction, -l), co, ci);
            },
            checked, zeros);
        qInfo("spot: %d lit pixels, %d pixels outside the outer cone", checked, zeros);
        QVERIFY(checked >= 10);
        QVERIFY(zeros >= 100);
    }

    // A small sphere area light (representative point) of luminance L and radius r lights a
    // rough surface like a point light of L pi r^2 candela.
    void smallSphereLightIsPointLight() {
        Scene scene = analyticScene();
        scene.material.setScalar(ParamId::Roughness, 0.9f);
        Light point;
        point.type = LightType::Point;
        point.position = {0.6f, 0.7f, 2.0f};
        point.range = 20.0f;
        Light area = point;
        area.type = LightType::Area;
        area.shape = AreaShape::Sphere;
        area.size = glm::vec2(0.02f);
        area.intensity = 5000.0f;
        point.intensity = area.intensity * 3.14159265f * 0.02f * 0.02f;
        scene.lights = {point};
        const Frame a = renderFrame(scene, 64);
        scene.lights = {area};
        const Frame b = renderFrame(scene, 64);
        float worst = 0.0f;
        const double fraction = differingFraction(a.display, b.display, &worst);
        qInfo("small sphere light vs point light: %.3f %% pixels differ, worst %.0f/255",
              100.0 * fraction, worst);
        QVERIFY(fraction <= 0.001);
    }

    // A rectangle area light (one-sided, representative point): every pixel within 2 % of the
    // C++ twin (lights::rectangleIlluminancePerNit, rectangleRepresentativePoint and
    // brdf::evalLobes); exactly 0 beyond its range. The representative point is far from the
    // centre on many pixels (the specular lobes see a different direction than the diffuse one).
    void rectangleLightMatchesCpuTwin() {
        Scene scene = analyticScene();
        scene.material.setScalar(ParamId::Roughness, 0.3f);
        Light light;
        light.type = LightType::Area;
        light.shape = AreaShape::Rectangle;
        light.position = {0.6f, 0.9f, 1.6f};
        light.direction = glm::normalize(glm::vec3(-0.3f, -0.5f, -1.0f));
        light.size = {1.2f, 0.5f};
        light.range = 2.2f;
        light.intensity = 6.0f;
        light.color = {0.9f, 1.0f, 0.8f};
        scene.lights = {light};
        int checked = 0, zeros = 0, offCentre = 0;
        compareWithCpu(
            scene,
            [&](glm::vec3 p, glm::vec3 n, glm::vec3 v, const brdf::Surface& s) {
                glm::vec3 ax, ay;
                lights::rectangleAxes(light.direction, ax, ay);
                const glm::vec3 rp = lights::rectangleRepresentativePoint(
                    light.position - p, ax, ay, 0.5f * light.size.x, 0.5f * light.size.y,
                    glm::reflect(-v, n));
                offCentre += glm::length(rp - (light.position - p)) > 0.2f;
                return areaLightTwin(light, p, n, v, s);
            },
            [&](glm::vec3 p) { return glm::normalize(light.position - p); }, checked, zeros);
        qInfo("rectangle light: %d lit pixels, %d unreached, %d with the representative point "
              "> 20 cm from the centre match the twin",
              checked, zeros, offCentre);
        QVERIFY(checked >= 40);
        QVERIFY(zeros >= 10);
        QVERIFY(offCentre >= 20);
    }

    // A wide sphere light (radius 0.6 m, 1.3-1.9 m away: far from a point light) matches its twin
    // (sphereIlluminancePerNit, sphereRepresentativePoint, evalLobes with the widened lobe).
    void wideSphereLightMatchesCpuTwin() {
        Scene scene = analyticScene();
        scene.material.setScalar(ParamId::Roughness, 0.25f);
        scene.material.setScalar(ParamId::ClearcoatWeight, 0.5f);
        Light light;
        light.type = LightType::Area;
        light.shape = AreaShape::Sphere;
        light.position = {-0.9f, 0.7f, 1.5f};
        light.size = glm::vec2(0.6f);
        light.range = 2.2f;
        light.intensity = 3.0f;
        light.color = {1.0f, 0.85f, 0.7f};
        scene.lights = {light};
        int checked = 0, zeros = 0;
        compareWithCpu(
            scene,
            [&](glm::vec3 p, glm::vec3 n, glm::vec3 v, const brdf::Surface& s) {
                return areaLightTwin(light, p, n, v, s);
            },
            [&](glm::vec3 p) { return glm::normalize(light.position - p); }, checked, zeros);
        qInfo("wide sphere light: %d lit pixels and %d unreached pixels match the twin", checked,
              zeros);
        QVERIFY(checked >= 40);
        QVERIFY(zeros >= 10);
    }

    // Ambient light: a uniform radiance L = colour x intensity from every direction, added to the
    // environment's. With a black environment and no specular lobe (specular weight 0, metallic
    // 0) a Lambertian surface reflects exactly albedo x L (the irradiance is pi L). With the
    // dielectric specular on, the image only gets brighter (the split sum adds its albedo x L).
    void ambientLightIsAlbedoTimesRadiance() {
        Scene scene = analyticScene();
        scene.material.setScalar(ParamId::SpecularWeight, 0.0f);
        Light ambient;
        ambient.type = LightType::Ambient;
        ambient.color = {0.5f, 0.7f, 1.0f};
        ambient.intensity = 0.8f;
        scene.lights = {ambient};
        const int size = 64;
        const Frame f = renderFrame(scene, size);
        const Frame albedo = renderFrame(scene, size, render::DebugView::Albedo);
        const Frame normal = renderFrame(scene, size, render::DebugView::Normal);
        Scene withSpecular = scene;
        withSpecular.material.setScalar(ParamId::SpecularWeight, 1.0f);
        const Frame g = renderFrame(withSpecular, size);
        const glm::vec3 L = ambient.color * ambient.intensity;
        int checked = 0;
        double worst = 0.0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                if (glm::length(glm::vec3(normal.linear.rgba(x, y))) < 0.5f)
                    continue;
                const glm::vec3 expected = glm::vec3(albedo.linear.rgba(x, y)) * L;
                const glm::vec3 got = glm::vec3(f.linear.rgba(x, y));
                for (int k = 0; k < 3; ++k) {
                    const double rel = std::abs(got[k] - expected[k]) / expected[k];
                    worst = std::max(worst, rel);
                    QVERIFY2(rel < 0.01, qPrintable(QString("pixel (%1,%2): GPU %3, CPU %4")
                                                        .arg(x)
                                                        .arg(y)
                                                        .arg(got[k])
                                                        .arg(expected[k])));
                    QVERIFY(g.linear.rgba(x, y)[k] >= got[k]);
                }
                ++checked;
            }
        qInfo("ambient: %d sphere pixels = albedo x L, worst relative error %.2e", checked, worst);
        QVERIFY(checked > 1000);
    }
};

QTEST_GUILESS_MAIN(TestRenderLights)
#include "test_render_lights.moc"
