// The CLI's contract (DESIGN.md): exit codes 0 success, 1 usage error, 2 bad input (one line per
// problem on stderr, nothing written), 3 rendering failure; no crash and no hang on any input.
// Runs the real `velvet` binary on real files.
#include "core/image.h"
#include "run_velvet.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace {

using velvet::test::Result;

/// Runs velvet with no display (the CLI must not need one) and a time limit (no hang).
Result runVelvet(const QStringList& args, const QString& workingDir = {},
                 const QString& resources = {}) {
    velvet::test::RunOptions options;
    options.workingDir = workingDir;
    options.timeoutMs = 120000;
    if (!resources.isEmpty())
        options.extraEnv.insert("VELVET_RESOURCES", resources);
    return velvet::test::runVelvet(args, options);
}

QString data(const QString& rel) {
    return QStringLiteral(VELVET_TEST_DATA "/") + rel;
}
QString source(const QString& rel) {
    return QStringLiteral(VELVET_SOURCE_DIR "/") + rel;
}

/// Largest distance between two colours at the same pixel; infinity when the sizes differ.
float maxDifference(const velvet::Image& a, const velvet::Image& b) {
    if (a.width != b.width || a.height != b.height)
        return INFINITY;
    float d = 0.0f;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            d = std::max(d, glm::length(glm::vec3(a.rgba(x, y)) - glm::vec3(b.rgba(x, y))));
    return d;
}

} // namespace

class TestAppCli : public QObject {
    Q_OBJECT
private slots:
    void helpForEveryCommand_data() {
        QTest::addColumn<QStringList>("args");
        QTest::newRow("top") << QStringList{"--help"};
        for (const char* c : {"render", "validate", "info", "schema", "export"})
            QTest::newRow(c) << QStringList{c, "--help"};
    }
    void helpForEveryCommand() {
        QFETCH(QStringList, args);
        Result r = runVelvet(args);
        QCOMPARE(r.status, QProcess::NormalExit);
        QCOMPARE(r.exitCode, 0);
        QVERIFY2(r.out.contains("Usage"), qPrintable(r.out));
    }

    void usageErrors_data() {
        QTest::addColumn<QStringList>("args");
        QTest::newRow("render without -o") << QStringList{"render"};
        QTest::newRow("unknown option") << QStringList{"render", "-o", "x.png", "--frobnicate"};
        QTest::newRow("bad size") << QStringList{"render", "-o", "x.png", "--size", "12by4"};
        QTest::newRow("zero size") << QStringList{"render", "-o", "x.png", "--size", "0x10"};
        QTest::newRow("huge size") << QStringList{"render", "-o", "x.png", "--size", "90000x10"};
        QTest::newRow("bad extension") << QStringList{"render", "-o", "x.bmpx"};
        QTest::newRow("bad tonemap") << QStringList{"render", "-o", "x.png", "--tonemap", "warm"};
        QTest::newRow("bad debug view")
            << QStringList{"render", "-o", "x.png", "--debug-view", "shiny"};
        QTest::newRow("unknown OCIO view")
            << QStringList{"render", "-o", "x.png", "--view", "Nope"};
        QTest::newRow("unknown OCIO display")
            << QStringList{"render", "-o", "x.png", "--display", "CRT"};
        QTest::newRow("unknown OCIO look")
            << QStringList{"render", "-o", "x.png", "--look", "Teal"};
        QTest::newRow("tonemap with OCIO view")
            << QStringList{"render", "-o", "x.png", "--view", "ACES", "--tonemap", "aces"};
        QTest::newRow("bad time") << QStringList{"render", "-o", "x.png", "--time", "noon"};
        QTest::newRow("negative time") << QStringList{"render", "-o", "x.png", "--time", "-1"};
        QTest::newRow("infinite time") << QStringList{"render", "-o", "x.png", "--time", "inf"};
        QTest::newRow("option without value") << QStringList{"render", "-o"};
        QTest::newRow("two files") << QStringList{"render", "a.json", "b.json", "-o", "x.png"};
        QTest::newRow("validate nothing") << QStringList{"validate"};
        QTest::newRow("schema of what") << QStringList{"schema", "texture"};
        QTest::newRow("unknown editor option") << QStringList{"--frobnicate"};
    }
    void usageErrors() {
        QFETCH(QStringList, args);
        QTemporaryDir dir; // a wrongly accepted command would write x.png here
        Result r = runVelvet(args, dir.path());
        QCOMPARE(r.status, QProcess::NormalExit);
        QCOMPARE(r.exitCode, 1);
        QVERIFY(!r.err.isEmpty());
        QVERIFY(QDir(dir.path()).isEmpty());
    }

