// Atlas documents (core/atlas_document.h, issue 5 "Atlas panel"): save then load gives back an
// equal set (regions, padding, export path, source pixels, composed image) whether the sources
// came from files or lived only in memory (written beside the document as float EXR); paths are
// stored relative to the document; every problem names its JSON path; a newer version is
// refused; a missing source is a warning; a scene names its atlas document (scene version 2) and
// version 1 scenes still load; exporting writes every non-empty atlas image atomically; the
// shipped schema is the generated one (regenerate with VELVET_UPDATE_SCHEMAS=1).
#include "core/atlas_document.h"
#include "core/atomic_file.h"
#include "core/document_io.h"
#include "shipped_schema.h"

#include <QTemporaryDir>
#include <QtTest>
#include <filesystem>

using namespace velvet;
namespace fs = std::filesystem;

namespace {

Image gradient(int w, int h, float blue) {
    Image image(w, h, 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = image.at(x, y);
            p[0] = float(x) / float(w), p[1] = float(y) / float(h), p[2] = blue, p[3] = 1.0f;
        }
    return image;
}

std::string allMessages(const Problems& problems) {
    std::string all;
    for (const Problem& p : problems.items)
        all += p.toString() + "\n";
    return all;
}

/// Two albedo entries packed with padding, one moved afterwards; one normal entry.
AtlasSet sampleSet(const fs::path& pngSource) {
    AtlasSet set;
    AtlasDocument& albedo = set[AtlasKind::Albedo];
    albedo.padding = 2;
    AtlasEntry a;
    a.name = "weave";
    a.source = gradient(24, 16, 0.25f);
    AtlasEntry b;
    b.name = "from-file.png";
    b.file = pngSource.string();
    std::string error;
    if (!readImage(pngSource, b.source, &error))
        qFatal("%s", error.c_str());
    albedo.entries = {a, b};
    AtlasLayout layout;
    const std::vector<AtlasItemSize> sizes{{24, 16}, {b.source.width, b.source.height}};
    AtlasOptions options;
    options.padding = albedo.padding;
    if (!planAtlas(sizes, options, layout, &error))
        qFatal("%s", error.c_str());
    albedo.width = layout.width;
    albedo.height = layout.height;
    for (size_t i = 0; i < albedo.entries.size(); ++i)
        albedo.entries[i].region = layout.regions[i];
    albedo.entries[1].region.x = albedo.width - albedo.entries[1].region.width - 3; // dragged
    composeAtlas(albedo);
    AtlasDocument& normal = set[AtlasKind::Normal];
    normal.width = normal.height = 32;
    AtlasEntry n;
    n.name = "flat";
    n.source = gradient(8, 8, 1.0f);
    n.region = {4, 4, 16, 16}; // resized: stretched over twice its size
    normal.entries = {n};
    composeAtlas(normal);
    return set;
}

} // namespace

