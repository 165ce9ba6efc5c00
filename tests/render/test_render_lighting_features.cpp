// Lighting variants (render/lighting_features.h, issue 16): the features read off the material
// records, and the specialised lighting programs drawing the same image as the generic one for
// materials that exercise every specialisation (fixed terms, lobes compiled out, shadows and
// occlusion off or on), with the compile rules: a value edit never compiles, a new set of
// features compiles once at the next frame without an edit.
#include "core/light_rigs.h"
#include "core/resources.h"
#include "render/frame_uniforms.h"
#include "render/lighting_features.h"
#include "render/lobe_channels.h"
#include "render_test_util.h"

#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <optional>

using namespace velvet;
using render::GpuMaterial;
using render::LightingFeatures;

namespace {

Material preset(const char* name) {
    Problems problems;
    auto m = loadMaterialFile(resources::path(std::string("presets/") + name + ".json"), problems);
    if (!m)
        qFatal("cannot load preset %s", name);
    return *m;
}

/// Largest difference of any channel over the two images, relative to the larger value (with a
/// floor so black pixels compare absolutely).
double maxRelativeDifference(const Image& a, const Image& b) {
    double worst = 0.0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const double p = a.rgba(x, y)[c], q = b.rgba(x, y)[c];
                worst =
                    std::max(worst, std::abs(p - q) / std::max({std::abs(p), std::abs(q), 0.05}));
            }
    return worst;
}

/// A 64x64 checker of @p a and @p b written to @p file.
std::string writeChecker(const QTemporaryDir& dir, const char* name, glm::vec4 a, glm::vec4 b) {
    Image img(64, 64, 4);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const glm::vec4 c = ((x / 8 + y / 8) % 2) ? a : b;
            for (int k = 0; k < 4; ++k)
                img.at(x, y)[k] = c[k];
        }
    const std::string file = dir.filePath(name).toStdString();
    std::string error;
    if (!writeImage(file, img, PixelFormat::UInt8, &error))
        qFatal("%s", error.c_str());
    return file;
}

} // namespace

class TestRenderLightingFeatures : public QObject {
    Q_OBJECT
    test::OffscreenRenderer m_fx;

    /// The scene drawn by the specialised and by the generic program (one renderer, switched).
    /// With @p b, the A/B split (B right of the centre).
    std::pair<Image, Image> drawBoth(const Scene& scene, const Material* b = nullptr) {
        render::FrameSettings fs;
        fs.width = fs.height = m_fx.size;
        if (b)
            fs.splitMaterial = *b;
        auto draw = [&] {
            std::string error;
            if (!m_fx.renderer->render(fs, m_fx.target->framebuffer(), &error))
                qFatal("render failed: %s", error.c_str());
            return m_fx.renderer->readLinear();
        };
        m_fx.renderer->setSpecialisedPrograms(true);
        m_fx.renderer->setScene(scene);
        m_fx.renderer->finishEnvironment();
        m_fx.renderer->finishTextures();
        m_fx.renderer->finishGraph(); // a graph adopted inside a frame defers the specialisation
        const Image specialised = draw();
        if (!m_fx.renderer->lastFrameSpecialised())
            QTest::qFail("the frame was not drawn by a specialised program", __FILE__, __LINE__);
        m_fx.renderer->setSpecialisedPrograms(false);
        const Image generic = draw();
        m_fx.renderer->setSpecialisedPrograms(true);
        return {specialised, generic};
    }

private slots:
    void initTestCase() {
        const std::string error = m_fx.start(96);
        QVERIFY2(error.empty(), error.c_str()); // headless EGL is part of the test setup
    }
    void cleanupTestCase() { m_fx.stop(); }

