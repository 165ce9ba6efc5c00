// `velvet render` and the prefiltered environment cache (issue 16, "a preview image in one
// second"): the second render of a scene takes the environment from the disk cache, decodes no
// HDRI and never loads the image codec (OpenImageIO) to write its PNG, and draws the same
// pixels as the first and as a render with caching off; a truncated entry is rebuilt with a
// warning; a changed HDRI gets an entry of its own.
#include "core/default_stage.h"
#include "core/document_io.h"
#include "core/image.h"
#include "core/resources.h"
#include "run_velvet.h"

#include <QDir>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <filesystem>

namespace {

namespace fs = std::filesystem;

struct Env {
    QTemporaryDir dir;
    QMap<QString, QString> vars() const {
        return {{"HOME", dir.path()},
                {"XDG_CACHE_HOME", dir.filePath("xdg")},
                {"VELVET_CACHE_DIR", dir.filePath("cache")}};
    }
    QStringList entries() const {
        return QDir(dir.filePath("cache/environments")).entryList({"*.ibl"}, QDir::Files);
    }
};

velvet::test::Result render(const Env& env, const QStringList& args,
                            const QMap<QString, QString>& more = {}) {
    velvet::test::RunOptions options;
    options.extraEnv = env.vars();
    for (auto it = more.begin(); it != more.end(); ++it)
        options.extraEnv.insert(it.key(), it.value());
    return velvet::test::runVelvet(QStringList{"render"} + args, options);
}

/// Largest difference of any channel of two images of the same size (1 when sizes differ).
float maxDifference(const QString& a, const QString& b) {
    velvet::Image ia, ib;
    std::string error;
    if (!velvet::readImage(a.toStdString(), ia, &error) ||
        !velvet::readImage(b.toStdString(), ib, &error) || ia.width != ib.width ||
        ia.height != ib.height || ia.pixels.size() != ib.pixels.size())
        return 1.0f;
    float worst = 0.0f;
    for (size_t i = 0; i < ia.pixels.size(); ++i)
        worst = std::max(worst, std::abs(ia.pixels[i] - ib.pixels[i]));
    return worst;
}

} // namespace

class TestAppRenderCache : public QObject {
    Q_OBJECT
private slots:
    void secondRenderSkipsDecodeAndBake() {
        Env env;
        const QStringList size{"--size", "96x64", "--timings"};
        const auto first = render(env, QStringList{"-o", env.dir.filePath("a.png")} + size);
        QVERIFY2(first.exitCode == 0, qPrintable(first.err));
        QCOMPARE(env.entries().size(), 1);
        // The first render decoded the EXR: the codec was loaded then.
        QVERIFY2(first.err.contains(QRegularExpression("image codec \\(OpenImageIO\\) +loaded")),
                 qPrintable(first.err));

        const auto second = render(env, QStringList{"-o", env.dir.filePath("b.png")} + size);
        QVERIFY2(second.exitCode == 0, qPrintable(second.err));
        QVERIFY2(
            second.err.contains(QRegularExpression("image codec \\(OpenImageIO\\) +not loaded")),
            qPrintable(second.err));
        QCOMPARE(env.entries().size(), 1);
        // The same texels (the equirect and cube as the GPU held them): the same image.
        QCOMPARE(maxDifference(env.dir.filePath("a.png"), env.dir.filePath("b.png")), 0.0f);

        // Caching off: the same image again, and nothing new in the cache.
        const auto off = render(env, QStringList{"-o", env.dir.filePath("c.png")} + size,
                                {{"VELVET_NO_CACHE", "1"}});
        QVERIFY2(off.exitCode == 0, qPrintable(off.err));
        QCOMPARE(maxDifference(env.dir.filePath("a.png"), env.dir.filePath("c.png")), 0.0f);
        QCOMPARE(env.entries().size(), 1);
    }

    void truncatedEntryIsRebuiltWithAWarning() {
        Env env;
        const QStringList size{"--size", "64x48"};
        const auto first = render(env, QStringList{"-o", env.dir.filePath("a.png")} + size);
        QVERIFY2(first.exitCode == 0, qPrintable(first.err));
        QCOMPARE(env.entries().size(), 1);
        const fs::path entry =
            env.dir.filePath("cache/environments/" + env.entries()[0]).toStdString();
        const auto full = fs::file_size(entry);
        fs::resize_file(entry, full / 3);

        const auto second = render(env, QStringList{"-o", env.dir.filePath("b.png")} + size);
        QVERIFY2(second.exitCode == 0, qPrintable(second.err));
        QVERIFY2(second.err.contains("is not usable (truncated"), qPrintable(second.err));
        QVERIFY2(second.err.contains("baking it again"), qPrintable(second.err));
        QCOMPARE(fs::file_size(entry), full); // written again, whole
        QCOMPARE(maxDifference(env.dir.filePath("a.png"), env.dir.filePath("b.png")), 0.0f);

        const auto third = render(env, QStringList{"-o", env.dir.filePath("c.png")} + size);
        QVERIFY2(third.exitCode == 0, qPrintable(third.err));
        QVERIFY2(!third.err.contains("not usable"), qPrintable(third.err));
    }

    // The entry is named by the HDRI's content: the same file name with other bytes is another
    // entry, and the render follows the new content.
    void changedHdriGetsItsOwnEntry() {
        Env env;
        const fs::path hdri = env.dir.filePath("env.exr").toStdString();
        fs::copy_file(velvet::resources::path("hdri") / "studio.exr", hdri);
        velvet::Scene scene = velvet::stageScene();
        scene.environment.hdri = hdri.string();
        const QString sceneFile = env.dir.filePath("scene.json");
        std::string error;
        QVERIFY2(velvet::saveSceneFile(scene, sceneFile.toStdString(), &error), error.c_str());
        const QStringList size{"--size", "64x48"};
        const auto first =
            render(env, QStringList{sceneFile, "-o", env.dir.filePath("a.png")} + size);
        QVERIFY2(first.exitCode == 0, qPrintable(first.err));
        QCOMPARE(env.entries().size(), 1);

        fs::copy_file(velvet::resources::path("hdri") / "sunset.exr", hdri,
                      fs::copy_options::overwrite_existing);
        const auto second =
            render(env, QStringList{sceneFile, "-o", env.dir.filePath("b.png")} + size);
        QVERIFY2(second.exitCode == 0, qPrintable(second.err));
        QCOMPARE(env.entries().size(), 2);
        QVERIFY(maxDifference(env.dir.filePath("a.png"), env.dir.filePath("b.png")) > 0.05f);
    }
};

QTEST_GUILESS_MAIN(TestAppRenderCache)
#include "test_app_render_cache.moc"
