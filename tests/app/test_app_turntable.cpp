// velvet render --turntable (issue 14): numbered frames with progress on stderr, what each mode
// turns (measured on the frames), bad patterns and folders refused before anything is written,
// and --video with and without the ffmpeg program on PATH.
#include "core/document_io.h"
#include "core/image.h"
#include "core/image_ops.h"
#include "core/video_encoder.h"
#include "run_velvet.h"

#include <QDir>
#include <QFile>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QtTest>
#include <glm/common.hpp>

using velvet::test::Result;
using velvet::test::runVelvet;

namespace {

velvet::Image read(const QString& file) {
    velvet::Image image;
    std::string error;
    if (!velvet::readImage(file.toStdString(), image, &error))
        QTest::qFail(error.c_str(), __FILE__, __LINE__);
    return image;
}

/// The largest channel difference between two images of one size, and how many pixels differ
/// by more than 2/255.
std::pair<float, int> difference(const velvet::Image& a, const velvet::Image& b) {
    float worst = 0;
    int count = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const glm::vec4 d = glm::abs(a.rgba(x, y) - b.rgba(x, y));
            const float m = std::max({d.r, d.g, d.b});
            worst = std::max(worst, m);
            count += m > 2.0f / 255.0f;
        }
    return {worst, count};
}

} // namespace