    void featuresFollowTheRecords() {
        GpuMaterial velvet = render::packMaterial(preset("crimson_velvet"));
        LightingFeatures f = render::lightingFeaturesOf({&velvet, 1}, false, false, true, true);
        QCOMPARE(f.distribution, int(Distribution::GGX));
        QCOMPARE(f.sheenModel, velvet.terms2.x);
        QVERIFY(f.sheen);
        QVERIFY(!f.clearcoat);
        QVERIFY(!f.anisotropy);
        QVERIFY(!f.directionalShadows && !f.occlusion);
        QCOMPARE(f.iblBaked, 1);
        // No bent normal: the geometric horizon's reconstruction is compiled out.
        QVERIFY(!f.geometricHorizon);
        const std::vector<std::string> defines = f.defines();
        QVERIFY(std::find(defines.begin(), defines.end(), "WITH_GEOMETRIC_HORIZON 0") !=
                defines.end());
        GpuMaterial bent = velvet;
        bent.sheenWeightAnisotropy.w = 1.0f; // packMaterialRecord: a normal map or graph normal
        QVERIFY(render::lightingFeaturesOf({&bent, 1}, false, false, true, true).geometricHorizon);

        // A record whose base colour, metallic and roughness are per material (packMaterialRecord
        // flags a plain one) is read from the table alone: the G-buffer's side and its sRGB
        // decode compile out; one record of two that decodes the G-buffer keeps them.
        QVERIFY(f.gbufferValues); // packMaterial alone does not flag the record
        GpuMaterial fromTable = velvet;
        fromTable.terms2.y = render::kRecordValuesPerMaterial;
        f = render::lightingFeaturesOf({&fromTable, 1}, false, false, true, true);
        QVERIFY(!f.gbufferValues);
        const std::vector<std::string> tableDefines = f.defines();
        QVERIFY(std::find(tableDefines.begin(), tableDefines.end(), "WITH_GBUFFER_VALUES 0") !=
                tableDefines.end());
        const GpuMaterial mixed[] = {fromTable, velvet};
        QVERIFY(render::lightingFeaturesOf(mixed, false, false, true, true).gbufferValues);

        // Two materials that disagree on a term leave it to run time; a coat on one compiles it in.
        Material beckmann = preset("car_paint");
        beckmann.setChoice(ParamId::Distribution, int(Distribution::Beckmann));
        const GpuMaterial two[] = {velvet, render::packMaterial(beckmann)};
        f = render::lightingFeaturesOf(two, true, true, true, true);
        QCOMPARE(f.distribution, LightingFeatures::kAnyTerm);
        QVERIFY(f.clearcoat);
        QVERIFY(f.directionalShadows && f.occlusion);

        // A lobe that varies per pixel counts even at a zero weight: the channel carries it.
        GpuMaterial plain = render::packMaterial(preset("plastic"));
        plain.clearcoat.x = 0.0f;
        plain.sheenWeightAnisotropy = glm::vec4(0.0f);
        QVERIFY(!render::lightingFeaturesOf({&plain, 1}, false, false, true, true).clearcoat);
        render::LobeChannelMap map =
            render::assignLobeChannels(render::lobeBit(render::LobeValue::Clearcoat));
        plain.terms2.w = map.packed();
        f = render::lightingFeaturesOf({&plain, 1}, false, false, true, true);
        QVERIFY(f.clearcoat && f.lobeChannels);
        // Anisotropy needs GGX (common_brdf.glsl's usesAnisotropy).
        plain.sheenWeightAnisotropy.y = 0.5f;
        QVERIFY(render::lightingFeaturesOf({&plain, 1}, false, false, true, true).anisotropy);
        plain.terms.x = int(Distribution::Beckmann);
        QVERIFY(!render::lightingFeaturesOf({&plain, 1}, false, false, true, true).anisotropy);

        QVERIFY(LightingFeatures::generic().defines().empty());
        QVERIFY(LightingFeatures::generic().isGeneric());
    }

