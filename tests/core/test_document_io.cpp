// Proves the file formats keep what they are given: save then load returns an equal model, old
// versions migrate, newer ones are refused, every shipped preset loads cleanly and the shipped
// schemas are exactly what the metadata generates.
#include "core/atomic_file.h"
#include "core/document_io.h"
#include "core/resources.h"
#include "shipped_schema.h"

#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>
#include <filesystem>
#include <fstream>
#include <unistd.h>

using namespace velvet;
namespace fs = std::filesystem;

namespace {

std::string problemsText(const Problems& p) {
    std::string out;
    for (const Problem& item : p.items)
        out += item.toString() + "\n";
    return out;
}

void writeText(const fs::path& file, const std::string& text) {
    fs::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << text;
}

/// Every parameter away from its default, to a value a float stores exactly enough to compare.
Material everythingSet(const fs::path& dir) {
    Material m;
    m.name = "Everything \"quoted\" ünïcode";
    m.tags = {"fabric", "test tag"};
    for (int i = 0; i < kParamCount; ++i) {
        const auto id = static_cast<ParamId>(i);
        const ParamMeta& meta = paramMeta(id);
        switch (meta.type) {
        case ParamType::Float:
            m.setScalar(id, meta.defaultValue.x == meta.max ? meta.min + 0.125f : meta.max - 0.25f);
            break;
        case ParamType::Color:
            m.setColor(id, {0.1f, 0.55f, 0.9f});
            break;
        case ParamType::Choice:
            m.setChoice(id, static_cast<int>(meta.choices.size()) - 1);
            break;
        }
    }
    TextureRef albedo;
    albedo.file = (dir / "textures/atlas_albedo.png").generic_string();
    albedo.useRegion = true;
    albedo.region = {64, 128, 256, 32};
    albedo.colorSpace = "sRGB texture";
    m.setTexture(TextureSlot::BaseColor, albedo);
    TextureRef srm;
    srm.file = (dir / "textures/atlas_material.png").generic_string();
    srm.useRegion = true;
    srm.region = {0, 0, 16, 16};
    m.setTexture(TextureSlot::SpecRoughMetal, srm);
    TextureRef normal;
    normal.file = "/somewhere/else/normal.png"; // outside the folder: stays absolute
    m.setTexture(TextureSlot::Normal, normal);
    return m;
}

Scene everyLightScene(const fs::path& dir) {
    Scene s;
    s.camera.target = {0.1f, 0.5f, -0.25f};
    s.camera.yawDeg = 725.0f;
    s.camera.pitchDeg = -30.0f;
    s.camera.distance = 5.5f;
    s.camera.fovYDeg = 50.0f;
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 50.0f;
    s.camera.orthographic = true;
    s.camera.orthoHeight = 3.0f;
    for (int t = 0; t <= static_cast<int>(LightType::Ambient); ++t) {
        Light l;
        l.type = static_cast<LightType>(t);
        l.name = "light " + std::to_string(t);
        l.color = {1.0f, 0.5f + 0.1f * static_cast<float>(t), 0.25f};
        l.intensity = 2.0f + static_cast<float>(t);
        l.position = {1.0f, 2.0f, static_cast<float>(t)};
        l.direction = {0.0f, -1.0f, 0.5f};
        l.range = 7.5f;
        l.innerConeDeg = 12.5f;
        l.outerConeDeg = 45.0f;
        l.shape = AreaShape::Rectangle;
        l.size = {2.0f, 0.75f};
        l.castShadows = t % 2 == 0;
        l.sourceAngleDeg = 0.5f + float(t);
        l.sourceRadius = 0.1f * float(t + 1);
        s.lights.push_back(l);
    }
    s.lights[0].innerConeDeg = 5.0f; // irrelevant to a directional light, kept anyway
    s.environment.hdri = (dir / "hdri/sky.exr").generic_string();
    s.environment.color = {0.5f, 0.6f, 0.7f};
    s.environment.intensity = 0.75f;
    s.environment.rotationDeg = -45.0f;
    s.environment.background = BackgroundMode::SolidColor;
    s.environment.backgroundColor = {0.05f, 0.05f, 0.06f};
    s.environment.ground = GroundMode::Plain;
    s.environment.groundColor = {0.3f, 0.25f, 0.2f};
    s.environment.groundRoughness = 0.45f;
    s.environment.ambientOcclusion = true;
    s.environment.occlusionRadius = 0.6f;
    s.mesh.kind = PreviewMeshKind::Custom;
    s.mesh.file = (dir / "meshes/dress.glb").generic_string();
    s.material = everythingSet(dir);
    s.materialPreset = (dir / "presets/source.json").generic_string();
    EffectInstance bloom;
    bloom.type = "bloom";
    bloom.params = {{"threshold", {1.0f}}, {"tint", {1.0f, 0.9f, 0.8f}}};
    EffectInstance vignette;
    vignette.type = "vignette";
    vignette.enabled = false;
    vignette.params = {{"intensity", {0.35f}}};
    EffectInstance tonemap;
    tonemap.type = "tonemap";
    // Stage order (core/post_effects.h): pre-pass, tone mapping, LDR.
    s.post.effects = {bloom, tonemap, vignette};
    return s;
}

} // namespace

