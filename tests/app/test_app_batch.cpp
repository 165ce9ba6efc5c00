// Batch runs (issue 12, docs/batch.md) through the real binary: a render batch with one broken
// input finishes the others, reports the broken one in one line and exits 2; progress lines name
// done/total and the file; `velvet thumbnails DIR` in two shards writes disjoint sets of
// thumbnails that together are every document of DIR; an export batch with --jobs; bad --jobs
// and --shard are usage errors.
#include "core/image.h"
#include "run_velvet.h"

#include <QDir>
#include <QFile>
#include <QRegularExpression>
#include <QSet>
#include <QTemporaryDir>
#include <QtTest>

namespace {

using velvet::test::Result;

Result runVelvet(const QStringList& args) {
    velvet::test::RunOptions options;
    options.timeoutMs = 300000;
    return velvet::test::runVelvet(args, options);
}

QString preset(const QString& name) {
    return QStringLiteral(VELVET_SOURCE_DIR "/resources/presets/") + name;
}

QSet<QString> filesIn(const QString& dir) {
    const QStringList list = QDir(dir).entryList(QDir::Files);
    return QSet<QString>(list.begin(), list.end());
}

} // namespace

class TestAppBatch : public QObject {
    Q_OBJECT
    QTemporaryDir m_tmp;

private slots:
    void initTestCase() { QVERIFY(m_tmp.isValid()); }

    void brokenInputFinishesTheOthersAndExits2() {
        const QString broken = m_tmp.filePath("broken.json");
        QFile f(broken);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("{ \"format\": \"velvet-material\", "); // truncated JSON
        f.close();
        const QString out = m_tmp.filePath("renders");
        const Result r = runVelvet({"render", preset("gold.json"), broken, preset("silk.json"),
                                    "-o", out, "--size", "24x24", "--jobs", "2"});
        QCOMPARE(r.status, QProcess::NormalExit);
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(QFile::exists(out + "/gold.png") && QFile::exists(out + "/silk.png"),
                 qPrintable(r.err));
        QVERIFY(!QFile::exists(out + "/broken.png"));
        // One FAILED line for the broken input, naming it; none for the others.
        const QStringList failed =
            r.err.split('\n').filter(QRegularExpression("^velvet render: FAILED "));
        QCOMPARE(failed.size(), 1);
        QVERIFY2(failed.front().contains("broken.json"), qPrintable(r.err));
        // Progress: done/total and the file on every finished input.
        QVERIFY2(r.err.contains(QRegularExpression(R"(\[3/3\] \S+\.json (ok|FAILED))")),
                 qPrintable(r.err));
        QVERIFY(r.err.contains("1 of 3 inputs failed"));
        // The outputs are real renders of the requested size.
        velvet::Image img;
        std::string error;
        QVERIFY(velvet::readImage((out + "/gold.png").toStdString(), img, &error));
        QCOMPARE(img.width, 24);
    }

    void thumbnailShardsAreDisjointAndCover() {
        // A library folder of five documents (and an atlas, which is not one).
        const QString lib = m_tmp.filePath("library");
        QVERIFY(QDir().mkpath(lib + "/sub"));
        const QStringList names{"gold", "silk", "denim", "copper", "leather"};
        for (int i = 0; i < names.size(); ++i)
            QVERIFY(QFile::copy(preset(names[i] + ".json"),
                                lib + (i == 4 ? "/sub/" : "/") + names[i] + ".json"));
        QFile atlas(lib + "/gold.atlas.json");
        QVERIFY(atlas.open(QIODevice::WriteOnly));
        atlas.write("{}");
        atlas.close();
        const QString a = m_tmp.filePath("thumbs0"), b = m_tmp.filePath("thumbs1");
        const Result r0 = runVelvet(
            {"thumbnails", lib, "-o", a, "--size", "16", "--shard", "0/2", "--jobs", "2"});
        QVERIFY2(r0.exitCode == 0, qPrintable(r0.err));
        const Result r1 = runVelvet({"thumbnails", lib, "-o", b, "--size", "16", "--shard", "1/2"});
        QVERIFY2(r1.exitCode == 0, qPrintable(r1.err));
        const QSet<QString> s0 = filesIn(a), s1 = filesIn(b);
        QVERIFY(!s0.isEmpty() && !s1.isEmpty());
        QVERIFY(!s0.intersects(s1));
        QSet<QString> all;
        for (const QString& n : names)
            all.insert(n + ".png");
        QCOMPARE(s0 + s1, all);
        QVERIFY(r0.err.contains(QRegularExpression(R"(\[\d/3\])")));
    }

    void exportBatchWithJobs() {
        const QString out = m_tmp.filePath("presets");
        const Result r = runVelvet({"export", preset("gold.json"), preset("silk.json"), "-f",
                                    "preset", "-o", out, "--jobs", "2"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY(QFile::exists(out + "/gold.json") && QFile::exists(out + "/silk.json"));
        QVERIFY(r.out.contains("gold.json") && r.out.contains("silk.json"));
    }

    void badBatchOptionsAreUsageErrors() {
        QCOMPARE(runVelvet({"render", preset("gold.json"), "-o", "x", "--jobs", "0"}).exitCode, 1);
        QCOMPARE(runVelvet({"render", preset("gold.json"), "-o", "x", "--shard", "2/2"}).exitCode,
                 1);
        QCOMPARE(runVelvet({"thumbnails", m_tmp.path(), "-o", "x", "--shard", "x"}).exitCode, 1);
        QCOMPARE(
            runVelvet({"render", preset("gold.json"), preset("silk.json"), "-o", "x.png"}).exitCode,
            1);
        QCOMPARE(runVelvet({"thumbnails", m_tmp.filePath("nowhere"), "-o", "x"}).exitCode, 2);
    }
};

QTEST_GUILESS_MAIN(TestAppBatch)
#include "test_app_batch.moc"