    /// The frame's structure compiled in: the directional lights' count (the frame block's, the
    /// ambient and local lights left out, capped as the block is) and the one material id.
    void lightCountAndMaterialIdAreDefines() {
        std::vector<Light> lights = *lightRigLights("three-point");
        QCOMPARE(render::frameDirectionalLightCount(lights), 3);
        Light ambient, point;
        ambient.type = LightType::Ambient;
        point.type = LightType::Point;
        lights.push_back(ambient);
        lights.push_back(point);
        QCOMPARE(render::frameDirectionalLightCount(lights), 3);
        Light sun;
        sun.type = LightType::Directional;
        QCOMPARE(render::frameDirectionalLightCount(
                     std::vector<Light>(render::kMaxDirectionalLights + 3, sun)),
                 render::kMaxDirectionalLights);
        QCOMPARE(render::frameDirectionalLightCount({}), 0);

        LightingFeatures f;
        f.directionalLights = 3;
        f.materialId = 0;
        const std::vector<std::string> defines = f.defines();
        QVERIFY(std::find(defines.begin(), defines.end(), "FIXED_DIRECTIONAL_LIGHTS 3") !=
                defines.end());
        QVERIFY(std::find(defines.begin(), defines.end(), "FIXED_MATERIAL_ID 0") != defines.end());
        QVERIFY(!f.isGeneric());
    }

    /// The table's base colour as the G-buffer stores it (8-bit sRGB, decoded): known answers
    /// computed by hand (0.5 encodes to 187.52 of 255, stored as 188: 0.50289), and a stored
    /// colour stores as itself, so the table and a G-buffer written from it agree.
    void storedBaseColorIsTheGBuffersValue() {
        const glm::vec3 stored = render::storedBaseColor({0.5f, 0.18f, 0.02f});
        QVERIFY(std::abs(stored.r - 0.502886f) < 2e-6f);
        QVERIFY(std::abs(stored.g - 0.181164f) < 2e-6f);
        QVERIFY(std::abs(stored.b - 0.020289f) < 2e-6f);
        QCOMPARE(render::storedBaseColor(glm::vec3(0.0f)), glm::vec3(0.0f));
        QVERIFY(std::abs(render::storedBaseColor(glm::vec3(1.0f)).r - 1.0f) < 1e-6f);
        QVERIFY(render::storedBaseColor(glm::vec3(-0.2f, 2.0f, 0.0f)).g <= 1.0f + 1e-6f);
        for (int i = 0; i <= 1000; ++i) {
            const glm::vec3 once = render::storedBaseColor(glm::vec3(float(i) / 1000.0f));
            QVERIFY(glm::all(
                glm::lessThan(glm::abs(render::storedBaseColor(once) - once), glm::vec3(1e-6f))));
        }
        const GpuMaterial velvet = render::packMaterial(preset("crimson_velvet"));
        QCOMPARE(glm::vec3(velvet.storedBaseColor),
                 render::storedBaseColor(glm::vec3(velvet.baseColorMetallic)));
    }

