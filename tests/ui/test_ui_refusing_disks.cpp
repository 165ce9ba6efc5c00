// Issue 18, "Disks and folders that say no": a full disk, a read-only folder, a path that is a
// folder and a folder that vanished each give one clear message naming the file and the reason,
// keep the previous file intact and (for the editor's save and autosave) keep the document dirty.
// Tested for the editor's save (DocumentController::saveAs), the autosave, `velvet export` and
// `velvet unpack`.
//
// The full disk is a 64 KiB tmpfs and the read-only folder a tmpfs remounted read-only, mounted by
// the test (mount(8) works when the test runs as root, as in this project's container; a
// permission bit would not stop root). Without mount the two cases are skipped, saying so; the
// folder and vanished cases need nothing.
#include "core/atomic_file.h"
#include "core/document_io.h"
#include "core/image.h"
#include "ui/autosave.h"
#include "ui/document_controller.h"

#include <QDir>
#include <QFile>
#include <QProcess>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest>
#include <filesystem>

namespace fs = std::filesystem;
using namespace velvet;

namespace {

bool run(const QString& program, const QStringList& args, QString* err = nullptr) {
    QProcess p;
    p.start(program, args);
    if (!p.waitForFinished(120000))
        return false;
    if (err)
        *err = QString::fromUtf8(p.readAllStandardError());
    return p.exitStatus() == QProcess::NormalExit && p.exitCode() == 0;
}

QByteArray readAll(const QString& file) {
    QFile f(file);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

/// Fills the file system of @p folder until a write fails (ENOSPC).
void fillDisk(const QString& folder) {
    QFile filler(folder + "/filler");
    if (!filler.open(QIODevice::WriteOnly))
        return;
    const QByteArray block(4096, 'x');
    while (filler.write(block) == block.size() && filler.flush()) {
    }
}

/// The ways a folder says no; Prepare puts the previous files in first.
enum class Refusal { FullDisk, ReadOnly, IsFolder, Vanished };

} // namespace

class TestUiRefusingDisks : public QObject {
    Q_OBJECT
    QStringList m_mounts;
    bool m_canMount = false;