    /// Every malformed file in the corpus: exit 2 from validate and from render, a message that
    /// names the file, and no output written.
    void malformedFilesAreBadInput_data() {
        QTest::addColumn<QString>("file");
        const QDir dir(data("malformed"));
        const auto files = dir.entryInfoList(QDir::Files, QDir::Name);
        QVERIFY2(files.size() >= 15, "the malformed corpus should hold at least 15 files");
        for (const QFileInfo& f : files) {
            // A valid preset that is malformed only where a scene is expected (a core test).
            if (f.fileName() == "scene_is_material.json")
                continue;
            QTest::newRow(qPrintable(f.fileName())) << f.absoluteFilePath();
        }
        QTest::newRow("missing file") << data("malformed/does-not-exist.json");
    }
    void malformedFilesAreBadInput() {
        QFETCH(QString, file);
        Result v = runVelvet({"validate", file});
        QCOMPARE(v.status, QProcess::NormalExit);
        QCOMPARE(v.exitCode, 2);
        QVERIFY2(v.err.contains(QFileInfo(file).fileName()), qPrintable(v.err));

        QTemporaryDir dir;
        const QString out = dir.filePath("out.png");
        Result r = runVelvet({"render", file, "-o", out, "--size", "16x16"});
        QCOMPARE(r.status, QProcess::NormalExit);
        QCOMPARE(r.exitCode, 2);
        QVERIFY(!r.err.isEmpty());
        QVERIFY2(QDir(dir.path()).isEmpty(), "bad input must write nothing");
    }

    /// --timings (issue 16): every phase of the render on stderr, in milliseconds, each below the
    /// total, and the image still written.
    void renderTimingsNameEveryPhase() {
        QTemporaryDir dir;
        const QString out = dir.filePath("t.png");
        Result r = runVelvet({"render", "-o", out, "--size", "32x32", "--timings"});
        QCOMPARE(r.exitCode, 0);
        QVERIFY(QFileInfo::exists(out));
        QVERIFY2(r.out.isEmpty(), qPrintable(r.out)); // stdout stays clean for scripts
        double total = -1;
        QMap<QString, double> phases;
        for (const QString& line : r.err.split('\n')) {
            const int at = line.lastIndexOf(' ');
            if (!line.startsWith("  ") || at < 0)
                continue;
            phases[line.left(at).trimmed()] = line.mid(at + 1).toDouble();
        }
        total = phases.value("total", -1);
        QVERIFY2(total > 0, qPrintable(r.err));
        for (const char* phase : {"start-up (to main)", "context", "renderer", "scene upload",
                                  "environment bake", "frame", "read back", "write"}) {
            QVERIFY2(phases.contains(phase), qPrintable(QString(phase) + " missing:\n" + r.err));
            QVERIFY(phases[phase] >= 0 && phases[phase] <= total);
        }
    }

    void outputFolderMissingIsBadInput() {
        Result r = runVelvet({"render", "-o", "/nonexistent-velvet-dir/out.png", "--size", "8x8"});
        QCOMPARE(r.exitCode, 2);
        QVERIFY(r.err.contains("does not exist"));
    }

    /// A shader that does not compile is a rendering failure: exit 3, the message names the shader
    /// file and line, and no image is written.
    void brokenShaderIsRenderingFailure() {
        QTemporaryDir resources, out;
        QVERIFY(QProcess::execute("cp", {"-r", source("resources/."), resources.path()}) == 0);
        QFile shader(resources.filePath("shaders/lighting.frag"));
        QVERIFY(shader.open(QIODevice::Append));
        shader.write("\nthis is not GLSL;\n");
        shader.close();
        const QString image = out.filePath("x.png");
        Result r = runVelvet({"render", "-o", image, "--size", "16x16"}, {}, resources.path());
        QCOMPARE(r.status, QProcess::NormalExit);
        QCOMPARE(r.exitCode, 3);
        QVERIFY2(r.err.contains("lighting.frag:"), qPrintable(r.err));
        QVERIFY(!QFileInfo::exists(image));
    }

