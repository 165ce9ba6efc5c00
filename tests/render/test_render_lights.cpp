// Point, spot and area lights and the three many-light paths (render/light_passes.h). What each
// case proves is stated on the case.
//
// Regenerating the debug-view goldens (only after a deliberate change, reviewed by eye):
//   VELVET_UPDATE_GOLDENS=1 ctest --test-dir build -R test_render_lights
// rewrites tests/render/golden/view_<name>_128.png and passes; commit the new PNGs.
#include "core/brdf.h"
#include "core/lights.h"
#include "render/camera.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <cstdlib>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <optional>
#include <set>

using namespace velvet;

namespace {

bool updateGoldens() {
    const char* v = std::getenv("VELVET_UPDATE_GOLDENS");
    return v && std::string(v) == "1";
}

/// One renderer for the whole file (shaders compile once).
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

struct Frame {
    Image linear, display;
};

Frame renderFrame(const Scene& scene, int size, render::DebugView view = render::DebugView::Final,
                  render::LightPath path = render::LightPath::Auto,
                  const std::optional<Material>& splitMaterial = std::nullopt) {
    Rig* r = rig();
    std::string error;
    if (!r->target.resize(size, size, &error))
        qFatal("target: %s", error.c_str());
    render::FrameSettings fs;
    fs.width = fs.height = size;
    fs.view = view;
    fs.lightPath = path;
    fs.splitMaterial = splitMaterial;
    r->renderer.setScene(scene);
    if (!r->renderer.render(fs, r->target.framebuffer(), &error))
        qFatal("render failed: %s", error.c_str());
    return {r->renderer.readLinear(), r->renderer.readDisplay()};
}

/// Orthographic unit sphere, black environment, no lights yet.
Scene analyticScene() {
    Scene scene = test::blackOrthographicScene();
    Material& m = scene.material;
    m.setColor(ParamId::BaseColor, {0.8f, 0.3f, 0.2f});
    m.setScalar(ParamId::Roughness, 0.4f);
    return scene;
}

/// Point lights on a grid in [-1.5, 1.5]^3 with the given radius.
std::vector<Light> lightGrid(int count, float radius) {
    const int side = int(std::ceil(std::cbrt(double(count))));
    std::vector<Light> lights;
    for (int i = 0; i < count; ++i) {
        const int x = i % side, y = (i / side) % side, z = i / (side * side);
        auto c = [&](int k) { return -1.5f + 3.0f * (float(k) + 0.5f) / float(side); };
        Light l;
        l.type = LightType::Point;
        l.position = {c(x), c(y), c(z)};
        l.range = radius;
        l.intensity = 0.1f;
        l.color = {0.3f + 0.7f * float(x) / side, 0.3f + 0.7f * float(y) / side, 1.0f};
        lights.push_back(l);
    }
    return lights;
}

/// DESIGN.md's golden rule: pixels differing by more than 5/255 in any channel; returns the
/// fraction of such pixels.
double differingFraction(const Image& a, const Image& b, float* worst = nullptr) {
    int differing = 0;
    float w = 0.0f;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            float d = 0.0f;
            for (int k = 0; k < 3; ++k)
                d = std::max(d, std::abs(std::round(a.rgba(x, y)[k] * 255.0f) -
                                         std::round(b.rgba(x, y)[k] * 255.0f)));
            w = std::max(w, d);
            differing += d > 5.0f;
        }
    if (worst)
        *worst = w;
    return double(differing) / double(a.width * a.height);
}

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