class TestCoreAtlasDocument : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() { QVERIFY(m_tmp.isValid()); }

    void saveLoadEqual() {
        const fs::path dir = m_tmp.path().toStdString();
        const fs::path png = dir / "textures" / "source.png";
        fs::create_directories(png.parent_path());
        std::string error;
        QVERIFY2(writeImage(png, gradient(10, 14, 0.0f), PixelFormat::UInt8, &error),
                 error.c_str());
        AtlasSet set = sampleSet(png);
        set[AtlasKind::Albedo].filePath = (dir / "exports" / "albedo.png").string();
        const AtlasSet before = set;
        const fs::path file = dir / "look.atlas.json";
        QVERIFY2(saveAtlasFile(set, file, &error), error.c_str());
        // In-memory sources now name the float EXR files written beside the document.
        QCOMPARE(QString::fromStdString(set[AtlasKind::Albedo].entries[0].file),
                 QString::fromStdString(
                     fs::absolute(dir / "look.albedo-0.exr").lexically_normal().generic_string()));
        QVERIFY(fs::exists(dir / "look.albedo-0.exr"));
        QVERIFY(fs::exists(dir / "look.normal-0.exr"));
        QCOMPARE(set[AtlasKind::Albedo].entries[1].file, png.string()); // file-backed: kept
        QVERIFY(!(set == before)); // the files are new; the pixels and regions are not
        const std::string text = *readWholeFile(file, 1 << 20, &error);
        QVERIFY2(text.find("\"file\": \"textures/source.png\"") != std::string::npos,
                 text.c_str()); // relative to the document
        QVERIFY(text.find("\"exported\": \"exports/albedo.png\"") != std::string::npos);

        Problems problems;
        const std::optional<AtlasSet> loaded = loadAtlasFile(file, problems);
        QVERIFY2(loaded, allMessages(problems).c_str());
        QVERIFY2(problems.items.empty(), allMessages(problems).c_str());
        QVERIFY(*loaded == set);
        for (int k = 0; k < kAtlasKindCount; ++k) {
            QCOMPARE((*loaded).atlases[size_t(k)].image.pixels,
                     before.atlases[size_t(k)].image.pixels); // composed again, same texels
            for (size_t i = 0; i < before.atlases[size_t(k)].entries.size(); ++i)
                QVERIFY((*loaded).atlases[size_t(k)].entries[i].source.pixels ==
                        before.atlases[size_t(k)].entries[i].source.pixels);
        }
        // Saving again writes the same text (nothing new to write).
        AtlasSet again = *loaded;
        QVERIFY2(saveAtlasFile(again, file, &error), error.c_str());
        QCOMPARE(*readWholeFile(file, 1 << 20, &error), text);
    }

    void problemsNameTheirJsonPath_data() {
        QTest::addColumn<QString>("json");
        QTest::addColumn<QString>("expected");
        QTest::newRow("newer") << R"({"format": "velvet.atlas", "version": 2, "atlases": {}})"
                               << "version: version 2 is newer than this Velvet reads (1)";
        QTest::newRow("format") << R"({"format": "velvet.scene", "version": 1, "atlases": {}})"
                                << "format: expected \"velvet.atlas\"";
        QTest::newRow("kind") << R"({"format": "velvet.atlas", "version": 1,
                                     "atlases": {"albdo": {}}})"
                              << "atlases.albdo: unknown key \"albdo\" (did you mean \"albedo\"?)";
        QTest::newRow("outside")
            << R"({"format": "velvet.atlas", "version": 1, "atlases": {"normal": {
                  "width": 16, "height": 16, "entries": [
                  {"file": "a.png", "region": [0, 0, 8, 8]},
                  {"file": "b.png", "region": [12, 0, 8, 8]}]}}})"
            << "atlases.normal.entries[1].region: the region [12, 0, 8, 8] does not fit in the "
               "16 x 16 atlas";
        QTest::newRow("fraction")
            << R"({"format": "velvet.atlas", "version": 1, "atlases": {"material": {
                  "width": 16, "height": 16, "entries": [
                  {"file": "a.png", "region": [0, 0.5, 8, 8]}]}}})"
            << "atlases.material.entries[0].region: expected 4 whole numbers";
        QTest::newRow("file") << R"({"format": "velvet.atlas", "version": 1, "atlases": {
                                     "albedo": {"width": 4, "height": 4, "entries": [
                                     {"region": [0, 0, 1, 1]}]}}})"
                              << "atlases.albedo.entries[0].file: required key is missing";
        QTest::newRow("padding") << R"({"format": "velvet.atlas", "version": 1, "atlases": {
                                        "albedo": {"width": 4, "height": 4, "padding": -1,
                                        "entries": []}}})"
                                 << "atlases.albedo.padding: ";
    }

    void problemsNameTheirJsonPath() {
        QFETCH(QString, json);
        QFETCH(QString, expected);
        Problems problems;
        const auto set = parseAtlasSet(json.toStdString(), "bad.atlas.json", {}, problems);
        const std::string all = allMessages(problems);
        QVERIFY(!set);
        QVERIFY2(all.find("bad.atlas.json: " + expected.toStdString()) != std::string::npos,
                 all.c_str());
    }

    void missingSourceIsAWarningAndKeepsTheEntry() {
        Problems problems;
        const auto set = parseAtlasSet(
            R"({"format": "velvet.atlas", "version": 1, "atlases": {"albedo": {
                "width": 8, "height": 8, "entries": [
                {"name": "gone", "file": "gone.png", "region": [1, 1, 4, 4]}]}}})",
            "x.atlas.json", m_tmp.path().toStdString(), problems);
        QVERIFY2(set, allMessages(problems).c_str());
        QVERIFY(!problems.hasErrors());
        QVERIFY(allMessages(problems).find("atlases.albedo.entries[0].file: source not read") !=
                std::string::npos);
        const AtlasEntry& e = (*set)[AtlasKind::Albedo].entries.at(0);
        QCOMPARE(e.region, (AtlasRegion{1, 1, 4, 4}));
        QVERIFY(e.source.empty());
        QCOMPARE(e.file,
                 (fs::path(m_tmp.path().toStdString()) / "gone.png").lexically_normal().string());
    }

    void sceneNamesItsAtlases() {
        const fs::path dir = m_tmp.path().toStdString();
        Scene scene = sceneWithMaterial(Material());
        scene.atlases = (dir / "look.atlas.json").string();
        const std::string text = sceneToJson(scene, dir);
        QVERIFY(text.find("\"atlases\": \"look.atlas.json\"") != std::string::npos);
        QVERIFY(text.find("\"version\": 2") != std::string::npos);
        Problems problems;
        const auto loaded = parseScene(text, "s.json", dir, problems);
        QVERIFY2(loaded, allMessages(problems).c_str());
        QCOMPARE(loaded->atlases, scene.atlases);
        // Version 1 had no atlases: it still loads, and the key is not allowed there.
        Problems v1;
        QVERIFY(parseScene(R"({"format": "velvet.scene", "version": 1})", "v1.json", dir, v1));
        QVERIFY(!v1.hasErrors());
        Problems v1Atlases;
        QVERIFY(!parseScene(R"({"format": "velvet.scene", "version": 1, "atlases": "a.json"})",
                            "v1.json", dir, v1Atlases));
    }

    void exportWritesEveryNonEmptyAtlas() {
        const fs::path dir = fs::path(m_tmp.path().toStdString()) / "export";
        fs::create_directories(dir);
        const fs::path png = dir / "src.png";
        std::string error;
        QVERIFY(writeImage(png, gradient(6, 6, 0.5f), PixelFormat::UInt8, &error));
        const AtlasSet set = sampleSet(png);
        std::vector<fs::path> written;
        QVERIFY2(exportAtlasImages(set, dir, "look", "png", &written, &error), error.c_str());
        QCOMPARE(written.size(), size_t(2)); // albedo and normal; the material atlas is empty
        QCOMPARE(written[0], dir / "look-albedo.png");
        QCOMPARE(written[1], dir / "look-normal.png");
        ImageInfo info;
        QVERIFY(readImageInfo(written[1], info, &error));
        QCOMPARE(info.bitsPerSample, 16); // data atlases keep 16 bits
        QCOMPARE(info.width, set[AtlasKind::Normal].width);
        Image back;
        QVERIFY(readImage(written[0], back, &error));
        QCOMPARE(back.width, set[AtlasKind::Albedo].width);
        QVERIFY(!exportAtlasImages(AtlasSet{}, dir, "none", "png", nullptr, &error));
    }

    void schemaFileIsGenerated() {
        const fs::path file = fs::path(VELVET_SOURCE_DIR) / "resources/schemas/atlas.schema.json";
        const std::string generated = atlasJsonSchema();
        const std::string problem = test::checkShippedSchema(file, generated);
        QVERIFY2(problem.empty(), problem.c_str());
    }

private:
    QTemporaryDir m_tmp;
};

QTEST_GUILESS_MAIN(TestCoreAtlasDocument)
#include "test_core_atlas_document.moc"
