// core/export_files.h: names from documents cannot leave the output folder, an existing file
// refuses the whole export unless forced, nothing is written when any check fails.
#include "core/export_files.h"

#include <QDir>
#include <QFile>
#include <QTemporaryDir>
#include <QtTest>
#include <filesystem>

using velvet::ExportFile;
using velvet::ExportWriteError;
using velvet::sanitizeFileStem;
using velvet::writeExportFiles;

namespace {

QStringList entries(const QString& dir) {
    return QDir(dir).entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot, QDir::Name);
}

} // namespace

class TestCoreExportFiles : public QObject {
    Q_OBJECT
private slots:
    void sanitize_data() {
        QTest::addColumn<QString>("in");
        QTest::addColumn<QString>("out");
        QTest::newRow("path up") << "../../x"
                                 << "x";
        QTest::newRow("absolute") << "/etc/passwd"
                                  << "etc_passwd";
        QTest::newRow("spaces") << "Crimson velvet"
                                << "Crimson_velvet";
        QTest::newRow("backslashes") << "..\\..\\evil"
                                     << "evil";
        QTest::newRow("dots only") << "..."
                                   << "material";
        QTest::newRow("empty") << ""
                               << "material";
        QTest::newRow("kept") << "gold-2_b"
                              << "gold-2_b";
        QTest::newRow("non-ASCII") << QString::fromUtf8("Samt\xc3\xa9") << "Samt";
    }
    void sanitize() {
        QFETCH(QString, in);
        QFETCH(QString, out);
        QCOMPARE(QString::fromStdString(sanitizeFileStem(in.toStdString())), out);
        QCOMPARE(sanitizeFileStem(std::string(500, 'a')).size(), size_t(100));
    }

    void refusesNamesThatAreNotPlain_data() {
        QTest::addColumn<QString>("name");
        for (const char* n : {"../x.glb", "a/b.glb", ".", "..", "", "/abs.glb"})
            QTest::newRow(*n ? n : "empty") << n;
    }
    void refusesNamesThatAreNotPlain() {
        QFETCH(QString, name);
        QTemporaryDir tmp;
        const QString dir = tmp.filePath("out");
        std::string error;
        const std::vector<ExportFile> files{{"ok.bin", "1"}, {name.toStdString(), "2"}};
        QCOMPARE(writeExportFiles(dir.toStdString(), files, true, &error),
                 ExportWriteError::Unsafe);
        QVERIFY(!error.empty());
        QVERIFY(!QFileInfo::exists(dir + "/ok.bin")); // checked before anything is written
        QCOMPARE(entries(tmp.path()), QStringList{}); // not even the folder
    }

    void existingRefusedWholeUnlessForced() {
        QTemporaryDir tmp;
        const QString dir = tmp.path();
        QFile f(dir + "/b.gltf");
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("old");
        f.close();
        const std::vector<ExportFile> files{{"b.bin", "bin"}, {"b.gltf", "new"}};
        std::string error;
        QCOMPARE(writeExportFiles(dir.toStdString(), files, false, &error),
                 ExportWriteError::Exists);
        QVERIFY2(error.find("b.gltf") != std::string::npos, error.c_str());
        QCOMPARE(entries(dir), QStringList{"b.gltf"});
        std::vector<std::filesystem::path> written;
        QCOMPARE(writeExportFiles(dir.toStdString(), files, true, &error, &written),
                 ExportWriteError::None);
        QCOMPARE(written.size(), size_t(2));
        QCOMPARE(QString::fromStdString(written.back().filename().string()), QString("b.gltf"));
        QVERIFY(f.open(QIODevice::ReadOnly));
        QCOMPARE(f.readAll(), QByteArray("new"));
        QCOMPARE(entries(dir), (QStringList{"b.bin", "b.gltf"})); // no temporary left
    }

    void symlinkNeverReplaced() {
        QTemporaryDir tmp;
        const QString outside = tmp.filePath("outside.txt");
        QFile o(outside);
        QVERIFY(o.open(QIODevice::WriteOnly));
        o.write("keep");
        o.close();
        QVERIFY(QDir().mkpath(tmp.filePath("out")));
        QVERIFY(QFile::link(outside, tmp.filePath("out/m.glb")));
        std::string error;
        QCOMPARE(
            writeExportFiles(tmp.filePath("out").toStdString(), {{"m.glb", "x"}}, true, &error),
            ExportWriteError::Unsafe);
        QVERIFY(o.open(QIODevice::ReadOnly));
        QCOMPARE(o.readAll(), QByteArray("keep"));
    }

    void duplicateNamesRefused() {
        QTemporaryDir tmp;
        std::string error;
        QCOMPARE(writeExportFiles(tmp.path().toStdString(), {{"a", "1"}, {"a", "2"}}, true, &error),
                 ExportWriteError::Unsafe);
        QCOMPARE(entries(tmp.path()), QStringList{});
    }
};

QTEST_GUILESS_MAIN(TestCoreExportFiles)
#include "test_core_export_files.moc"