/// The debug-view golden scene: the shipped default scene (HDRI, key light, crimson velvet) with
/// a material that has every lobe (textured metallic, roughness and occlusion, clearcoat, sheen,
/// emission), 20 point lights of overlapping radii around the sphere (so the lights-per-pixel
/// heat map has several levels), and the A/B split's material B (id 1) on the right half, which
/// differs in every G-buffer and material value a view shows.
struct GoldenScene {
    Scene scene;
    Material b;
};
GoldenScene debugViewGoldenScene() {
    GoldenScene g{test::shippedDefaultScene(), {}};
    Material& a = g.scene.material;
    // Textures written here (both materials use them): metallic and roughness (glTF packing: G
    // roughness, B metallic) and occlusion as gradients across u and v, so those views vary
    // across the sphere and not only between the halves.
    static QTemporaryDir dir;
    const std::string mr = dir.filePath("metal_rough.png").toStdString();
    const std::string ao = dir.filePath("occlusion.png").toStdString();
    Image metalRough(16, 16, 3), occlusion(16, 16, 1);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            metalRough.at(x, y)[1] = 0.3f + 0.7f * float(y) / 15.0f;
            metalRough.at(x, y)[2] = float(x) / 15.0f;
            occlusion.at(x, y)[0] = 0.2f + 0.8f * float(y) / 15.0f;
        }
    std::string error;
    if (!writeImage(mr, metalRough, PixelFormat::UInt8, &error) ||
        !writeImage(ao, occlusion, PixelFormat::UInt8, &error))
        qFatal("writing the golden scene's textures: %s", error.c_str());
    a.setTexture(TextureSlot::MetallicRoughness, TextureRef{mr});
    a.setTexture(TextureSlot::Occlusion, TextureRef{ao});
    a.setColor(ParamId::BaseColor, {0.75f, 0.2f, 0.15f});
    a.setScalar(ParamId::Metallic, 0.5f);
    a.setScalar(ParamId::Roughness, 0.5f);
    a.setScalar(ParamId::ClearcoatWeight, 0.8f);
    a.setScalar(ParamId::ClearcoatRoughness, 0.15f);
    a.setScalar(ParamId::SheenWeight, 1.0f);
    a.setColor(ParamId::SheenColor, {0.9f, 0.6f, 0.9f});
    a.setColor(ParamId::EmissiveColor, {0.2f, 0.5f, 1.0f});
    a.setScalar(ParamId::EmissiveStrength, 0.3f);
    g.b = a;
    g.b.setColor(ParamId::BaseColor, {0.9f, 0.8f, 0.3f});
    g.b.setScalar(ParamId::Metallic, 1.0f);
    g.b.setScalar(ParamId::SpecularWeight, 0.6f);
    g.b.setColor(ParamId::SpecularColor, {1.0f, 0.8f, 0.6f});
    g.b.setScalar(ParamId::Roughness, 0.7f);
    g.b.setScalar(ParamId::ClearcoatWeight, 0.3f);
    g.b.setScalar(ParamId::ClearcoatRoughness, 0.5f);
    g.b.setColor(ParamId::SheenColor, {0.2f, 0.9f, 0.4f});
    g.b.setColor(ParamId::EmissiveColor, {1.0f, 0.4f, 0.1f});
    g.b.setScalar(ParamId::EmissiveStrength, 0.6f);
    for (int i = 0; i < 20; ++i) {
        // A ring of lights around the view axis, alternating in depth and radius.
        const float angle = 2.0f * 3.14159265f * float(i) / 20.0f;
        Light l;
        l.type = LightType::Point;
        l.position = {1.1f * std::cos(angle), 1.1f * std::sin(angle), i % 2 ? 0.9f : 0.3f};
        l.range = i % 3 == 0 ? 1.4f : 0.9f;
        l.intensity = 0.6f;
        l.color = {0.5f + 0.5f * std::cos(angle), 0.7f, 0.5f + 0.5f * std::sin(angle)};
        g.scene.lights.push_back(l);
    }
    return g;
}