    void validateShippedPresets() {
        const auto files = QDir(source("resources/presets")).entryInfoList({"*.json"}, QDir::Files);
        QVERIFY(files.size() >= 12);
        QStringList args{"validate"};
        for (const QFileInfo& f : files)
            args << f.absoluteFilePath();
        Result r = runVelvet(args);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(r.out.count(": ok"), files.size());
    }

    void validateMixedFilesReportsEachAndFails() {
        const QString good = source("resources/presets/crimson_velvet.json");
        const auto bad = QDir(data("malformed")).entryInfoList(QDir::Files, QDir::Name);
        QVERIFY(!bad.isEmpty());
        Result r = runVelvet({"validate", good, bad.first().absoluteFilePath()});
        QCOMPARE(r.exitCode, 2);
        QVERIFY(r.out.contains("crimson_velvet.json: ok"));
        QVERIFY(r.err.contains(bad.first().fileName()));
    }

    /// The default scene renders headless to a PNG that is not blank.
    void renderDefaultScenePng() {
        QTemporaryDir dir;
        const QString out = dir.filePath("default.png");
        Result r = runVelvet({"render", "-o", out, "--size", "64x48"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        velvet::Image image;
        std::string error;
        QVERIFY2(velvet::readImage(out.toStdString(), image, &error), error.c_str());
        QCOMPARE(image.width, 64);
        QCOMPARE(image.height, 48);
        // Not blank: the sphere in the middle differs from the corner, and pixels vary.
        const glm::vec4 centre = image.rgba(32, 24), corner = image.rgba(1, 1);
        QVERIFY(glm::length(glm::vec3(centre) - glm::vec3(corner)) > 0.05f);
        float minV = 1, maxV = 0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                minV = std::min(minV, image.rgba(x, y).r);
                maxV = std::max(maxV, image.rgba(x, y).r);
            }
        QVERIFY(maxV - minV > 0.2f);
    }

    /// --display/--view/--look choose OpenColorIO's display transform; an unknown name is a usage
    /// error whose message lists the valid names, and nothing is written.
    void renderWithOcioView() {
        QTemporaryDir dir;
        const QString out = dir.filePath("aces.png");
        Result r = runVelvet({"render", "-o", out, "--view", "ACES", "--size", "32x32"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        velvet::Image image;
        std::string error;
        QVERIFY2(velvet::readImage(out.toStdString(), image, &error), error.c_str());
        QCOMPARE(image.width, 32);

        const QString p3 = dir.filePath("p3.png");
        r = runVelvet({"render", "-o", p3, "--display", "Display P3", "--look",
                       "ACES Blue Light Fix", "--exposure", "0.5", "--size", "16x16"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY(QFileInfo::exists(p3));

        const QString bad = dir.filePath("bad.png");
        r = runVelvet({"render", "-o", bad, "--view", "Nope", "--size", "16x16"});
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains("Nope") && r.err.contains("\"Standard\"") &&
                     r.err.contains("\"AgX\""),
                 qPrintable(r.err));
        QVERIFY(!QFileInfo::exists(bad));
    }

    /// --tonemap with a look (and the default, encoding-only view) blames the look, not the view;
    /// with a tone-mapping view, the view.
    void tonemapConflictNamesTheReason() {
        QTemporaryDir dir;
        Result r = runVelvet(
            {"render", "-o", "x.png", "--tonemap", "aces", "--look", "ACES Blue Light Fix"},
            dir.path());
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains("--look (\"ACES Blue Light Fix\")"), qPrintable(r.err));
        QVERIFY2(!r.err.contains("--view"), qPrintable(r.err));
        r = runVelvet({"render", "-o", "x.png", "--tonemap", "aces", "--view", "AgX"}, dir.path());
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains("--view (\"AgX\")") && !r.err.contains("--look"),
                 qPrintable(r.err));
        QVERIFY(QDir(dir.path()).isEmpty());
    }

    /// A config without an encoding view (OCIO v1 has no view transforms; a v2 config may lack
    /// default_view_transform) still renders: the built-in curve is encoded with the hand-written
    /// sRGB curve, which equals the shipped config's OCIO encoding, and one warning names the
    /// config file and the resolved default display.
    void renderWithConfigWithoutEncodingView_data() {
        QTest::addColumn<QString>("config");
        QTest::newRow("OCIO v1") << R"(ocio_profile_version: 1
roles:
  default: linear
  scene_linear: linear
displays:
  Monitor:
    - !<View> {name: Gamma, colorspace: gamma}
colorspaces:
  - !<ColorSpace>
    name: linear
  - !<ColorSpace>
    name: gamma
    from_reference: !<ExponentTransform> {value: [0.4545, 0.4545, 0.4545, 1]}
)";
        QTest::newRow("v2 without default_view_transform") << R"(ocio_profile_version: 2
roles:
  default: linear
  scene_linear: linear
  data: linear
displays:
  Monitor:
    - !<View> {name: Gamma, view_transform: Curve, display_colorspace: screen}
view_transforms:
  - !<ViewTransform>
    name: Curve
    from_scene_reference: !<ExponentTransform> {value: [0.4545, 0.4545, 0.4545, 1]}
display_colorspaces:
  - !<ColorSpace>
    name: screen
colorspaces:
  - !<ColorSpace>
    name: linear
)";
    }
    void renderWithConfigWithoutEncodingView() {
        QFETCH(QString, config);
        QTemporaryDir dir;
        const QString configPath = dir.filePath("no-encoding-view.ocio");
        QFile file(configPath);
        QVERIFY(file.open(QIODevice::WriteOnly));
        file.write(config.toUtf8());
        file.close();

        const QString reference = dir.filePath("shipped.png");
        Result r = runVelvet({"render", "-o", reference, "--size", "32x32"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));

        const QString out = dir.filePath("fallback.png");
        velvet::test::RunOptions options;
        options.extraEnv.insert("OCIO", configPath);
        r = velvet::test::runVelvet({"render", "-o", out, "--size", "32x32"}, options);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(r.err.count("warning"), 1);
        QVERIFY2(r.err.contains(configPath) && r.err.contains("\"Monitor\"") &&
                     r.err.contains("sRGB curve"),
                 qPrintable(r.err));
        velvet::Image expected, image;
        std::string error;
        QVERIFY2(velvet::readImage(reference.toStdString(), expected, &error), error.c_str());
        QVERIFY2(velvet::readImage(out.toStdString(), image, &error), error.c_str());
        QVERIFY(maxDifference(image, expected) <= 1.5f / 255.0f);
    }