class TestDocumentIo : public QObject {
    Q_OBJECT
private slots:
    void materialRoundTripThroughFile() {
        QTemporaryDir tmp;
        const fs::path dir = fs::path(tmp.path().toStdString()).lexically_normal();
        const Material m = everythingSet(dir);
        for (int i = 0; i < kParamCount; ++i)
            QVERIFY2(m.value(ParamId(i)) != paramMeta(ParamId(i)).defaultValue,
                     std::string(paramMeta(ParamId(i)).id).c_str());
        const fs::path file = dir / "everything.json";
        std::string error;
        QVERIFY2(saveMaterialFile(m, file, &error), error.c_str());
        Problems problems;
        const auto loaded = loadMaterialFile(file, problems);
        QVERIFY2(loaded.has_value(), problemsText(problems).c_str());
        QVERIFY2(!problems.hasErrors(), problemsText(problems).c_str());
        QVERIFY(*loaded == m);
        // Files under the document's folder are written relative, with "/" separators.
        const std::string text = *readWholeFile(file, kMaxDocumentBytes, nullptr);
        QVERIFY(text.find("\"file\": \"textures/atlas_albedo.png\"") != std::string::npos);
        QVERIFY(text.find("\"region\": [64, 128, 256, 32]") != std::string::npos);
        QVERIFY(text.find("\"/somewhere/else/normal.png\"") != std::string::npos);
        // The textures do not exist: warnings, one per slot, and still a material.
        QCOMPARE(static_cast<int>(problems.items.size()), 3);
    }

    void materialRoundTripInMemory() {
        const Material m = everythingSet({});
        Problems problems;
        const auto loaded = parseMaterial(materialToJson(m), "", {}, problems);
        QVERIFY2(loaded && *loaded == m, problemsText(problems).c_str());
        QVERIFY(parseMaterial(materialToJson(Material{}), "", {}, problems) == Material{});
    }

    void sceneRoundTrip() {
        QTemporaryDir tmp;
        const fs::path dir = fs::path(tmp.path().toStdString()).lexically_normal();
        const Scene s = everyLightScene(dir);
        const fs::path file = dir / "scene.json";
        std::string error;
        QVERIFY2(saveSceneFile(s, file, &error), error.c_str());
        Problems problems;
        const auto loaded = loadSceneFile(file, problems);
        QVERIFY2(loaded.has_value(), problemsText(problems).c_str());
        QVERIFY(loaded->lights == s.lights);
        QVERIFY(loaded->camera == s.camera);
        QVERIFY(loaded->environment == s.environment);
        QVERIFY(loaded->mesh == s.mesh);
        QVERIFY(loaded->post == s.post);
        QVERIFY(loaded->material == s.material);
        QCOMPARE(loaded->materialPreset, s.materialPreset);
        QVERIFY(*loaded == s);
        // Saving again keeps the previous file as backup generation 1.
        QVERIFY(saveSceneFile(*loaded, file, &error));
        QVERIFY(fs::exists(dir / "scene.json.1"));
    }

    void defaultSceneRoundTrip() {
        Problems problems;
        const Scene s = defaultScene(&problems);
        QVERIFY2(problems.items.empty(), problemsText(problems).c_str());
        QCOMPARE(s.material.name, std::string("Crimson velvet"));
        QCOMPARE(s.lights.size(), size_t(1));
        QCOMPARE(s.lights[0].type, LightType::Directional);
        QVERIFY(s.lights[0].direction.x > 0 && s.lights[0].direction.y < 0 &&
                s.lights[0].direction.z < 0);
        QVERIFY(fs::exists(s.environment.hdri));
        QCOMPARE(s.mesh.kind, PreviewMeshKind::Sphere);
        QVERIFY(s.post.effects.empty());
        const auto loaded = parseScene(sceneToJson(s), "", {}, problems);
        QVERIFY2(loaded && *loaded == s, problemsText(problems).c_str());

        Material gold;
        gold.name = "Gold";
        const Scene withGold = sceneWithMaterial(gold);
        QCOMPARE(withGold.material, gold);
        QCOMPARE(withGold.lights, s.lights);
    }