    /// @p folder made to refuse as @p how, after @p prepare wrote the previous files into it.
    /// False (the case skipped) when that needs a mount and mount is not allowed.
    bool makeRefuse(const QString& folder, Refusal how, const std::function<void()>& prepare) {
        QDir().mkpath(folder);
        if (how == Refusal::FullDisk || how == Refusal::ReadOnly) {
            if (!m_canMount)
                return false;
            if (!run("mount", {"-t", "tmpfs", "-o", "size=64k", "tmpfs", folder}))
                return false;
            m_mounts.prepend(folder);
        }
        prepare();
        if (how == Refusal::FullDisk)
            fillDisk(folder);
        if (how == Refusal::ReadOnly && !run("mount", {"-o", "remount,ro", folder}))
            return false;
        return true;
    }

private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);
        QTemporaryDir probe;
        m_canMount = run("mount", {"-t", "tmpfs", "-o", "size=16k", "tmpfs", probe.path()});
        if (m_canMount)
            run("umount", {probe.path()});
    }
    void cleanup() {
        for (const QString& m : m_mounts)
            run("umount", {m});
        m_mounts.clear();
    }

    void refusals_data() {
        QTest::addColumn<int>("how");
        QTest::addColumn<QString>("reason");
        QTest::newRow("full disk") << int(Refusal::FullDisk) << "disk is full";
        QTest::newRow("read-only folder") << int(Refusal::ReadOnly) << "read-only";
        QTest::newRow("path is a folder") << int(Refusal::IsFolder) << "folder";
        QTest::newRow("vanished folder") << int(Refusal::Vanished) << "does not exist";
    }

    // The editor's save: false, the message names the file and the reason, the previous file
    // and its content are intact, the document is still dirty.
    void refusals() {
        QFETCH(int, how);
        QFETCH(QString, reason);
        const Refusal refusal = Refusal(how);
        QTemporaryDir tmp;
        const QString folder = tmp.filePath("docs");
        const QString file = folder + "/scene.json";
        ui::DocumentController doc;
        QByteArray previous;
        const bool ready = makeRefuse(folder, refusal, [&] {
            QString error;
            QVERIFY2(doc.saveAs(file, &error), qPrintable(error));
            previous = readAll(file);
            if (refusal == Refusal::IsFolder) {
                QFile::remove(file);
                QDir().mkpath(file);
            }
        });
        if (!ready)
            QSKIP("mount -t tmpfs is not allowed here: no full disk or read-only folder to test");
        if (refusal == Refusal::Vanished)
            QVERIFY(QDir(folder).removeRecursively());
        doc.editParam(ParamId::Roughness, glm::vec3(0.77f));
        QVERIFY(doc.isDirty());
        QString error;
        QVERIFY(!doc.saveAs(file, &error));
        QVERIFY2(error.contains("scene.json") && error.contains(reason, Qt::CaseInsensitive),
                 qPrintable(error));
        QVERIFY2(!error.contains('\n'), qPrintable(error));
        QVERIFY(doc.isDirty());
        if (refusal == Refusal::FullDisk || refusal == Refusal::ReadOnly)
            QCOMPARE(readAll(file), previous);
        std::printf("save, %s: %s\n", QTest::currentDataTag(), qPrintable(error));
        cleanup(); // unmount before the temporary folder goes
    }

    // The autosave: the same refusals of its folder, reported through the returned message.
    void autosaveRefusals_data() { refusals_data(); }
    void autosaveRefusals() {
        QFETCH(int, how);
        QFETCH(QString, reason);
        const Refusal refusal = Refusal(how);
        if (refusal == Refusal::Vanished)
            QSKIP("the autosave folder is created again on each write (mkpath): it cannot vanish");
        ui::DocumentController doc;
        ui::Autosave autosave(&doc);
        const QString folder = ui::Autosave::directory();
        QDir(folder).removeRecursively();
        const QString file = ui::Autosave::autosavePathFor(QString());
        QByteArray previous;
        const bool ready = makeRefuse(folder, refusal, [&] {
            doc.editParam(ParamId::Roughness, glm::vec3(0.5f));
            QString error;
            QVERIFY2(autosave.saveNow(&error), qPrintable(error));
            previous = readAll(file);
            if (refusal == Refusal::IsFolder) {
                QFile::remove(file);
                QDir().mkpath(file);
            }
        });
        if (!ready)
            QSKIP("mount -t tmpfs is not allowed here: no full disk or read-only folder to test");
        doc.editParam(ParamId::Roughness, glm::vec3(0.6f));
        QString error;
        QVERIFY(!autosave.saveNow(&error));
        QVERIFY2(error.contains(".autosave.json") && error.contains(reason, Qt::CaseInsensitive),
                 qPrintable(error));
        QVERIFY(doc.isDirty());
        if (refusal != Refusal::IsFolder)
            QCOMPARE(readAll(file), previous);
        std::printf("autosave, %s: %s\n", QTest::currentDataTag(), qPrintable(error));
        cleanup();
        QDir(folder).removeRecursively();
    }

    // `velvet export -f preset --force` over a previous export and `velvet unpack` over previous
    // maps: exit 2, one line naming the file and the reason, the previous file intact.
    void cliRefusals_data() {
        QTest::addColumn<int>("how");
        QTest::addColumn<QString>("reason");
        QTest::addColumn<bool>("unpack");
        for (bool unpack : {false, true}) {
            const char* what = unpack ? "unpack" : "export";
            QTest::addRow("%s, full disk", what)
                << int(Refusal::FullDisk) << "disk is full" << unpack;
            QTest::addRow("%s, read-only", what) << int(Refusal::ReadOnly) << "read-only" << unpack;
            QTest::addRow("%s, path is a folder", what)
                << int(Refusal::IsFolder) << (unpack ? "not a regular file" : "folder") << unpack;
        }
    }
    void cliRefusals() {
        QFETCH(int, how);
        QFETCH(QString, reason);
        QFETCH(bool, unpack);
        const Refusal refusal = Refusal(how);
        QTemporaryDir tmp;
        const QString scene = tmp.filePath("look.json");
        std::string message;
        QVERIFY(saveSceneFile(defaultScene(), scene.toStdString(), &message));
        const QString packed = tmp.filePath("orm.png");
        Image orm(16, 16, 3);
        for (float& v : orm.pixels)
            v = 0.5f;
        QVERIFY(writeImage(packed.toStdString(), orm, PixelFormat::UInt8, &message));
        const QString out = tmp.filePath("out");
        const QStringList args =
            unpack ? QStringList{"unpack", "--layout", "unreal-orm", packed, "--out-dir", out}
                   : QStringList{"export", scene, "-f", "preset", "-o", out, "--force"};
        const QString target = out + (unpack ? "/roughness.png" : "/look.json");
        QByteArray previous;
        QString err;
        const bool ready = makeRefuse(out, refusal, [&] {
            QVERIFY2(run(VELVET_BINARY, args, &err), qPrintable(err));
            previous = readAll(target);
            if (refusal == Refusal::IsFolder) {
                QFile::remove(target);
                QDir().mkpath(target);
            }
        });
        if (!ready)
            QSKIP("mount -t tmpfs is not allowed here: no full disk or read-only folder to test");
        QProcess p;
        p.start(VELVET_BINARY, args);
        QVERIFY(p.waitForFinished(120000));
        err = QString::fromUtf8(p.readAllStandardError()).trimmed();
        QCOMPARE(p.exitCode(), 2);
        QVERIFY2(err.contains(QFileInfo(target).fileName()) || err.contains(out), qPrintable(err));
        QVERIFY2(err.contains(reason, Qt::CaseInsensitive), qPrintable(err));
        if (refusal != Refusal::IsFolder)
            QCOMPARE(readAll(target), previous);
        std::printf("%s: %s\n", QTest::currentDataTag(), qPrintable(err));
        cleanup(); // unmount before the temporary folder goes
    }
};

QTEST_GUILESS_MAIN(TestUiRefusingDisks)
#include "test_ui_refusing_disks.moc"
