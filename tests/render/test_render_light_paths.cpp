// The three many-light paths give the same image (render/light_passes.h), the spot's cone proxy,
// the lights-per-pixel heat map, every light honoured at scale, the directional lights' limit
// reported, and the debug views' goldens. What each case proves is stated on the case.
//
// Regenerating the debug-view goldens (only after a deliberate change, reviewed by eye):
//   VELVET_UPDATE_GOLDENS=1 ctest --test-dir build -R test_render_light_paths
// rewrites tests/render/golden/view_<name>_128.png and passes; commit the new PNGs.
#include "light_test_rig.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <cstdlib>
#include <glm/geometric.hpp>
#include <set>

using namespace velvet;
using namespace velvet::test;

namespace {

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

class TestRenderLightPaths : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        rig();
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

QTEST_GUILESS_MAIN(TestRenderLightPaths)
#include "test_render_light_paths.moc"