    /// Every specialisation draws what the generic program draws.
    void specialisedDrawsTheGenericImage_data() {
        QTest::addColumn<QString>("name");
        QTest::addColumn<bool>("shadowsAndOcclusion");
        QTest::addColumn<int>("ground"); // GroundMode; each has its own variants
        const int off = int(GroundMode::Off), plain = int(GroundMode::Plain),
                  catcher = int(GroundMode::ShadowCatcher);
        QTest::newRow("velvet (sheen, GGX terms)") << "crimson_velvet" << false << off;
        QTest::newRow("car paint (clearcoat)") << "car_paint" << true << plain;
        QTest::newRow("brushed aluminium (anisotropy)") << "brushed_aluminium" << false << off;
        QTest::newRow("wool (the knit bends the normal: the geometric horizon)")
            << "wool" << false << off;
        QTest::newRow("other terms") << "other-terms" << true << plain;
        QTest::newRow("textured (slots, atlas, lobe channels), split")
            << "textured" << false << off;
        // The shadow catcher's own program is specialised too (no shadow lookup without one).
        QTest::newRow("velvet on a shadow catcher") << "crimson_velvet" << false << catcher;
        QTest::newRow("car paint on a shadow catcher, shadows") << "car_paint" << true << catcher;
        // Three directional lights (FIXED_DIRECTIONAL_LIGHTS 3), on the catcher and on the plain
        // ground (whose frame decodes the material id per pixel).
        QTest::newRow("velvet, three-point rig, catcher") << "three-point" << true << catcher;
        QTest::newRow("velvet, three-point rig, plain ground") << "three-point" << false << plain;
    }
    void specialisedDrawsTheGenericImage() {
        QFETCH(QString, name);
        QFETCH(bool, shadowsAndOcclusion);
        QFETCH(int, ground);
        Scene scene = test::shippedDefaultScene();
        if (name == "other-terms") { // every term away from its default
            scene.material = preset("leather");
            scene.material.setChoice(ParamId::Distribution, int(Distribution::Beckmann));
            scene.material.setChoice(ParamId::Visibility, int(Visibility::SmithGGXCorrelated));
            scene.material.setChoice(ParamId::Fresnel, int(Fresnel::ExactDielectric));
            scene.material.setChoice(ParamId::Diffuse, int(Diffuse::Burley));
            scene.material.setScalar(ParamId::SheenWeight, 0.5f);
            scene.material.setChoice(ParamId::SheenModel, int(SheenModel::CharlieAshikhmin));
        }
        QTemporaryDir dir;
        std::optional<Material> b;
        if (name == "textured") { // G-buffer specialisations: slots, an atlas region, a lobe map
            scene.material = preset("crimson_velvet");
            TextureRef base;
            base.file = writeChecker(dir, "base.png", {1, 1, 1, 1}, {0.3f, 0.5f, 0.9f, 1});
            scene.material.setTexture(TextureSlot::BaseColor, base);
            TextureRef sheen;
            sheen.file = writeChecker(dir, "sheen.png", {1, 0.8f, 0.2f, 1}, {0.1f, 0.1f, 0.1f, 1});
            sheen.useRegion = true; // its top-left quarter, as an atlas region
            sheen.region = {0, 0, 32, 32};
            scene.material.setTexture(TextureSlot::SheenColor, sheen);
            b = preset("car_paint"); // B: other values, a coat, no textures of its own
        } else if (name == "three-point") {
            scene.material = preset("crimson_velvet");
            scene.lights = *lightRigLights("three-point");
        } else if (name != "other-terms") {
            scene.material = preset(name.toUtf8().constData());
        }
        for (Light& light : scene.lights)
            light.castShadows = shadowsAndOcclusion;
        scene.environment.ambientOcclusion = shadowsAndOcclusion;
        scene.environment.ground = GroundMode(ground);
        const auto [specialised, generic] = drawBoth(scene, b ? &*b : nullptr);
        QCOMPARE(m_fx.renderer->lightingSpecialisationFailures(), 0);
        const double difference = maxRelativeDifference(specialised, generic);
        qInfo("%s: largest relative difference %.2e", qPrintable(name), difference);
        QVERIFY2(difference < 2e-3, qPrintable(QString::number(difference)));
    }