    void sceneReferencesPresetRelatively() {
        QTemporaryDir tmp;
        const fs::path dir = fs::path(tmp.path().toStdString()).lexically_normal();
        writeText(dir / "presets/red.json",
                  R"({"format":"velvet.material","version":2,"name":"Red",)"
                  R"("lobes":{"base":{"color":[1,0,0]}}})");
        writeText(dir / "scene.json",
                  R"({"format":"velvet.scene","version":1,"material":"presets/red.json"})");
        Problems problems;
        const auto s = loadSceneFile(dir / "scene.json", problems);
        QVERIFY2(s.has_value(), problemsText(problems).c_str());
        QCOMPARE(s->material.name, std::string("Red"));
        QCOMPARE(s->material.color(ParamId::BaseColor), glm::vec3(1, 0, 0));
        QCOMPARE(s->materialPreset, (dir / "presets/red.json").generic_string());
        QCOMPARE(detectDocumentKind(dir / "scene.json"), DocumentKind::Scene);
        QCOMPARE(detectDocumentKind(dir / "presets/red.json"), DocumentKind::Material);
        QCOMPARE(detectDocumentKind(dir / "missing.json"), DocumentKind::Unknown);
    }

    // Scenes written before the look-dev stage have no ground, no occlusion and lights that cast
    // no shadows (their image is unchanged); the rigs' key lights cast shadows; the editor's mesh
    // switch puts the drape and the shader ball on a shadow catcher (core/scene.h).
    void stageDefaults() {
        Problems problems;
        const auto old =
            parseScene(R"({"format":"velvet.scene","version":2,"lights":[{"type":"directional"}]})",
                       "", {}, problems);
        QVERIFY2(old, problemsText(problems).c_str());
        QCOMPARE(old->environment.ground, GroundMode::Off);
        QVERIFY(!old->environment.ambientOcclusion);
        QVERIFY(!old->lights[0].castShadows);
        QVERIFY(defaultScene().lights[0].castShadows);
        Environment env;
        QVERIFY(hasStageDefaults(env, PreviewMeshKind::Sphere));
        applyStageDefaults(env, PreviewMeshKind::ShaderBall);
        QCOMPARE(env.ground, GroundMode::ShadowCatcher);
        QVERIFY(env.ambientOcclusion);
        QVERIFY(hasStageDefaults(env, PreviewMeshKind::ClothDrape));
        QVERIFY(!hasStageDefaults(env, PreviewMeshKind::Cube));
        const auto bad =
            parseScene(R"({"format":"velvet.scene","version":2,"environment":{"ground":"floor"}})",
                       "", {}, problems);
        QVERIFY(!bad);
        QVERIFY2(problemsText(problems).find("environment.ground") != std::string::npos,
                 problemsText(problems).c_str());
    }

    void version1Migrates() {
        Problems problems;
        const auto m = parseMaterial(
            R"({"format":"velvet.material","version":1,"name":"Seed","albedo":[0.5,0.25,0.125],)"
            R"("specular":0.25,"roughness":0.7,"metallic":0.5})",
            "seed.json", {}, problems);
        QVERIFY2(m.has_value(), problemsText(problems).c_str());
        QCOMPARE(m->name, std::string("Seed"));
        QCOMPARE(m->color(ParamId::BaseColor), glm::vec3(0.5f, 0.25f, 0.125f));
        QCOMPARE(m->scalar(ParamId::SpecularWeight), 0.5f); // 2 × 0.25
        QCOMPARE(m->scalar(ParamId::Roughness), 0.7f);
        QCOMPARE(m->scalar(ParamId::Metallic), 0.5f);
        // Disney's 0.5 (4 %) is the glTF default weight 1; higher values saturate.
        const auto bright =
            parseMaterial(R"({"format":"velvet.material","version":1,"name":"B","specular":0.9})",
                          "", {}, problems);
        QVERIFY(bright && bright->scalar(ParamId::SpecularWeight) == 1.0f);
        // Migrated documents save as the current version.
        QVERIFY(materialToJson(*m).find("\"version\": 2") != std::string::npos);
    }

