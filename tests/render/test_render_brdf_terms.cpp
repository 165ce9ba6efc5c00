// Every selectable BRDF term on the GPU against its C++ twin (core/brdf.h): the analytic sphere
// (orthographic camera, unit sphere, one directional light, no environment), one term changed at a
// time from the default, on nine materials (dielectric and metal, rough and smooth, clearcoat,
// sheen, coloured specular). Every lit pixel must be within 2 % (or 1/255 absolute where dark) of
// the C++ evaluation with that pixel's G-buffer values, and switching terms must compile no shader
// (the choices are a uniform branch on the material table).
#include "core/brdf.h"
#include "render/camera.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QtTest>
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <string>
#include <vector>

using namespace velvet;

namespace {

constexpr int kSize = 96;

struct NamedMaterial {
    const char* name;
    Material material;
};

std::vector<NamedMaterial> materials() {
    std::vector<NamedMaterial> out;
    auto add = [&](const char* name, auto setup) {
        Material m;
        m.setColor(ParamId::BaseColor, {0.8f, 0.3f, 0.2f});
        m.setScalar(ParamId::SheenWeight, 0.0f);
        m.setScalar(ParamId::ClearcoatWeight, 0.0f);
        setup(m);
        out.push_back({name, m});
    };
    add("dielectric rough", [](Material& m) { m.setScalar(ParamId::Roughness, 0.65f); });
    add("dielectric smooth", [](Material& m) { m.setScalar(ParamId::Roughness, 0.3f); });
    add("metal rough", [](Material& m) {
        m.setColor(ParamId::BaseColor, {1.0f, 0.78f, 0.34f});
        m.setScalar(ParamId::Metallic, 1.0f);
        m.setScalar(ParamId::Roughness, 0.55f);
    });
    add("metal smooth", [](Material& m) {
        m.setColor(ParamId::BaseColor, {0.95f, 0.64f, 0.54f});
        m.setScalar(ParamId::Metallic, 1.0f);
        m.setScalar(ParamId::Roughness, 0.3f);
    });
    add("half metal", [](Material& m) {
        m.setColor(ParamId::BaseColor, {0.5f, 0.6f, 0.7f});
        m.setScalar(ParamId::Metallic, 0.5f);
        m.setScalar(ParamId::Roughness, 0.45f);
    });
    add("clearcoat", [](Material& m) {
        m.setColor(ParamId::BaseColor, {0.1f, 0.2f, 0.6f});
        m.setScalar(ParamId::Roughness, 0.5f);
        m.setScalar(ParamId::ClearcoatWeight, 1.0f);
        m.setScalar(ParamId::ClearcoatRoughness, 0.2f);
    });
    add("coloured specular, IOR 1.8", [](Material& m) {
        m.setColor(ParamId::BaseColor, {0.2f, 0.5f, 0.2f});
        m.setScalar(ParamId::Roughness, 0.4f);
        m.setScalar(ParamId::Ior, 1.8f);
        m.setScalar(ParamId::SpecularWeight, 0.8f);
        m.setColor(ParamId::SpecularColor, {1.0f, 0.8f, 0.6f});
    });
    add("sheen velvet", [](Material& m) {
        m.setColor(ParamId::BaseColor, {0.35f, 0.02f, 0.05f});
        m.setScalar(ParamId::Roughness, 0.8f);
        m.setScalar(ParamId::SheenWeight, 1.0f);
        m.setColor(ParamId::SheenColor, {1.0f, 0.6f, 0.7f});
        m.setScalar(ParamId::SheenRoughness, 0.4f);
    });
    add("sheen + clearcoat", [](Material& m) {
        m.setColor(ParamId::BaseColor, {0.4f, 0.4f, 0.45f});
        m.setScalar(ParamId::Roughness, 0.7f);
        m.setScalar(ParamId::SheenWeight, 0.8f);
        m.setColor(ParamId::SheenColor, {0.6f, 0.7f, 1.0f});
        m.setScalar(ParamId::SheenRoughness, 0.7f);
        m.setScalar(ParamId::ClearcoatWeight, 0.5f);
        m.setScalar(ParamId::ClearcoatRoughness, 0.3f);
    });
    return out;
}

/// One term changed from the default (choice -1: every term at its default).
struct TermChoice {
    const char* name;
    ParamId param;
    int choice;
};

const std::vector<TermChoice>& termChoices() {
    static const std::vector<TermChoice> list{
        {"default (GGX, Smith separable, Schlick, Lambert, Charlie/Conty-Kulla)", ParamId::Count,
         -1},
        {"D Beckmann", ParamId::Distribution, int(Distribution::Beckmann)},
        {"D Blinn-Phong", ParamId::Distribution, int(Distribution::BlinnPhong)},
        {"V Smith-GGX height-correlated", ParamId::Visibility, int(Visibility::SmithGGXCorrelated)},
        {"V Schlick-GGX", ParamId::Visibility, int(Visibility::SchlickGGX)},
        {"V Cook-Torrance", ParamId::Visibility, int(Visibility::CookTorrance)},
        {"V implicit", ParamId::Visibility, int(Visibility::Implicit)},
        {"V Neumann", ParamId::Visibility, int(Visibility::Neumann)},
        {"V Kelemen", ParamId::Visibility, int(Visibility::Kelemen)},
        {"F Schlick spherical gaussian", ParamId::Fresnel, int(Fresnel::SchlickSphericalGaussian)},
        {"F exact dielectric", ParamId::Fresnel, int(Fresnel::ExactDielectric)},
        {"diffuse Burley", ParamId::Diffuse, int(Diffuse::Burley)},
        {"sheen Charlie/Ashikhmin", ParamId::SheenModel, int(SheenModel::CharlieAshikhmin)},
        {"sheen Charlie/Neubelt", ParamId::SheenModel, int(SheenModel::CharlieNeubelt)},
    };
    return list;
}

Scene analyticScene(const Material& m) {
    Scene scene = test::blackOrthographicScene();
    scene.lights = {test::analyticKeyLight()};
    scene.material = m;
    return scene;
}

struct TermResult {
    double worstRel = 0.0;   ///< worst |GPU - CPU| / CPU where CPU >= 0.05
    double worstAbs = 0.0;   ///< worst |GPU - CPU|
    double worstRatio = 0.0; ///< worst error / tolerance (must stay <= 1)
    double maxChange = 0.0;  ///< largest change from the default image, over all materials
    int pixels = 0;
    std::string where; ///< material and pixel of worstRatio
};

} // namespace