    /// A preset renders in the default scene; EXR output is linear half float.
    void renderPresetExr() {
        QTemporaryDir dir;
        const QString out = dir.filePath("gold.exr");
        Result r = runVelvet(
            {"render", source("resources/presets/gold.json"), "-o", out, "--size", "32x32"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        velvet::Image image;
        std::string error;
        QVERIFY2(velvet::readImage(out.toStdString(), image, &error), error.c_str());
        QCOMPARE(image.width, 32);
        // Gold reflects more red than blue at the sphere's centre.
        const glm::vec4 c = image.rgba(16, 16);
        QVERIFY2(c.r > c.b, qPrintable(QString("r=%1 b=%2").arg(c.r).arg(c.b)));
    }

    /// --time sets the animation time: the painterly chain's strokes change between two times
    /// (they change every 4 s) and are identical for the same time.
    void renderTimeAnimatesPainterly() {
        QTemporaryDir dir;
        const QString chain = source("resources/post-chains/painterly.json");
        auto render = [&](const QString& name, const QString& time) {
            const QString out = dir.filePath(name);
            Result r = runVelvet(
                {"render", "-o", out, "--size", "48x48", "--chain", chain, "--time", time});
            velvet::Image image;
            std::string error;
            if (r.exitCode != 0 || !velvet::readImage(out.toStdString(), image, &error))
                qWarning("render --time %s: %s %s", qPrintable(time), qPrintable(r.err),
                         error.c_str());
            return image;
        };
        const velvet::Image a = render("a.png", "0.5"), again = render("again.png", "0.5");
        const velvet::Image later = render("later.png", "9.5");
        QCOMPARE(a.width, 48);
        QCOMPARE(again.width, 48);
        QCOMPARE(later.width, 48);
        QCOMPARE(maxDifference(a, again), 0.0f);
        const float d = maxDifference(a, later);
        QVERIFY2(d > 0.05f, qPrintable(QString::number(d)));
        QVERIFY(runVelvet({"render", "--help"}).out.contains("--time"));
    }

    /// --chain replaces the scene's chain: the toon preset gives another image than the default
    /// scene's own chain; a malformed chain file is bad input naming the file, nothing written.
    void renderWithChainFile() {
        QTemporaryDir dir;
        const QString plain = dir.filePath("plain.png"), toon = dir.filePath("toon.png");
        Result r = runVelvet({"render", "-o", plain, "--size", "48x48"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        r = runVelvet({"render", "-o", toon, "--size", "48x48", "--chain",
                       source("resources/post-chains/toon.json")});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        velvet::Image a, b;
        std::string error;
        QVERIFY2(velvet::readImage(plain.toStdString(), a, &error), error.c_str());
        QVERIFY2(velvet::readImage(toon.toStdString(), b, &error), error.c_str());
        const float d = maxDifference(a, b);
        QVERIFY2(d > 0.1f, qPrintable(QString::number(d)));

        QTemporaryDir bad;
        const QString chain = bad.filePath("broken_chain.json");
        QFile f(chain);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(R"({"format": "velvet.post-chain", "version": 1, "effects": [{"type": )");
        f.close();
        const QString out = dir.filePath("never.png");
        r = runVelvet({"render", "-o", out, "--size", "16x16", "--chain", chain});
        QCOMPARE(r.status, QProcess::NormalExit);
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("broken_chain.json"), qPrintable(r.err));
        QVERIFY(!QFileInfo::exists(out));
    }

    void debugViewsAndLightRigsRender() {
        QTemporaryDir dir;
        const auto render = [&](const QString& name, const QStringList& extra) {
            const QString out = dir.filePath(name);
            Result r = runVelvet(QStringList{"render", "-o", out, "--size", "40x40"} + extra);
            velvet::Image image;
            std::string error;
            if (r.exitCode != 0 || !velvet::readImage(out.toStdString(), image, &error))
                qWarning("%s: %s %s", qPrintable(name), qPrintable(r.err), error.c_str());
            return image;
        };
        const velvet::Image final = render("final.png", {});
        const velvet::Image normal = render("normal.png", {"--debug-view", "normal"});
        // `--view NAME` with a debug view's name is that debug view (the OCIO views are
        // capitalised), the same image as --debug-view.
        const velvet::Image viaView = render("normal_view.png", {"--view", "normal"});
        QVERIFY(normal.width == 40 && viaView.width == 40);
        QCOMPARE(maxDifference(normal, viaView), 0.0f);
        QVERIFY(maxDifference(final, normal) > 0.1f);
        // The centre of the sphere faces the camera (+Z): the normal view shows (0.5, 0.5, 1)
        // encoded, blue highest.
        const glm::vec4 c = normal.rgba(20, 20);
        QVERIFY2(c.b > c.r && c.b > c.g,
                 qPrintable(QStringLiteral("%1 %2 %3").arg(c.r).arg(c.g).arg(c.b)));

        // A light rig replaces the lights: the environment alone is darker than the key light.
        const velvet::Image envOnly = render("env.png", {"--light-rig", "environment"});
        const velvet::Image sun = render("sun.png", {"--light-rig", "sun"});
        QVERIFY(maxDifference(final, envOnly) > 0.05f);
        QVERIFY(maxDifference(envOnly, sun) > 0.05f);
        Result bad = runVelvet({"render", "-o", dir.filePath("x.png"), "--light-rig", "disco"});
        QCOMPARE(bad.exitCode, 1);
        QVERIFY2(bad.err.contains("--light-rig") && bad.err.contains("disco"), qPrintable(bad.err));
        QVERIFY(!QFileInfo::exists(dir.filePath("x.png")));
    }

    void infoReportsHeadlessGl() {
        Result r = runVelvet({"info"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err + r.out));
        QVERIFY(r.out.contains("OpenGL"));
        QVERIFY(r.out.contains("version:"));
        QVERIFY(r.out.contains("OpenImageIO"));
    }

    void schemaMatchesShippedFile() {
        for (const QString kind : {"material", "scene", "post-chain"}) {
            Result r = runVelvet({"schema", kind});
            QCOMPARE(r.exitCode, 0);
            QFile shipped(source("resources/schemas/" + kind + ".schema.json"));
            QVERIFY(shipped.open(QIODevice::ReadOnly));
            QCOMPARE(r.out, QString::fromUtf8(shipped.readAll()));
        }
    }
};

QTEST_GUILESS_MAIN(TestAppCli)
#include "test_app_cli.moc"