    /// A value edit compiles nothing, even one that turns a lobe on: that frame the generic
    /// program draws it; the next frame without an edit builds the variant, once.
    void valueEditsNeverCompile() {
        Scene scene = test::shippedDefaultScene();
        scene.material = preset("plastic");
        scene.material.setScalar(ParamId::ClearcoatWeight, 0.0f);
        for (Light& light : scene.lights)
            light.castShadows = false;
        m_fx.renderer->setScene(scene);
        m_fx.renderer->finishEnvironment();
        m_fx.draw(nullptr);
        m_fx.draw(nullptr);
        QVERIFY(m_fx.renderer->lastFrameSpecialised());
        const int compiles = m_fx.renderer->shaderCompileCount();

        // Roughness: the same features, the same program.
        scene.material.setScalar(ParamId::Roughness, 0.3f);
        m_fx.renderer->update(scene, ScenePart::MaterialValues);
        m_fx.draw(nullptr);
        QVERIFY(m_fx.renderer->lastFrameSpecialised());
        QCOMPARE(m_fx.renderer->shaderCompileCount(), compiles);

        // A coat appears: drawn at once by the generic program, no compile.
        scene.material.setScalar(ParamId::ClearcoatWeight, 1.0f);
        m_fx.renderer->update(scene, ScenePart::MaterialValues);
        const Image duringEdit = m_fx.draw(nullptr);
        QVERIFY(!m_fx.renderer->lastFrameSpecialised());
        QCOMPARE(m_fx.renderer->shaderCompileCount(), compiles);
        // The next frame without an edit builds the coat's variant, once, and draws the same.
        const Image after = m_fx.draw(nullptr);
        QVERIFY(m_fx.renderer->lastFrameSpecialised());
        QCOMPARE(m_fx.renderer->shaderCompileCount(), compiles + 1);
        QVERIFY(maxRelativeDifference(duringEdit, after) < 2e-3);
        m_fx.draw(nullptr);
        QCOMPARE(m_fx.renderer->shaderCompileCount(), compiles + 1);

        // Back to no coat: that variant is still built, nothing compiles.
        scene.material.setScalar(ParamId::ClearcoatWeight, 0.0f);
        m_fx.renderer->update(scene, ScenePart::MaterialValues);
        m_fx.draw(nullptr);
        QVERIFY(m_fx.renderer->lastFrameSpecialised());
        QCOMPARE(m_fx.renderer->shaderCompileCount(), compiles + 1);

        // A light's values (its intensity, its direction) are no structure either, though the
        // directional lights' count is compiled in (FIXED_DIRECTIONAL_LIGHTS).
        QVERIFY(!scene.lights.empty() && scene.lights.front().type == LightType::Directional);
        scene.lights.front().intensity *= 0.5f;
        scene.lights.front().direction = glm::vec3(0.3f, -1.0f, -0.2f);
        m_fx.renderer->update(scene, ScenePart::Lights);
        m_fx.draw(nullptr);
        QVERIFY(m_fx.renderer->lastFrameSpecialised());
        QCOMPARE(m_fx.renderer->shaderCompileCount(), compiles + 1);
    }

    /// A specialised program that fails to build (here: lighting.frag broken only where a lobe is
    /// compiled out, in a copy of the shaders) is a warning naming the file, and the generic
    /// program draws the frame. Last: the process keeps the shader copy.
    void aFailedSpecialisationWarnsAndDrawsGeneric() {
        QTemporaryDir dir;
        const std::filesystem::path shaders = test::useShaderCopy(dir.path().toStdString());
        const std::filesystem::path file = shaders / "lighting.frag";
        std::string text = test::readText(file);
        const size_t main = text.rfind("void main()");
        QVERIFY(main != std::string::npos);
        text.insert(main, "#if !WITH_CLEARCOAT\nthis is not glsl;\n#endif\n");
        test::writeText(file, text);

        test::OffscreenRenderer fx;
        QCOMPARE(QString::fromStdString(fx.start(48)), QString());
        Scene scene = test::shippedDefaultScene(); // velvet: no clear coat, the broken branch
        fx.renderer->setScene(scene);
        fx.renderer->finishEnvironment();
        const Image drawn = fx.draw(nullptr);
        QVERIFY(!fx.renderer->lastFrameSpecialised());
        QCOMPARE(fx.renderer->lightingSpecialisationFailures(), 1);
        const Problems warnings = fx.renderer->takeWarnings();
        bool named = false;
        for (const Problem& p : warnings.items)
            named = named || p.toString().find("lighting.frag") != std::string::npos;
        QVERIFY2(named, "no warning names lighting.frag");
        fx.draw(nullptr);
        QCOMPARE(fx.renderer->lightingSpecialisationFailures(), 1); // not retried every frame
        fx.renderer->setSpecialisedPrograms(false);
        QCOMPARE(maxRelativeDifference(drawn, fx.draw(nullptr)), 0.0);
        fx.stop();
    }
};

QTEST_MAIN(TestRenderLightingFeatures)
#include "test_render_lighting_features.moc"