    void newerVersionRefused() {
        Problems problems;
        QVERIFY(!parseMaterial(R"({"format":"velvet.material","version":3,"name":"x"})", "f.json",
                               {}, problems));
        QCOMPARE(problems.items.size(), size_t(1));
        QCOMPARE(problems.items[0].toString(),
                 std::string("f.json: version: version 3 is newer than this Velvet reads (2); "
                             "update Velvet"));
        Problems sceneProblems;
        QVERIFY(!parseScene(R"({"format":"velvet.scene","version":3})", "", {}, sceneProblems));
        QVERIFY(problemsText(sceneProblems).find("newer than this Velvet reads (2)") !=
                std::string::npos);
    }

    void shippedPresetsLoadCleanly() {
        const fs::path presets = resources::path("presets");
        int count = 0;
        for (const auto& entry : fs::directory_iterator(presets)) {
            if (entry.path().extension() != ".json")
                continue;
            ++count;
            Problems problems;
            const auto m = loadMaterialFile(entry.path(), problems);
            QVERIFY2(m.has_value() && problems.items.empty(),
                     (entry.path().string() + "\n" + problemsText(problems)).c_str());
            QVERIFY2(!m->tags.empty(), entry.path().string().c_str());
            QCOMPARE(detectDocumentKind(entry.path()), DocumentKind::Material);
            // Saving reproduces the same model.
            const auto again = parseMaterial(materialToJson(*m), "", {}, problems);
            QVERIFY(again && *again == *m);
        }
        QVERIFY2(count >= 14, "expected the 14 library presets");
    }

    void shippedSchemasMatchGenerated_data() {
        QTest::addColumn<int>("kind");
        QTest::addColumn<QString>("file");
        QTest::newRow("material") << int(DocumentKind::Material) << "material.schema.json";
        QTest::newRow("scene") << int(DocumentKind::Scene) << "scene.schema.json";
    }
    void shippedSchemasMatchGenerated() {
        QFETCH(int, kind);
        QFETCH(QString, file);
        const std::string generated = jsonSchema(static_cast<DocumentKind>(kind));
        const fs::path shipped =
            fs::path(VELVET_SOURCE_DIR) / "resources/schemas" / file.toStdString();
        const std::string problem = test::checkShippedSchema(shipped, generated);
        QVERIFY2(problem.empty(), problem.c_str());
        // The schema is itself a valid JSON document.
        Problems problems;
        QVERIFY(!parseMaterial(generated, "schema", {}, problems)); // not a material …
        QVERIFY(problemsText(problems).find("invalid JSON") == std::string::npos); // … but JSON
    }
    // One switch regenerates every shipped schema (tests/core/shipped_schema.h): a stale file is
    // reported with that switch's name, rewritten only when it is set, and the old second name
    // (VELVET_WRITE_SCHEMAS) no longer does anything.
    void oneSwitchRegeneratesSchemas() {
        QTemporaryDir tmp;
        const fs::path file = fs::path(tmp.path().toStdString()) / "stale.schema.json";
        writeText(file, "{}\n");
        const std::string generated = jsonSchema(DocumentKind::Material);
        qunsetenv(test::kUpdateSchemasVariable);
        qputenv("VELVET_WRITE_SCHEMAS", "1");
        const std::string stale = test::checkShippedSchema(file, generated);
        QVERIFY(stale.find("stale.schema.json is out of date") != std::string::npos);
        QVERIFY(stale.find("VELVET_UPDATE_SCHEMAS=1") != std::string::npos);
        QCOMPARE(*readWholeFile(file, 100, nullptr), std::string("{}\n"));
        qunsetenv("VELVET_WRITE_SCHEMAS");
        qputenv(test::kUpdateSchemasVariable, "1");
        const std::string updated = test::checkShippedSchema(file, generated);
        qunsetenv(test::kUpdateSchemasVariable);
        QVERIFY2(updated.empty(), updated.c_str());
        QCOMPARE(*readWholeFile(file, kMaxDocumentBytes, nullptr), generated);
    }

    void atomicWriteReplacesAndBacksUp() {
        QTemporaryDir tmp;
        const fs::path file = fs::path(tmp.path().toStdString()) / "doc.json";
        std::string error;
        QVERIFY(writeFileAtomically(file, "one", &error));
        QVERIFY(writeFileAtomically(file, "two", &error, true));
        QCOMPARE(*readWholeFile(file, 100, nullptr), std::string("two"));
        QCOMPARE(*readWholeFile(backupPath(file, 1), 100, nullptr), std::string("one"));
        // No temporary files are left behind.
        int entries = 0;
        for ([[maybe_unused]] const auto& e : fs::directory_iterator(file.parent_path()))
            ++entries;
        QCOMPARE(entries, 2);
        QVERIFY(!writeFileAtomically(fs::path(tmp.path().toStdString()) / "no/such/dir/x.json", "x",
                                     &error));
        QVERIFY2(error.find("no/such/dir/x.json") != std::string::npos &&
                     error.find("does not exist") != std::string::npos,
                 error.c_str());
        QVERIFY(!readWholeFile(file, 2, &error));
        QVERIFY2(error.find("doc.json") != std::string::npos &&
                     error.find("3 bytes") != std::string::npos,
                 error.c_str());
        QVERIFY(!readWholeFile(file.parent_path(), 100, &error));
        QVERIFY2(error.find("folder") != std::string::npos, error.c_str());
    }

