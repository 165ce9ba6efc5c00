// A scene saved with its atlases as one document (core/scene_document.h), the core function the
// editor's Save and the CLI share: the atlases go to "<stem>.atlas.json" beside the scene (sources
// that live only in memory written as EXR), the scene names that file, loading both gives back
// the same document; no atlases: no atlas file and a scene that names none; a failed write
// returns nothing, reports one error naming the file, and leaves the caller's document and the
// scene file as they were.
#include "core/atomic_file.h"
#include "core/document_io.h"
#include "core/scene_document.h"

#include <QTemporaryDir>
#include <QtTest>
#include <filesystem>
#include <fstream>

using namespace velvet;
namespace fs = std::filesystem;

namespace {

std::string allMessages(const Problems& problems) {
    std::string all;
    for (const Problem& p : problems.items)
        all += p.toString() + "\n";
    return all;
}

/// One albedo atlas whose only source exists in memory.
AtlasSet inMemoryAtlases() {
    AtlasSet set;
    AtlasDocument& albedo = set[AtlasKind::Albedo];
    albedo.width = albedo.height = 16;
    albedo.padding = 1;
    AtlasEntry e;
    e.name = "weave";
    e.source = Image(4, 4, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            float* p = e.source.at(x, y);
            p[0] = float(x) / 4.0f, p[1] = float(y) / 4.0f, p[2] = 0.5f, p[3] = 1.0f;
        }
    e.region = {2, 2, 8, 8};
    albedo.entries = {e};
    composeAtlas(albedo);
    return set;
}

std::string absoluteGeneric(const fs::path& p) {
    return fs::absolute(p).lexically_normal().generic_string();
}

} // namespace

class TestCoreSceneDocument : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() { QVERIFY(m_tmp.isValid()); }

    void atlasFileIsBesideTheScene() {
        QCOMPARE(atlasFileFor("/a/b/look.json"), fs::path("/a/b/look.atlas.json"));
        QCOMPARE(atlasFileFor("look.scene.json"), fs::path("look.scene.atlas.json"));
    }

    void savesSceneAndAtlasesTogether() {
        const fs::path dir = fs::path(m_tmp.path().toStdString()) / "together";
        fs::create_directories(dir);
        SceneDocument document;
        document.scene.environment.intensity = 2.5f;
        document.atlases = inMemoryAtlases();
        const SceneDocument before = document;
        Problems problems;
        const std::optional<SceneDocument> saved =
            saveSceneDocument(document, dir / "look.json", problems);
        QVERIFY2(saved, allMessages(problems).c_str());
        QVERIFY2(problems.items.empty(), allMessages(problems).c_str());
        // The caller's document is untouched; the saved one names what was written.
        QVERIFY(document.atlases == before.atlases);
        QVERIFY(document.scene.atlases.empty());
        QCOMPARE(saved->scene.atlases, absoluteGeneric(dir / "look.atlas.json"));
        QCOMPARE(saved->atlases[AtlasKind::Albedo].entries[0].file,
                 absoluteGeneric(dir / "look.albedo-0.exr"));
        QVERIFY(fs::exists(dir / "look.atlas.json"));
        QVERIFY(fs::exists(dir / "look.albedo-0.exr"));
        // The scene file names its atlases relative to itself, and both read back as saved.
        std::string error;
        const std::string text = *readWholeFile(dir / "look.json", 1 << 20, &error);
        QVERIFY2(text.find("\"atlases\": \"look.atlas.json\"") != std::string::npos, text.c_str());
        const std::optional<Scene> scene = loadSceneFile(dir / "look.json", problems);
        QVERIFY2(scene, allMessages(problems).c_str());
        QCOMPARE(scene->atlases, saved->scene.atlases);
        QCOMPARE(scene->environment.intensity, 2.5f);
        const std::optional<AtlasSet> atlases = loadAtlasFile(scene->atlases, problems);
        QVERIFY2(atlases, allMessages(problems).c_str());
        QVERIFY(*atlases == saved->atlases);
        QCOMPARE(atlases->atlases[0].image.pixels, before.atlases.atlases[0].image.pixels);
        QVERIFY2(problems.items.empty(), allMessages(problems).c_str());
    }

    void noAtlasesNoAtlasFile() {
        const fs::path dir = fs::path(m_tmp.path().toStdString()) / "none";
        fs::create_directories(dir);
        SceneDocument document;
        document.scene.atlases = absoluteGeneric(dir / "stale.atlas.json"); // named, now empty
        Problems problems;
        const auto saved = saveSceneDocument(document, dir / "plain.json", problems);
        QVERIFY2(saved, allMessages(problems).c_str());
        QVERIFY(saved->scene.atlases.empty());
        QVERIFY(!fs::exists(dir / "plain.atlas.json"));
        std::string error;
        const std::string text = *readWholeFile(dir / "plain.json", 1 << 20, &error);
        QVERIFY2(text.find("\"atlases\"") == std::string::npos, text.c_str());
    }

    // The atlas file cannot be written (its name is taken by a folder): nothing is returned, one
    // error names the file, and the scene file already there is not replaced.
    void failedAtlasWriteKeepsTheScene() {
        const fs::path dir = fs::path(m_tmp.path().toStdString()) / "atlas-fails";
        fs::create_directories(dir / "look.atlas.json");
        std::ofstream(dir / "look.json") << "previous";
        SceneDocument document;
        document.atlases = inMemoryAtlases();
        Problems problems;
        QVERIFY(!saveSceneDocument(document, dir / "look.json", problems));
        QCOMPARE(int(problems.items.size()), 1);
        QVERIFY(problems.hasErrors());
        QVERIFY2(problems.items[0].toString().find("look.atlas.json") != std::string::npos,
                 allMessages(problems).c_str());
        std::string error;
        QCOMPARE(*readWholeFile(dir / "look.json", 100, &error), std::string("previous"));
    }

    // The scene file cannot be written (a folder of that name): nothing is returned and the
    // error names the scene file.
    void failedSceneWriteIsReported() {
        const fs::path dir = fs::path(m_tmp.path().toStdString()) / "scene-fails";
        fs::create_directories(dir / "look.json");
        SceneDocument document;
        Problems problems;
        QVERIFY(!saveSceneDocument(document, dir / "look.json", problems));
        QCOMPARE(int(problems.items.size()), 1);
        QVERIFY2(problems.items[0].toString().find("look.json") != std::string::npos,
                 allMessages(problems).c_str());
    }

private:
    QTemporaryDir m_tmp;
};

QTEST_GUILESS_MAIN(TestCoreSceneDocument)
#include "test_core_scene_document.moc"
