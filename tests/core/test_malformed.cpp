// Proves every kind of bad document is refused with a message that says where and what, that
// loading is all-or-nothing, and that hostile input (huge, deep, binary) costs neither a crash nor
// a hang. The inputs are real files in tests/data/malformed/; the very large and very deep ones
// are generated at test time rather than committed.
#include "core/document_io.h"

#include <QTemporaryDir>
#include <QtTest>
#include <filesystem>
#include <fstream>

using namespace velvet;
namespace fs = std::filesystem;

namespace {

const fs::path kMalformed = fs::path(VELVET_TEST_DATA) / "malformed";

std::string problemsText(const Problems& p) {
    std::string out;
    for (const Problem& item : p.items)
        out += item.toString() + "\n";
    return out;
}

/// Loads @p file as a scene when its name says so, else as a material; true when a model came
/// back.
bool load(const fs::path& file, Problems& problems) {
    if (file.filename().string().starts_with("scene_"))
        return loadSceneFile(file, problems).has_value();
    return loadMaterialFile(file, problems).has_value();
}

} // namespace

class TestMalformed : public QObject {
    Q_OBJECT
private slots:
    void refused_data() {
        QTest::addColumn<QString>("file");
        QTest::addColumn<QString>("expected");
        auto row = [](const char* file, const char* expected) {
            QTest::newRow(file) << QString(file) << QString::fromUtf8(expected);
        };
        row("truncated.json", "invalid JSON at line 5, column");
        row("truncated.json", "unexpected end of input");
        row("wrong_type.json", "lobes.base.roughness: expected a number in [0, 1], got \"high\"");
        row("out_of_range.json", "lobes.base.metallic: expected a number in [0, 1], got 1.5");
        row("nan.json", "NaN and Infinity are not numbers in JSON");
        row("nan.json", "lobes.base.roughness: invalid JSON at line 3");
        row("infinity.json", "NaN and Infinity are not numbers in JSON");
        row("overflow.json", "lobes.base.roughness: the number 1e999 is out of range");
        row("missing_format.json", "format: required key is missing");
        row("missing_version.json", "version: required key is missing");
        row("missing_name.json", "name: required key is missing");
        row("unknown_version.json",
            "version: version 3 is newer than this Velvet reads (2); update Velvet");
        row("version_string.json", "version: expected an integer in [1, 2], got \"2\"");
        row("version_negative.json", "version: expected an integer in [1, 2], got -1");
        row("version_fraction.json", "version: expected an integer in [1, 2], got 1.5");
        row("wrong_format.json", "format: expected \"velvet.material\", got \"velvet.scene\"");
        row("unknown_key.json",
            "lobes.base.rougness: unknown key \"rougness\" (did you mean \"roughness\"?)");
        row("color_two_numbers.json",
            "lobes.base.color: expected an array of 3 numbers, got an array of 2 items");
        row("bad_enum.json", "brdf.distribution: expected one of \"ggx\", \"beckmann\" or "
                             "\"blinn-phong\", got \"ggxx\" (did you mean \"ggx\"?)");
        row("not_an_object.json", "expected a material object, got an array of 3 items");
        row("duplicate_key.json", "lobes.base.roughness: duplicate key \"roughness\"");
        row("trailing_garbage.json", "invalid JSON at line 4, column 1");
        row("nested_arrays.json", "nesting deeper than 64 levels");
        row("bad_region.json", "textures.baseColor.region[2]: expected an integer in [1, ");
        row("many_errors.json", "lobes.sheen.weight: expected a number in [0, 1], got null");
        row("many_errors.json", "lobes.base.color[2]: expected a number in [0, 1], got 2");
        row("empty.json", "the file is empty");
        row("binary_garbage.bin", "not a UTF-8 text file (binary data: byte 0x89 at line 1, "
                                  "column 1)");
        row("scene_bad_lights.json", "lights[0].type: expected one of \"directional\", \"point\"");
        row("scene_bad_lights.json", "lights[1].innerCone: the inner cone (40°) must not be "
                                     "wider than the outer cone (30°)");
        row("scene_bad_lights.json",
            "lights[2].intensity: expected a number in [0, 1e+06], got -2");
        row("scene_camera.json", "camera.fovY: expected a number in (1, 179), got 0.5");
        row("scene_camera.json", "camera.distance: expected a number in [1e-04, 1e+06], got -1");
        row("scene_inline_material.json",
            "material.lobes.base.roughness: expected a number in [0, 1], got \"high\"");
        row("scene_bad_enum.json", "environment.background: expected one of");
        row("scene_bad_enum.json", "(did you mean \"blurred\"?)");
        row("scene_bad_enum.json", "mesh.kind: expected one of");
        row("scene_is_material.json", "format: expected \"velvet.scene\", got \"velvet.material\" "
                                      "(this is a material preset, not a scene)");
    }

