// The velvet executable as a process: `pack` / `unpack` round trips with real files and their
// refusals, and a bad VELVET_MAX_IMAGE_* value stopping the process. Runs under xvfb (XVFB in
// CMakeLists.txt); the cases that need no display remove DISPLAY themselves.
#include "core/image.h"

#include <QDir>
#include <QFileInfo>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace {

struct Result {
    int exitCode = -1;
    QProcess::ExitStatus status = QProcess::CrashExit;
    QString out, err;
};

enum class Display { Keep, None };

Result runVelvet(const QStringList& args, Display display = Display::None,
                 const QMap<QString, QString>& extraEnv = {}) {
    QProcess p;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    if (display == Display::None) {
        env.remove("DISPLAY");
        env.remove("WAYLAND_DISPLAY");
        env.remove("QT_QPA_PLATFORM");
    }
    for (auto it = extraEnv.begin(); it != extraEnv.end(); ++it)
        env.insert(it.key(), it.value());
    p.setProcessEnvironment(env);
    p.start(VELVET_BINARY, args);
    Result r;
    if (!p.waitForFinished(180000)) {
        p.kill();
        p.waitForFinished();
        return r;
    }
    r.exitCode = p.exitCode();
    r.status = p.exitStatus();
    r.out = QString::fromUtf8(p.readAllStandardOutput());
    r.err = QString::fromUtf8(p.readAllStandardError());
    return r;
}

/// A grey 8-bit PNG whose pixel (x, y) is ((x * 7 + y * 13 + seed) mod 256) / 255.
velvet::Image greyPattern(int w, int h, int seed) {
    velvet::Image img(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            img.at(x, y)[0] = float((x * 7 + y * 13 + seed) % 256) / 255.0f;
    return img;
}

} // namespace

class TestAppProcess : public QObject {
    Q_OBJECT
private slots:
    // pack then unpack gives back the pixel values of every map, for every layout.
    void packUnpackRoundTrips_data() {
        QTest::addColumn<QString>("layout");
        QTest::addColumn<QStringList>("maps");
        QTest::newRow("gltf-mr") << "gltf-mr" << QStringList{"occlusion", "roughness", "metallic"};
        QTest::newRow("unreal-orm")
            << "unreal-orm" << QStringList{"occlusion", "roughness", "metallic"};
        QTest::newRow("hdrp-mask")
            << "hdrp-mask" << QStringList{"metallic", "occlusion", "detail", "smoothness"};
        QTest::newRow("srm") << "srm" << QStringList{"specular", "roughness", "metallic"};
    }
    void packUnpackRoundTrips() {
        QFETCH(QString, layout);
        QFETCH(QStringList, maps);
        QTemporaryDir dir;
        QStringList args{"pack", "--layout", layout, "--out", dir.filePath("packed.png")};
        std::string error;
        for (int i = 0; i < maps.size(); ++i) {
            const QString file = dir.filePath(maps[i] + "-in.png");
            QVERIFY2(velvet::writeImage(file.toStdString(), greyPattern(20, 12, 40 * i),
                                        velvet::PixelFormat::UInt8, &error),
                     error.c_str());
            args << "--" + maps[i] << file;
        }
        Result r = runVelvet(args);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        velvet::ImageInfo info;
        QVERIFY2(velvet::readImageInfo(dir.filePath("packed.png").toStdString(), info, &error),
                 error.c_str());
        QCOMPARE(info.channels, layout == "hdrp-mask" ? 4 : 3);

        r = runVelvet({"unpack", "--layout", layout, dir.filePath("packed.png"), "--out-dir",
                       dir.filePath("out")});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(QDir(dir.filePath("out")).entryList(QDir::Files).size(), maps.size());
        for (int i = 0; i < maps.size(); ++i) {
            velvet::Image back;
            const QString file = dir.filePath("out/" + maps[i] + ".png");
            QVERIFY2(velvet::readImage(file.toStdString(), back, &error), error.c_str());
            const velvet::Image want = greyPattern(20, 12, 40 * i);
            QCOMPARE(back.width, want.width);
            for (int y = 0; y < want.height; ++y)
                for (int x = 0; x < want.width; ++x)
                    QVERIFY2(std::lround(back.rgba(x, y).r * 255.0f) ==
                                 std::lround(want.at(x, y)[0] * 255.0f),
                             qPrintable(QString("%1 (%2, %3)").arg(maps[i]).arg(x).arg(y)));
        }
    }

    // A missing input: exit 2, the file named, nothing written. A map the layout lacks: exit 1.
    void packRefusals() {
        QTemporaryDir dir;
        const QString out = dir.filePath("packed.png");
        std::string error;
        const QString rough = dir.filePath("rough.png");
        QVERIFY(velvet::writeImage(rough.toStdString(), greyPattern(8, 8, 0),
                                   velvet::PixelFormat::UInt8, &error));
        const QString missing = dir.filePath("no-such-metal.png");
        Result r = runVelvet({"pack", "--layout", "gltf-mr", "--out", out, "--roughness", rough,
                              "--metallic", missing});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("no-such-metal.png"), qPrintable(r.err));
        QCOMPARE(QDir(dir.path()).entryList(QDir::Files).size(), 1); // rough.png only

        r = runVelvet({"pack", "--layout", "gltf-mr", "--out", out, "--smoothness", rough});
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains("--roughness"), qPrintable(r.err));
        r = runVelvet({"pack", "--layout", "nope", "--out", out, "--roughness", rough});
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains("hdrp-mask"), qPrintable(r.err));
        r = runVelvet({"unpack", "--layout", "gltf-mr", missing, "--out-dir", dir.path()});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("no-such-metal.png"), qPrintable(r.err));
        QVERIFY(!QFileInfo::exists(out));
        for (const char* command : {"pack", "unpack"}) {
            r = runVelvet({command, "--help"});
            QCOMPARE(r.exitCode, 0);
            QVERIFY(r.out.contains("unreal-orm") && r.out.contains("--out"));
        }
    }

    // VELVET_MAX_IMAGE_SIDE / _BYTES: a bad value stops the process with exit 2 and names the
    // variable; a valid one applies (a 20-pixel-wide map over a limit of 16 is refused).
    void imageLimitsFromEnvironment() {
        Result r = runVelvet({"info"}, Display::None, {{"VELVET_MAX_IMAGE_SIDE", "lots"}});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("VELVET_MAX_IMAGE_SIDE") && r.err.contains("lots"),
                 qPrintable(r.err));
        r = runVelvet({"info"}, Display::None, {{"VELVET_MAX_IMAGE_BYTES", "12Q"}});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("VELVET_MAX_IMAGE_BYTES"), qPrintable(r.err));

        QTemporaryDir dir;
        const QString in = dir.filePath("wide.png");
        std::string error;
        QVERIFY(velvet::writeImage(in.toStdString(), greyPattern(20, 4, 0),
                                   velvet::PixelFormat::UInt8, &error));
        const QStringList args{
            "pack", "--layout", "unreal-orm", "--out", dir.filePath("o.png"), "--roughness", in};
        r = runVelvet(args, Display::None, {{"VELVET_MAX_IMAGE_SIDE", "16"}});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("limit of 16 pixels"), qPrintable(r.err));
        r = runVelvet(args, Display::None, {{"VELVET_MAX_IMAGE_SIDE", "20"}});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
    }
};

QTEST_GUILESS_MAIN(TestAppProcess)
#include "test_app_process.moc"