class TestAppTurntable : public QObject {
    Q_OBJECT
private slots:
    // Mesh mode on the default sphere: the sphere is round and its material has no texture, and
    // the lights and the environment stay with the camera, so every frame is the first (to
    // 2/255); light mode moves the reflections and the background, so frames differ. Each frame
    // is reported on stderr with frames done / total and an ETA.
    void turntableFramesAndProgress() {
        QTemporaryDir dir;
        Result r = runVelvet(
            {"render", "--turntable", "4", "-o", dir.filePath("mesh_%03d.png"), "--size", "48x32"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        for (int i = 1; i <= 4; ++i)
            QVERIFY2(r.err.contains(QString("frame %1/4").arg(i)), qPrintable(r.err));
        QVERIFY2(r.err.contains("ETA"), qPrintable(r.err));
        QVERIFY(r.out.isEmpty());
        const QStringList files =
            QDir(dir.path()).entryList({"mesh_*.png"}, QDir::Files, QDir::Name);
        QCOMPARE(files,
                 QStringList({"mesh_000.png", "mesh_001.png", "mesh_002.png", "mesh_003.png"}));
        const velvet::Image first = read(dir.filePath("mesh_000.png"));
        QCOMPARE(first.width, 48);
        QCOMPARE(first.height, 32);
        for (int i = 1; i < 4; ++i) {
            const auto [worst, count] = difference(
                first, read(dir.filePath(QString("mesh_%1.png").arg(i, 3, 10, QChar('0')))));
            qInfo("mesh mode, frame %d against frame 0: worst %.4f, %d pixels differ", i, worst,
                  count);
            QVERIFY(count <= 2);
        }

        r = runVelvet({"render", "--turntable", "4", "--turntable-mode", "light", "-o",
                       dir.filePath("light_%d.png"), "--size", "48x32"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const auto [worst, count] =
            difference(read(dir.filePath("light_0.png")), read(dir.filePath("light_2.png")));
        qInfo("light mode, frame 2 against frame 0: worst %.4f, %d pixels differ", worst, count);
        QVERIFY(count > 48 * 32 / 4);
    }

    // Mesh mode on the cube: a quarter turn maps the cube onto itself, an eighth does not.
    void meshModeTurnsTheMesh() {
        QTemporaryDir dir;
        const QString scene = dir.filePath("cube.json");
        velvet::Scene cube = velvet::defaultScene();
        cube.mesh.kind = velvet::PreviewMeshKind::Cube;
        cube.material = velvet::Material(); // untextured: a quarter turn leaves nothing changed
        cube.camera.yawDeg = 30.0f;
        cube.camera.pitchDeg = 20.0f;
        std::string error;
        QVERIFY2(velvet::saveSceneFile(cube, scene.toStdString(), &error), error.c_str());
        Result r = runVelvet(
            {"render", scene, "--turntable", "8", "-o", dir.filePath("%d.png"), "--size", "48x48"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const velvet::Image f0 = read(dir.filePath("0.png"));
        const int quarter = difference(f0, read(dir.filePath("2.png"))).second;
        const int eighth = difference(f0, read(dir.filePath("1.png"))).second;
        qInfo("cube: %d pixels differ after a quarter turn, %d after an eighth", quarter, eighth);
        QVERIFY(eighth > 100);
        QVERIFY(quarter < eighth / 10);
    }

    // --supersample N (stills and turntables alike, render/render_job.h): the frame drawn N times
    // larger each way and box-filtered. A known answer: the 2x2-supersampled 48x32 still is the
    // 96x64 still averaged over 2x2 blocks (to the rounding of the 8-bit images), and it differs
    // from the plain 48x32 still at the sphere's silhouette, whose pixels now hold partial
    // coverage instead of all mesh or all background. The material is a rough plain dielectric:
    // a supersampled still also samples a glossy lobe's or a sheen's environment light, as the
    // viewport at rest does, which a plain still does not (FrameSettings::reflectionSamples).
    void supersampledStillIsTheBoxFilteredLargerStill() {
        QTemporaryDir dir;
        const QString scenePath = dir.filePath("matte.json");
        velvet::Scene matte = velvet::defaultScene();
        matte.material = velvet::Material();
        matte.material.setColor(velvet::ParamId::BaseColor, glm::vec3(0.7f, 0.3f, 0.2f));
        matte.material.setScalar(velvet::ParamId::Roughness, 0.9f);
        matte.material.setScalar(velvet::ParamId::SheenWeight, 0.0f);
        std::string error;
        QVERIFY2(velvet::saveSceneFile(matte, scenePath.toStdString(), &error), error.c_str());
        Result r = runVelvet({"render", scenePath, "-o", dir.filePath("ss.png"), "--size", "48x32",
                              "--supersample", "2"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        r = runVelvet({"render", scenePath, "-o", dir.filePath("large.png"), "--size", "96x64"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        r = runVelvet({"render", scenePath, "-o", dir.filePath("plain.png"), "--size", "48x32"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const velvet::Image ss = read(dir.filePath("ss.png"));
        const velvet::Image filtered = velvet::boxDownsample(read(dir.filePath("large.png")), 2);
        QCOMPARE(ss.width, 48);
        QCOMPARE(ss.height, 32);
        const auto [worst, count] = difference(ss, filtered);
        qInfo("supersampled against the filtered large still: max %.4f, %d pixels > 2/255", worst,
              count);
        QVERIFY(worst <= 1.01f / 255.0f);
        const int edge = difference(ss, read(dir.filePath("plain.png"))).second;
        qInfo("supersampled against the plain still: %d pixels differ by more than 2/255", edge);
        QVERIFY(edge > 20); // the silhouette's ring (about 2 pi r = 80 pixels at r = 13)
    }

    // Supersampling outside 1 to 4, or drawing more than 8192x8192 pixels, is a usage error.
    void supersamplingOutOfRange_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<QString>("message");
        QTest::newRow("zero") << QStringList{"--supersample", "0"} << "1 to 4";
        QTest::newRow("five") << QStringList{"--supersample", "5"} << "1 to 4";
        QTest::newRow("not a number") << QStringList{"--supersample", "2x"} << "1 to 4";
        QTest::newRow("too many pixels")
            << QStringList{"--supersample", "3", "--size", "4096x4096"} << "12288x12288";
    }
    void supersamplingOutOfRange() {
        QFETCH(QStringList, args);
        QFETCH(QString, message);
        QTemporaryDir dir;
        Result r = runVelvet(QStringList{"render", "-o", dir.filePath("x.png")} + args);
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains(message), qPrintable(r.err));
        QVERIFY2(QDir(dir.path()).isEmpty(), "bad input must write nothing");
    }

    // Bad patterns, a missing folder and a bad mode are refused before anything is rendered.
    void badRequestsWriteNothing_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<int>("exitCode");
        QTest::addColumn<QString>("message");
        QTest::newRow("no frame number")
            << QStringList{"-o", "DIR/frame.png"} << 2 << "no frame number";
        QTest::newRow("two frame numbers")
            << QStringList{"-o", "DIR/%d_%d.png"} << 2 << "more than one";
        QTest::newRow("string conversion") << QStringList{"-o", "DIR/%s.png"} << 2 << "%0Nd";
        QTest::newRow("number in a folder")
            << QStringList{"-o", "DIR/f%02d/x.png"} << 2 << "folder name";
        QTest::newRow("jpeg frames") << QStringList{"-o", "DIR/%03d.jpg"} << 2 << ".png or .exr";
        QTest::newRow("missing folder")
            << QStringList{"-o", "DIR/none/%03d.png"} << 2 << "does not exist";
        QTest::newRow("bad mode") << QStringList{"-o", "DIR/%d.png", "--turntable-mode", "orbit"}
                                  << 1 << "mesh or light";
        QTest::newRow("bad video container")
            << QStringList{"-o", "DIR/%d.png", "--video", "DIR/a.gif"} << 2 << ".mp4";
        QTest::newRow("video from exr")
            << QStringList{"-o", "DIR/%d.exr", "--video", "DIR/a.mp4"} << 2 << ".png frames";
    }
    void badRequestsWriteNothing() {
        QFETCH(QStringList, args);
        QFETCH(int, exitCode);
        QFETCH(QString, message);
        QTemporaryDir dir;
        args.replaceInStrings("DIR", dir.path());
        Result r = runVelvet(QStringList{"render", "--turntable", "3", "--size", "16x16"} + args);
        QCOMPARE(r.exitCode, exitCode);
        QVERIFY2(r.err.contains(message), qPrintable(r.err));
        QVERIFY2(QDir(dir.path()).isEmpty(), "bad input must write nothing");
    }

    void turntableOptionsNeedTurntable() {
        Result r = runVelvet({"render", "-o", "x.png", "--video", "x.mp4"});
        QCOMPARE(r.exitCode, 1);
        QVERIFY2(r.err.contains("--video needs --turntable"), qPrintable(r.err));
        r = runVelvet({"render", "--turntable", "0", "-o", "%d.png"});
        QCOMPARE(r.exitCode, 1);
        // A still named like a sequence would land under a name nobody meant.
        QTemporaryDir dir;
        r = runVelvet({"render", "-o", dir.filePath("%03d.png"), "--size", "8x8"});
        QCOMPARE(r.exitCode, 2);
        QVERIFY(QDir(dir.path()).isEmpty());
    }

    // Without ffmpeg on PATH --video is refused with a message saying so, before any frame.
    void videoWithoutFfmpegSaysSo() {
        QTemporaryDir dir;
        velvet::test::RunOptions options;
        options.extraEnv.insert("PATH", dir.path()); // a PATH with no ffmpeg on it
        Result r = runVelvet({"render", "--turntable", "3", "--size", "16x16", "-o",
                              dir.filePath("%d.png"), "--video", dir.filePath("t.mp4")},
                             options);
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("ffmpeg") && r.err.contains("PATH"), qPrintable(r.err));
        QVERIFY(QDir(dir.path()).isEmpty());
    }

    // With ffmpeg: an MP4 (an ISO BMFF 'ftyp' box first), nothing left beside it, and with no
    // -o no frames left anywhere we can see.
    void videoThroughFfmpeg() {
        if (velvet::findProgram("ffmpeg").empty())
            QSKIP("the ffmpeg program is not installed (apt install ffmpeg); the path without it "
                  "is videoWithoutFfmpegSaysSo");
        QTemporaryDir dir;
        const QString video = dir.filePath("turn.mp4");
        Result r = runVelvet({"render", "--turntable", "6", "--size", "33x21", "--video", video});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(r.err.contains("frame 6/6") && r.err.contains("encoding"), qPrintable(r.err));
        QFile file(video);
        QVERIFY(file.open(QIODevice::ReadOnly));
        const QByteArray head = file.read(12);
        QCOMPARE(head.mid(4, 4), QByteArray("ftyp"));
        QCOMPARE(QDir(dir.path()).entryList(QDir::Files | QDir::Hidden), QStringList{"turn.mp4"});
        // The frames too, when named.
        r = runVelvet({"render", "--turntable", "3", "--size", "16x16", "-o",
                       dir.filePath("f%02d.png"), "--video", dir.filePath("b.mkv")});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY(QFileInfo::exists(dir.filePath("f02.png")));
        QVERIFY(QFileInfo(dir.filePath("b.mkv")).size() > 0);
    }
};

QTEST_GUILESS_MAIN(TestAppTurntable)
#include "test_app_turntable.moc"