    void refused() {
        QFETCH(QString, file);
        QFETCH(QString, expected);
        const fs::path path = kMalformed / file.toStdString();
        QVERIFY2(fs::exists(path), path.string().c_str());
        Problems problems;
        QVERIFY(!load(path, problems));
        QVERIFY(problems.hasErrors());
        const std::string text = problemsText(problems);
        QVERIFY2(text.find(expected.toStdString()) != std::string::npos,
                 ("expected \"" + expected.toStdString() + "\" in:\n" + text).c_str());
        // Every problem names the file it is about.
        for (const Problem& p : problems.items)
            QCOMPARE(p.file, path.string());
    }

    void everyProblemIsReported() {
        Problems problems;
        QVERIFY(!load(kMalformed / "many_errors.json", problems));
        QCOMPARE(static_cast<int>(problems.items.size()), 4);
        Problems scene;
        QVERIFY(!load(kMalformed / "scene_bad_lights.json", scene));
        QCOMPARE(static_cast<int>(scene.items.size()), 3);
    }

    void deepNestingDoesNotOverflowTheStack() {
        QTemporaryDir tmp;
        const fs::path file = fs::path(tmp.path().toStdString()) / "deep.json";
        {
            std::ofstream out(file, std::ios::binary);
            out << std::string(100000, '[') << std::string(100000, ']');
        }
        Problems problems;
        QVERIFY(!loadMaterialFile(file, problems));
        QVERIFY2(problemsText(problems).find("nesting deeper than 64 levels") != std::string::npos,
                 problemsText(problems).c_str());
        QCOMPARE(detectDocumentKind(file), DocumentKind::Unknown);
        // Unbalanced: only opening brackets.
        std::ofstream(file, std::ios::binary | std::ios::trunc) << std::string(100000, '{');
        Problems again;
        QVERIFY(!loadSceneFile(file, again));
        QVERIFY(again.hasErrors());
    }

    void hugeFileRefusedBeforeReading() {
        QTemporaryDir tmp;
        const fs::path file = fs::path(tmp.path().toStdString()) / "huge.json";
        {
            std::ofstream out(file, std::ios::binary);
            const std::string chunk(1 << 20, ' ');
            out << "{\"format\": \"velvet.material\"";
            for (int i = 0; i < 50; ++i)
                out << chunk;
            out << "}";
        }
        QVERIFY(fs::file_size(file) > 50u * 1024u * 1024u);
        Problems problems;
        QVERIFY(!loadMaterialFile(file, problems));
        const std::string text = problemsText(problems);
        QVERIFY2(text.find("huge.json: is 50.0 MB") != std::string::npos, text.c_str());
        QVERIFY2(text.find("more than the 16.0 MB limit") != std::string::npos, text.c_str());
        QCOMPARE(detectDocumentKind(file), DocumentKind::Unknown);
    }

    void unreadableFiles() {
        QTemporaryDir tmp;
        const fs::path dir = tmp.path().toStdString();
        Problems problems;
        QVERIFY(!loadMaterialFile(dir / "absent.json", problems));
        QVERIFY(problemsText(problems).find("absent.json: no such file") != std::string::npos);
        QVERIFY(!loadSceneFile(dir, problems));
        QVERIFY(problemsText(problems).find("is a folder") != std::string::npos);
    }

    void missingTextureIsAWarning() {
        QTemporaryDir tmp;
        const fs::path file = fs::path(tmp.path().toStdString()) / "m.json";
        std::ofstream(file) << R"({"format": "velvet.material", "version": 2, "name": "T",
            "textures": {"baseColor": {"file": "missing/albedo.png"}}})";
        Problems problems;
        const auto m = loadMaterialFile(file, problems);
        QVERIFY2(m.has_value(), problemsText(problems).c_str());
        QCOMPARE(problems.items.size(), size_t(1));
        QCOMPARE(problems.items[0].severity, Problem::Severity::Warning);
        QCOMPARE(problems.items[0].path, std::string("textures.baseColor.file"));
        QVERIFY(!problems.hasErrors());
        QCOMPARE(m->texture(TextureSlot::BaseColor).file,
                 (file.parent_path().lexically_normal() / "missing/albedo.png").generic_string());
    }

    void missingHdriIsAWarning() {
        Problems problems;
        const auto s = parseScene(R"({"format": "velvet.scene", "version": 1,
            "environment": {"hdri": "/no/such/sky.exr"}})",
                                  "s.json", {}, problems);
        QVERIFY2(s.has_value(), problemsText(problems).c_str());
        QCOMPARE(problems.items.size(), size_t(1));
        QCOMPARE(problems.items[0].toString().substr(0, 24),
                 std::string("s.json: environment.hdri"));
        QVERIFY(!problems.hasErrors());
    }

    void problemToString() {
        QCOMPARE((Problem{Problem::Severity::Error, "a.json", "x.y", "bad"}).toString(),
                 std::string("a.json: x.y: bad"));
        QCOMPARE((Problem{Problem::Severity::Error, "", "x.y", "bad"}).toString(),
                 std::string("x.y: bad"));
        QCOMPARE((Problem{Problem::Severity::Error, "a.json", "", "bad"}).toString(),
                 std::string("a.json: bad"));
    }
};

QTEST_APPLESS_MAIN(TestMalformed)
#include "test_malformed.moc"