    // Issue 18: three saves leave the two previous versions (FILE.1 newest, FILE.2 before it),
    // a fourth drops the oldest, and the file keeps its mode. Both write paths (unnamed temporary
    // and the named fallback) behave the same.
    void threeSavesLeaveTwoPreviousVersions_data() {
        QTest::addColumn<bool>("unnamed");
        QTest::newRow("O_TMPFILE") << true;
        QTest::newRow("named temporary") << false;
    }
    void threeSavesLeaveTwoPreviousVersions() {
        QFETCH(bool, unnamed);
        QTemporaryDir tmp;
        const fs::path file = fs::path(tmp.path().toStdString()) / "scene.json";
        AtomicWriteOptions options;
        options.backupGenerations = kDefaultBackupGenerations;
        options.allowUnnamedTemporary = unnamed;
        std::string error;
        for (const char* text : {"first", "second", "third"})
            QVERIFY2(writeFileAtomically(file, text, &error, options), error.c_str());
        QCOMPARE(*readWholeFile(file, 100, nullptr), std::string("third"));
        QCOMPARE(*readWholeFile(backupPath(file, 1), 100, nullptr), std::string("second"));
        QCOMPARE(*readWholeFile(backupPath(file, 2), 100, nullptr), std::string("first"));
        QVERIFY(!fs::exists(backupPath(file, 3)));
        fs::permissions(file, fs::perms(0640));
        QVERIFY2(writeFileAtomically(file, "fourth", &error, options), error.c_str());
        QCOMPARE(*readWholeFile(backupPath(file, 2), 100, nullptr), std::string("second"));
        QVERIFY(!fs::exists(backupPath(file, 3)));
        QCOMPARE(fs::status(file).permissions() & fs::perms::all, fs::perms(0640));
        // Exactly the file and its two generations: no temporaries.
        QCOMPARE(std::distance(fs::directory_iterator(file.parent_path()), {}), 3);
        // The document savers keep the default generations.
        Scene scene;
        const fs::path sceneFile = file.parent_path() / "s.json";
        for (int i = 0; i < 3; ++i)
            QVERIFY2(saveSceneFile(scene, sceneFile, &error), error.c_str());
        QVERIFY(fs::exists(backupPath(sceneFile, 2)) && !fs::exists(backupPath(sceneFile, 3)));
    }

    // A temporary a killed writer left behind (its process is gone) is removed by the next write
    // of the same target; one of a running writer, or of another target, is left alone.
    void staleTemporariesAreSweptOnTheNextWrite() {
        QTemporaryDir tmp;
        const fs::path dir = tmp.path().toStdString();
        const fs::path file = dir / "orm.png";
        // A process id that is certainly gone: a child that has exited and been reaped.
        QProcess child;
        child.start("true", {});
        QVERIFY(child.waitForFinished());
        const std::string deadPid = std::to_string(child.processId() ? child.processId() : 999999);
        const std::string stale = ".orm.png.velvet-tmp-" + deadPid + "-Ab12Cd";
        const std::string staleImage = ".orm.png.velvet-tmp-" + deadPid + "-o3.png";
        const std::string live = ".orm.png.velvet-tmp-" + std::to_string(::getpid()) + "-u7";
        const std::string other = ".other.png.velvet-tmp-" + deadPid + "-Ab12Cd";
        for (const std::string& name : {stale, staleImage, live, other})
            writeText(dir / name, "half");
        QVERIFY(isTemporaryOf(file, stale) && isTemporaryOf(file, live));
        QVERIFY(!isTemporaryOf(file, other) && !isTemporaryOf(file, "orm.png") &&
                !isTemporaryOf(file, ".orm.png.velvet-tmp--x"));
        std::string error;
        QVERIFY2(writeFileAtomically(file, "png", &error), error.c_str());
        QVERIFY(!fs::exists(dir / stale) && !fs::exists(dir / staleImage));
        QVERIFY(fs::exists(dir / live) && fs::exists(dir / other));
    }
};

QTEST_APPLESS_MAIN(TestDocumentIo)
#include "test_document_io.moc"