/// Fraction of pixels that differ from pixel (0, 0) by more than 5/255 in some channel (a
/// constant image gives 0).
double fractionUnlikeCorner(const Image& im) {
    int unlike = 0;
    const glm::vec4 c = im.rgba(0, 0);
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            const glm::vec4 p = im.rgba(x, y);
            float d = 0.0f;
            for (int k = 0; k < 3; ++k)
                d = std::max(d, std::abs(p[k] - c[k]));
            unlike += d * 255.0f > 5.0f;
        }
    return double(unlike) / double(im.width * im.height);
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

    // Light volumes, tiled and brute force give the same image within the golden tolerance, and
    // exactly the same lights-per-pixel counts, at 256 point, sphere and rectangle lights
    // (perspective camera).
    void pathsGiveSameImage() {
        Scene scene;
        scene.environment.hdri.clear();
        scene.environment.color = glm::vec3(0.05f);
        scene.lights = lightGrid(256, 0.7f);
        // Every fifth light a sphere area light, every seventh a rectangle facing the origin.
        for (size_t i = 0; i < scene.lights.size(); ++i) {
            Light& l = scene.lights[i];
            if (i % 5 == 0) {
                l.type = LightType::Area;
                l.shape = AreaShape::Sphere;
                l.size = glm::vec2(0.15f);
                l.intensity = 2.0f;
            } else if (i % 7 == 0) {
                l.type = LightType::Area;
                l.shape = AreaShape::Rectangle;
                l.direction = glm::normalize(-l.position);
                l.size = {0.4f, 0.25f};
                l.intensity = 2.0f;
            }
        }
        const int size = 128;
        const Frame brute =
            renderFrame(scene, size, render::DebugView::Final, render::LightPath::Brute);
        const Frame volumes =
            renderFrame(scene, size, render::DebugView::Final, render::LightPath::Volumes);
        const Frame tiled =
            renderFrame(scene, size, render::DebugView::Final, render::LightPath::Tiled);
        float worstV = 0.0f, worstT = 0.0f;
        const double fv = differingFraction(brute.display, volumes.display, &worstV);
        const double ft = differingFraction(brute.display, tiled.display, &worstT);
        qInfo("volumes vs brute: %.3f %% differ (worst %.0f/255); tiled vs brute: %.3f %% (worst "
              "%.0f/255)",
              100.0 * fv, worstV, 100.0 * ft, worstT);
        QVERIFY(fv <= 0.001);
        QVERIFY(ft <= 0.001);
        // The lights reach the sphere (the comparison is not of two black images).
        const Frame none = [&] {
            Scene s = scene;
            s.lights.clear();
            return renderFrame(s, size);
        }();
        QVERIFY(differingFraction(none.display, brute.display) > 0.1);

        const auto view = render::DebugView::LightsPerPixel;
        const Frame cb = renderFrame(scene, size, view, render::LightPath::Brute);
        const Frame cv = renderFrame(scene, size, view, render::LightPath::Volumes);
        const Frame ct = renderFrame(scene, size, view, render::LightPath::Tiled);
        double sum = 0.0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const float b = cb.linear.rgba(x, y).x;
                QCOMPARE(cv.linear.rgba(x, y).x, b);
                QCOMPARE(ct.linear.rgba(x, y).x, b);
                sum += b;
            }
        qInfo("lights per pixel: %.2f on average over the image", sum / (size * size));
        QVERIFY(sum > 0.0);
    }

    // Spot lights: the volumes path draws them with a cone proxy (narrow cones) or the sphere
    // (wide ones); it still gives the tiled path's image and exactly its lights-per-pixel counts
    // (a spot reaches only pixels inside its outer cone).
    void spotConeProxyMatchesTiled() {
        Scene scene;
        scene.environment.hdri.clear();
        scene.environment.color = glm::vec3(0.05f);
        scene.lights = lightGrid(64, 1.6f);
        for (size_t i = 0; i < scene.lights.size(); ++i) {
            Light& l = scene.lights[i];
            l.type = LightType::Spot;
            l.direction = glm::normalize(-l.position + glm::vec3(0.2f * float(i % 3) - 0.2f));
            l.outerConeDeg = i % 4 == 3 ? 75.0f : 12.0f + 3.0f * float(i % 10); // 75: sphere proxy
            l.innerConeDeg = 0.6f * l.outerConeDeg;
            l.intensity = 0.6f;
        }
        const int size = 128;
        const Frame tiled =
            renderFrame(scene, size, render::DebugView::Final, render::LightPath::Tiled);
        const Frame volumes =
            renderFrame(scene, size, render::DebugView::Final, render::LightPath::Volumes);
        float worst = 0.0f;
        const double f = differingFraction(tiled.display, volumes.display, &worst);
        qInfo("spots, volumes (cone proxies) vs tiled: %.3f %% differ (worst %.0f/255)", 100.0 * f,
              worst);
        QVERIFY(f <= 0.001);
        const Frame none = [&] {
            Scene s = scene;
            s.lights.clear();
            return renderFrame(s, size);
        }();
        QVERIFY(differingFraction(none.display, tiled.display) > 0.05);
        const auto view = render::DebugView::LightsPerPixel;
        const Frame ct = renderFrame(scene, size, view, render::LightPath::Tiled);
        const Frame cv = renderFrame(scene, size, view, render::LightPath::Volumes);
        const Frame cb = renderFrame(scene, size, view, render::LightPath::Brute);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                QCOMPARE(cv.linear.rgba(x, y).x, ct.linear.rgba(x, y).x);
                QCOMPARE(cb.linear.rgba(x, y).x, ct.linear.rgba(x, y).x);
            }
    }

    // The heat map counts exactly the lights whose radius contains the pixel's position: 0
    // outside every radius (pixels within 1 mm of a sphere's edge are left out).
    void heatMapCountsLightsReachingThePixel() {
        Scene scene;
        scene.environment.hdri.clear();
        Light a;
        a.type = LightType::Point;
        a.position = {0.5f, 0.5f, 0.8f};
        a.range = 0.6f;
        Light b = a;
        b.position = {-0.4f, -0.2f, 0.9f};
        b.range = 0.5f;
        Light c = a;
        c.position = {0.0f, 0.1f, 1.0f};
        c.range = 0.4f;
        scene.lights = {a, b, c};
        const int size = 96;
        const Frame pos = renderFrame(scene, size, render::DebugView::Position);
        const Frame depth = renderFrame(scene, size, render::DebugView::Depth);
        for (auto path :
             {render::LightPath::Brute, render::LightPath::Volumes, render::LightPath::Tiled}) {
            const Frame heat = renderFrame(scene, size, render::DebugView::LightsPerPixel, path);
            int zeros = 0, counted = 0;
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x) {
                    const float got = heat.linear.rgba(x, y).x;
                    if (depth.linear.rgba(x, y).x <= 0.0f) {
                        QCOMPARE(got, 0.0f); // background
                        continue;
                    }
                    const glm::vec3 p = glm::vec3(pos.linear.rgba(x, y));
                    int expected = 0;
                    bool edge = false;
                    for (const Light& l : scene.lights) {
                        const float d = glm::length(p - l.position);
                        expected += d < l.range;
                        edge = edge || std::abs(d - l.range) < 1e-3f;
                    }
                    if (edge)
                        continue;
                    QCOMPARE(int(got), expected);
                    zeros += expected == 0;
                    counted += expected > 0;
                }
            QVERIFY(zeros > 100);
            QVERIFY(counted > 100);
        }
    }

    // 4,096 point lights: every light is honoured. On every path, each pixel's lights-per-pixel
    // count equals the CPU count of the lights whose radius contains the pixel's position (pixels
    // within 1 mm of some light's sphere are left out), so no light is dropped by a buffer, tile
    // list or instance limit; and the volumes and tiled images equal brute force's within the
    // golden tolerance, all finite and brighter than the unlit image.
    void manyLightsAllHonoured() {
        Scene scene;
        scene.environment.hdri.clear();
        scene.environment.color = glm::vec3(0.05f);
        scene.lights = lightGrid(4096, 0.3f);
        const int size = 64;
        const Frame pos = renderFrame(scene, size, render::DebugView::Position);
        const Frame depth = renderFrame(scene, size, render::DebugView::Depth);
        std::vector<int> expected(size * size, -1); // -1: background or edge pixel
        long long sum = 0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                if (depth.linear.rgba(x, y).x <= 0.0f)
                    continue;
                const glm::vec3 p = glm::vec3(pos.linear.rgba(x, y));
                int count = 0;
                bool edge = false;
                for (const Light& l : scene.lights) {
                    const float d = glm::length(p - l.position);
                    count += d < l.range;
                    edge = edge || std::abs(d - l.range) < 1e-3f;
                }
                if (!edge) {
                    expected[y * size + x] = count;
                    sum += count;
                }
            }
        int compared = 0, maxCount = 0;
        for (int i = 0; i < size * size; ++i)
            if (expected[i] >= 0) {
                ++compared;
                maxCount = std::max(maxCount, expected[i]);
            }
        std::set<int> reaching; // lights that reach at least one compared pixel
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                if (expected[y * size + x] > 0)
                    for (size_t i = 0; i < scene.lights.size(); ++i)
                        if (glm::length(glm::vec3(pos.linear.rgba(x, y)) -
                                        scene.lights[i].position) < scene.lights[i].range)
                            reaching.insert(int(i));
        qInfo("4,096 lights: %d pixels compared, %.2f lights per pixel on average (max %d), %d "
              "distinct lights reach them",
              compared, double(sum) / std::max(compared, 1), maxCount, int(reaching.size()));
        QVERIFY(compared > 1000);
        QVERIFY(reaching.size() > 300);
        for (auto path :
             {render::LightPath::Brute, render::LightPath::Volumes, render::LightPath::Tiled}) {
            const Frame heat = renderFrame(scene, size, render::DebugView::LightsPerPixel, path);
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x)
                    if (expected[y * size + x] >= 0 &&
                        int(heat.linear.rgba(x, y).x) != expected[y * size + x])
                        QFAIL(qPrintable(QString("path %1, pixel (%2,%3): %4 lights, CPU %5")
                                             .arg(int(path))
                                             .arg(x)
                                             .arg(y)
                                             .arg(heat.linear.rgba(x, y).x)
                                             .arg(expected[y * size + x])));
        }
        Scene dark = scene;
        dark.lights.clear();
        const Frame base = renderFrame(dark, size);
        const Frame brute =
            renderFrame(scene, size, render::DebugView::Final, render::LightPath::Brute);
        for (auto path :
             {render::LightPath::Auto, render::LightPath::Tiled, render::LightPath::Volumes}) {
            const Frame f = renderFrame(scene, size, render::DebugView::Final, path);
            double added = 0.0;
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x) {
                    const glm::vec4 c = f.linear.rgba(x, y);
                    QVERIFY(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
                    added += c.x - base.linear.rgba(x, y).x;
                }
            float worst = 0.0f;
            const double fraction = differingFraction(brute.display, f.display, &worst);
            qInfo("4,096 lights, path %d vs brute: %.3f %% differ (worst %.0f/255)", int(path),
                  100.0 * fraction, worst);
            QVERIFY(fraction <= 0.001);
            QVERIFY(added > 1.0);
        }
    }

    // Directional lights past render::kMaxDirectionalLights are not drawn, and setScene() says
    // so: one warning per dropped light naming its JSON path (the index in the scene's lights,
    // counting the other light types before it); the first 16 are drawn as before.
    void directionalLightsPastTheLimitAreReported() {
        Scene scene = analyticScene();
        Light ambient;
        ambient.type = LightType::Ambient;
        ambient.intensity = 0.05f;
        scene.lights = {ambient};
        for (int i = 0; i < render::kMaxDirectionalLights; ++i) {
            Light l;
            l.type = LightType::Directional;
            l.direction = glm::normalize(glm::vec3(0.1f * float(i - 8), -0.3f, -1.0f));
            l.intensity = 0.1f;
            scene.lights.push_back(l);
        }
        Problems problems;
        rig()->renderer.setScene(scene, &problems);
        QVERIFY(problems.items.empty());
        // Both frames with the environment fully baked: a bake in progress (its slices are
        // timed, so a loaded machine runs fewer a frame) would change the image between them.
        rig()->renderer.finishEnvironment();
        const Frame drawn = renderFrame(scene, 48);
        Scene over = scene;
        Light bright;
        bright.type = LightType::Directional;
        bright.direction = {0.0f, 0.0f, -1.0f};
        bright.intensity = 50.0f;
        over.lights.push_back(bright);
        over.lights.push_back(bright);
        rig()->renderer.setScene(over, &problems);
        QCOMPARE(problems.items.size(), size_t(2));
        for (size_t k = 0; k < 2; ++k) {
            const Problem& p = problems.items[k];
            qInfo("%s", p.toString().c_str());
            QVERIFY(p.severity == Problem::Severity::Warning);
            QCOMPARE(p.path, "lights[" + std::to_string(17 + k) + "]");
            QVERIFY2(p.message.find("16") != std::string::npos, p.message.c_str());
        }
        QVERIFY(!problems.hasErrors());
        // The dropped lights really are not drawn (they would be 500x brighter than the rest).
        const Frame f = renderFrame(over, 48);
        QCOMPARE(differingFraction(drawn.display, f.display), 0.0);
    }

    // A golden image of every debug view of debugViewGoldenScene() (DESIGN.md's tolerance). Each
    // view must show structure (no constant image, so a view that goes blank fails even when its
    // golden is regenerated), and the material-id view both ids of the A/B split.
    void debugViewGoldens_data() {
        QTest::addColumn<int>("view");
        const char* names[] = {"final",         "albedo",           "normal",
                               "depth",         "roughness",        "metallic",
                               "position",      "specular",         "clearcoat",
                               "sheen",         "occlusion",        "emissive",
                               "material_id",   "lights_per_pixel", "diffuse_only",
                               "specular_only", "base_specular",    "sheen_only",
                               "clearcoat_only"};
        for (int i = 0; i <= int(render::DebugView::ClearcoatOnly); ++i)
            QTest::newRow(names[i]) << i;
    }
    void debugViewGoldens() {
        QFETCH(int, view);
        const QString path = QString(VELVET_SOURCE_DIR "/tests/render/golden/view_%1_128.png")
                                 .arg(QTest::currentDataTag());
        const GoldenScene g = debugViewGoldenScene();
        // The whole environment bake first: the views must not depend on how many slices the
        // frames before happened to run (the final view shows the prefiltered environment).
        rig()->renderer.setScene(g.scene);
        rig()->renderer.finishEnvironment();
        const Frame f =
            renderFrame(g.scene, 128, render::DebugView(view), render::LightPath::Auto, g.b);
        const double unlike = fractionUnlikeCorner(f.display);
        qInfo("%s: %.1f %% of pixels unlike the corner", QTest::currentDataTag(), 100.0 * unlike);
        QVERIFY2(unlike >= 0.02, "the view is (nearly) one colour");
        if (render::DebugView(view) == render::DebugView::MaterialId) {
            QCOMPARE(f.linear.rgba(40, 64).x, 0.0f); // left half of the sphere: A
            QCOMPARE(f.linear.rgba(88, 64).x, 1.0f); // right half: B
        }
        if (render::DebugView(view) == render::DebugView::Metallic ||
            render::DebugView(view) == render::DebugView::Roughness ||
            render::DebugView(view) == render::DebugView::Occlusion) {
            std::set<float> values; // the textures' gradients, not one value per half
            for (int y = 0; y < 128; ++y)
                for (int x = 0; x < 64; ++x)
                    values.insert(f.linear.rgba(x, y).x);
            QVERIFY2(values.size() >= 10, qPrintable(QString("%1 values").arg(values.size())));
        }
        if (render::DebugView(view) == render::DebugView::LightsPerPixel) {
            std::set<float> counts; // a heat map, not a mask: several overlap levels
            for (int y = 0; y < 128; ++y)
                for (int x = 0; x < 128; ++x)
                    counts.insert(f.linear.rgba(x, y).x);
            qInfo("lights per pixel: %d distinct counts, up to %.0f", int(counts.size()),
                  *counts.rbegin());
            QVERIFY(counts.size() >= 4);
        }
        std::string error;
        if (updateGoldens()) {
            QVERIFY2(writeImage(path.toStdString(), f.display, PixelFormat::UInt8, &error),
                     error.c_str());
            qWarning("VELVET_UPDATE_GOLDENS=1: rewrote %s", qPrintable(path));
            return;
        }
        Image golden;
        QVERIFY2(readImage(path.toStdString(), golden, &error), error.c_str());
        QCOMPARE(golden.width, f.display.width);
        float worst = 0.0f;
        const double fraction = differingFraction(golden, f.display, &worst);
        if (fraction > 0.001) {
            const QString actual =
                QDir::tempPath() + "/view_" + QTest::currentDataTag() + "_128_actual.png";
            writeImage(actual.toStdString(), f.display, PixelFormat::UInt8, nullptr);
            QFAIL(qPrintable(QString("%1 % of pixels differ (worst %2/255); this run: %3")
                                 .arg(100.0 * fraction)
                                 .arg(worst)
                                 .arg(actual)));
        }
    }
};

QTEST_GUILESS_MAIN(TestRenderLights)
#include "test_render_lights.moc"