class TestRenderBrdfTerms : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
    }

    void everyTermMatchesCpuTwin() {
        std::string error;
        render::Renderer renderer;
        QVERIFY2(renderer.initialize(&error), error.c_str());
        render::OffscreenTarget target;
        QVERIFY2(target.resize(kSize, kSize, &error), error.c_str());
        auto draw = [&](const Scene& scene, render::DebugView view) {
            render::FrameSettings fs;
            fs.width = fs.height = kSize;
            fs.view = view;
            renderer.setScene(scene);
            if (!renderer.render(fs, target.framebuffer(), &error))
                qFatal("render failed: %s", error.c_str());
            return renderer.readLinear();
        };

        // Compile whatever the first frames need (the G-buffer views are a lighting.frag variant
        // of their own, built the first time one is shown), then count.
        draw(analyticScene(Material()), render::DebugView::Final);
        draw(analyticScene(Material()), render::DebugView::Normal);
        const int compiles = renderer.shaderCompileCount();

        std::map<std::string, TermResult> results;
        int failures = 0;
        for (const NamedMaterial& nm : materials()) {
            const Scene base = analyticScene(nm.material);
            const Image normal = draw(base, render::DebugView::Normal);
            const Image albedo = draw(base, render::DebugView::Albedo);
            const Image rough = draw(base, render::DebugView::Roughness);
            const Image metal = draw(base, render::DebugView::Metallic);
            const Light& light = base.lights.front();
            const glm::vec3 v = glm::normalize(render::cameraEye(base.camera) - base.camera.target);
            const glm::vec3 l = -glm::normalize(light.direction);
            const glm::vec3 E = light.color * light.intensity;

            Image defaultImage;
            for (const TermChoice& term : termChoices()) {
                Scene scene = base;
                if (term.choice >= 0)
                    scene.material.setChoice(term.param, term.choice);
                if (term.choice >= 0)
                    QCOMPARE(scene.material.choice(term.param), term.choice);
                const Image img = draw(scene, render::DebugView::Final);
                if (term.choice < 0)
                    defaultImage = img;
                TermResult& r = results[term.name];
                const brdf::Surface material = brdf::surfaceFromMaterial(scene.material);
                for (int y = 0; y < kSize; ++y)
                    for (int x = 0; x < kSize; ++x) {
                        const glm::vec3 got = glm::vec3(img.rgba(x, y));
                        r.maxChange =
                            std::max(r.maxChange,
                                     double(glm::length(got - glm::vec3(defaultImage.rgba(x, y)))));
                        const glm::vec3 n = glm::vec3(normal.rgba(x, y));
                        if (glm::length(n) < 0.5f)
                            continue; // background
                        const glm::vec3 nn = glm::normalize(n);
                        // Lit and seen: the G-buffer normal is 16-bit octahedral and read back
                        // through a half-float debug view, so the last sliver at the terminator
                        // and the silhouette (n.l, n.v < 0.05) is left out.
                        if (glm::dot(nn, l) < 0.05f || glm::dot(nn, v) < 0.05f)
                            continue;
                        brdf::Surface s = material;
                        s.baseColor = glm::vec3(albedo.rgba(x, y));
                        s.roughness = rough.rgba(x, y).x;
                        s.metallic = metal.rgba(x, y).x;
                        const glm::vec3 expected = brdf::evalDirectional(s, nn, v, l) * E;
                        for (int k = 0; k < 3; ++k) {
                            const double err = std::abs(double(got[k]) - expected[k]);
                            const double tol = std::max(0.02 * expected[k], 1.0 / 255.0);
                            r.worstAbs = std::max(r.worstAbs, err);
                            if (err / tol > r.worstRatio) {
                                r.worstRatio = err / tol;
                                r.where = std::string(nm.name) + " (" + std::to_string(x) + "," +
                                          std::to_string(y) + ") GPU " + std::to_string(got[k]) +
                                          " CPU " + std::to_string(expected[k]) + " n.l " +
                                          std::to_string(glm::dot(nn, l)) + " n.v " +
                                          std::to_string(glm::dot(nn, v));
                            }
                            if (expected[k] >= 0.05)
                                r.worstRel = std::max(r.worstRel, err / expected[k]);
                            if (err > tol && ++failures <= 10)
                                qWarning("%s, %s: pixel (%d,%d) channel %d: GPU %.5f, CPU %.5f",
                                         nm.name, term.name, x, y, k, got[k], expected[k]);
                        }
                        ++r.pixels;
                    }
            }
        }

        for (const TermChoice& term : termChoices()) {
            const TermResult& r = results[term.name];
            qInfo("%-40s %6d lit pixels: worst rel %.4f (CPU >= 0.05), worst abs %.5f, worst "
                  "error/tolerance %.3f at %s; max change vs default %.4f",
                  term.name, r.pixels, r.worstRel, r.worstAbs, r.worstRatio, r.where.c_str(),
                  r.maxChange);
        }
        QVERIFY2(failures == 0, qPrintable(QString("%1 channel values off").arg(failures)));

        // Every non-default term changes some image, except Neubelt, which is Ashikhmin's form
        // (common_brdf.glsl: visibilityNeubelt) and so changes exactly what Ashikhmin changes.
        for (const TermChoice& term : termChoices()) {
            if (term.choice < 0)
                continue;
            QVERIFY2(results[term.name].maxChange > 1e-3,
                     qPrintable(QString("%1 changed nothing").arg(term.name)));
        }
        QCOMPARE(results["sheen Charlie/Neubelt"].maxChange,
                 results["sheen Charlie/Ashikhmin"].maxChange);

        // Each scene above was set whole (setScene), so each frame drew with the lighting program
        // specialised to its term choices (render/lighting_features.h): the twins checked those.
        qInfo("shader programs compiled: %d before the term switches, %d after (lighting "
              "variants specialised to each choice)",
              compiles, renderer.shaderCompileCount());
        QCOMPARE(renderer.lightingSpecialisationFailures(), 0);

        // Switching a term as a value edit (the editor's combo box) compiles nothing: the frame
        // draws with the generic program, which chooses the term at run time.
        Scene edited = analyticScene(Material());
        draw(edited, render::DebugView::Final);
        const int before = renderer.shaderCompileCount();
        for (const TermChoice& term : termChoices()) {
            if (term.choice < 0)
                continue;
            edited.material.resetValue(term.param);
            edited.material.setChoice(term.param, term.choice);
            renderer.update(edited, ScenePart::MaterialValues);
            render::FrameSettings fs;
            fs.width = fs.height = kSize;
            QVERIFY2(renderer.render(fs, target.framebuffer(), &error), error.c_str());
            QVERIFY(!renderer.lastFrameSpecialised());
            edited.material.resetValue(term.param);
        }
        QCOMPARE(renderer.shaderCompileCount(), before);
    }
};

QTEST_GUILESS_MAIN(TestRenderBrdfTerms)
#include "test_render_brdf_terms.moc"
