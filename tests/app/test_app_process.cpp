// The velvet executable as a process (issue 2 foundations, issues 3 and 6): the editor's
// --screenshot under xvfb, its refusal without a display, `render -o x.exr` writing linear half
// float, `info` reporting the GL context, `pack` / `unpack` round trips with real files, and a bad
// VELVET_MAX_IMAGE_* value stopping the process. Runs under xvfb (XVFB in CMakeLists.txt); the
// cases that need no display remove DISPLAY themselves.
#include "core/color_management.h"
#include "core/image.h"
#include "core/tone_curves.h"
#include "run_velvet.h"

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

using velvet::test::Display;
using velvet::test::Result;

Result runVelvet(const QStringList& args, Display display = Display::None,
                 const QMap<QString, QString>& extraEnv = {}) {
    velvet::test::RunOptions options;
    options.display = display;
    options.extraEnv = extraEnv;
    return velvet::test::runVelvet(args, options);
}

/// Khronos PBR Neutral (the default built-in curve), clamped to [0, 1].
glm::vec3 pbrNeutral(glm::vec3 c) {
    return glm::clamp(velvet::tone::khronosPbrNeutral(glm::max(c, glm::vec3(0.0f))), 0.0f, 1.0f);
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
    // The editor under xvfb renders its first frame, saves the window and exits 0.
    void screenshotUnderXvfb() {
        if (qEnvironmentVariableIsEmpty("DISPLAY"))
            QSKIP("needs a display (run through ctest: xvfb-run)");
        QTemporaryDir dir; // also HOME and XDG folders: the user's settings stay untouched
        const QString out = dir.filePath("window.png");
        const Result r = runVelvet({"--screenshot", out}, Display::Keep,
                                   {{"QT_QPA_PLATFORM", "xcb"},
                                    {"HOME", dir.path()},
                                    {"XDG_CONFIG_HOME", dir.filePath("config")},
                                    {"XDG_CACHE_HOME", dir.filePath("cache")}});
        QCOMPARE(r.status, QProcess::NormalExit);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        velvet::ImageInfo info;
        std::string error;
        QVERIFY2(velvet::readImageInfo(out.toStdString(), info, &error), error.c_str());
        // The editor's fixed screenshot size (ui/editor.cpp), allowing for window decorations.
        QVERIFY2(info.width >= 800 && info.width <= 1600 && info.height >= 500 &&
                     info.height <= 1000,
                 qPrintable(QString("%1x%2").arg(info.width).arg(info.height)));
        velvet::Image image;
        QVERIFY2(velvet::readImage(out.toStdString(), image, &error), error.c_str());
        // Not blank: many distinct values over the window (panels, viewport, text).
        float lo = 1.0f, hi = 0.0f;
        for (int y = 0; y < image.height; y += 7)
            for (int x = 0; x < image.width; x += 7) {
                const glm::vec4 c = image.rgba(x, y);
                lo = std::min(lo, c.g);
                hi = std::max(hi, c.g);
            }
        QVERIFY2(hi - lo > 0.3f, qPrintable(QString("range %1..%2").arg(lo).arg(hi)));
    }

    // Without any display the editor says so in one line pointing at `velvet render`.
    void noDisplayPointsAtRender() {
        const Result r = runVelvet({}, Display::None);
        QCOMPARE(r.status, QProcess::NormalExit);
        QVERIFY(r.exitCode != 0);
        const QStringList lines = r.err.trimmed().split('\n');
        QCOMPARE(lines.size(), 1);
        QVERIFY2(lines[0].contains("velvet render"), qPrintable(r.err));
    }

    // EXR output is half float and scene-linear: the PNG of the same render is the built-in
    // curve and OCIO's sRGB encoding of the EXR's values (within 8-bit rounding, half precision
    // and the curve).
    void renderExrIsLinearHalf() {
        QTemporaryDir dir;
        const QString exr = dir.filePath("x.exr"), png = dir.filePath("x.png");
        for (const QString& out : {exr, png}) {
            const Result r = runVelvet({"render", "-o", out, "--size", "48x48"});
            QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        }
        velvet::ImageInfo info;
        std::string error;
        QVERIFY2(velvet::readImageInfo(exr.toStdString(), info, &error), error.c_str());
        QCOMPARE(info.format, std::string("openexr"));
        QVERIFY(info.isFloat);
        QCOMPARE(info.bitsPerSample, 16);
        velvet::Image linear, display;
        QVERIFY2(velvet::readImage(exr.toStdString(), linear, &error), error.c_str());
        QVERIFY2(velvet::readImage(png.toStdString(), display, &error), error.c_str());
        velvet::ColorManagement cm;
        QVERIFY2(cm.loadFile(VELVET_SOURCE_DIR "/resources/ocio/config.ocio", &error),
                 error.c_str());
        velvet::Image expected = linear;
        float brightest = 0.0f;
        for (int y = 0; y < linear.height; ++y)
            for (int x = 0; x < linear.width; ++x) {
                float* p = expected.at(x, y);
                brightest = std::max({brightest, p[0], p[1], p[2]});
                const glm::vec3 t = pbrNeutral({p[0], p[1], p[2]});
                p[0] = t.r, p[1] = t.g, p[2] = t.b;
            }
        QVERIFY2(cm.applyDisplay(expected, {"sRGB", "Standard", "", 0.0f}, &error), error.c_str());
        float worst = 0.0f;
        for (int y = 0; y < linear.height; ++y)
            for (int x = 0; x < linear.width; ++x)
                for (int c = 0; c < 3; ++c)
                    worst = std::max(worst, std::abs(display.rgba(x, y)[c] -
                                                     std::clamp(expected.rgba(x, y)[c], 0.f, 1.f)));
        qInfo("max |PNG - encode(curve(EXR))| = %.2f/255; brightest linear value %.3f",
              double(worst * 255.0f), double(brightest));
        QVERIFY2(worst <= 2.5f / 255.0f, qPrintable(QString::number(worst * 255.0f)));
        QVERIFY(brightest > 0.05f); // not an empty frame
    }

    void infoPrintsGlLines() {
        const Result r = runVelvet({"info"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err + r.out));
        for (const char* key : {"vendor:", "renderer:", "version:"}) {
            const QStringList lines = r.out.split('\n').filter(key);
            QVERIFY2(!lines.isEmpty(), key);
            QVERIFY2(lines[0].section(':', 1).trimmed().size() > 0, qPrintable(lines[0]));
        }
    }

    // app/huge_pages.h: velvet runs itself again with glibc's huge-page tunable (not in ASan
    // builds, whose allocator is not glibc's); VELVET_HUGE_PAGES=0 and a user's own
    // glibc.malloc.hugetlb value keep it off, and other tunables stay as they were.
    void hugePagesForLargeAllocations() {
        const auto memoryLine = [](const Result& r) {
            const QStringList lines = r.out.split('\n').filter("Memory:");
            return lines.isEmpty() ? QString() : lines[0];
        };
        Result r = runVelvet({"info"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err + r.out));
#if defined(__SANITIZE_ADDRESS__)
        QVERIFY2(memoryLine(r).contains("pages for large allocations off"), qPrintable(r.out));
#else
        QVERIFY2(memoryLine(r).contains("pages for large allocations on"), qPrintable(r.out));
        r = runVelvet({"info"}, Display::None, {{"GLIBC_TUNABLES", "glibc.malloc.arena_max=4"}});
        QVERIFY2(memoryLine(r).contains("pages for large allocations on"), qPrintable(r.out));
#endif
        r = runVelvet({"info"}, Display::None, {{"VELVET_HUGE_PAGES", "0"}});
        QVERIFY2(memoryLine(r).contains("pages for large allocations off"), qPrintable(r.out));
        r = runVelvet({"info"}, Display::None, {{"GLIBC_TUNABLES", "glibc.malloc.hugetlb=0"}});
        QVERIFY2(memoryLine(r).contains("pages for large allocations off"), qPrintable(r.out));
    }

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

    // Maps of different sizes: exit 2, nothing written, and the message names the options the
    // user gave (HDRP's --smoothness, not the roughness channel it is stored as) and the files.
    void packSizeMismatchNamesTheFlags() {
        QTemporaryDir dir;
        std::string error;
        const QString metal = dir.filePath("metal.png"), smooth = dir.filePath("smooth.png");
        QVERIFY(velvet::writeImage(metal.toStdString(), greyPattern(32, 32, 0),
                                   velvet::PixelFormat::UInt8, &error));
        QVERIFY(velvet::writeImage(smooth.toStdString(), greyPattern(16, 16, 0),
                                   velvet::PixelFormat::UInt8, &error));
        const QString out = dir.filePath("mask.png");
        Result r = runVelvet({"pack", "--layout", "hdrp-mask", "--out", out, "--metallic", metal,
                              "--smoothness", smooth});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("--metallic " + metal + " is 32x32") &&
                     r.err.contains("--smoothness " + smooth + " is 16x16") &&
                     !r.err.contains("roughness"),
                 qPrintable(r.err));
        QVERIFY(!QFileInfo::exists(out));
    }

    // unpack is all or nothing: when one target cannot be written (here metallic.png, the last
    // gltf-mr map, is a folder) it exits 2 and leaves no map and no staging file behind.
    void unpackFailureWritesNothing() {
        QTemporaryDir dir;
        std::string error;
        const QString rough = dir.filePath("rough.png");
        QVERIFY(velvet::writeImage(rough.toStdString(), greyPattern(8, 8, 0),
                                   velvet::PixelFormat::UInt8, &error));
        const QString packed = dir.filePath("packed.png");
        Result r =
            runVelvet({"pack", "--layout", "gltf-mr", "--out", packed, "--roughness", rough});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const QString out = dir.filePath("out");
        QVERIFY(QDir().mkpath(out + "/metallic.png"));
        r = runVelvet({"unpack", "--layout", "gltf-mr", packed, "--out-dir", out});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("metallic.png"), qPrintable(r.err));
        QCOMPARE(QDir(out).entryList(QDir::Files | QDir::Hidden | QDir::System), QStringList{});
        QVERIFY(QFileInfo(out + "/metallic.png").isDir());
        // The same command succeeds once the folder is gone, and then holds exactly the maps.
        QVERIFY(QDir(out + "/metallic.png").removeRecursively());
        r = runVelvet({"unpack", "--layout", "gltf-mr", packed, "--out-dir", out});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(QDir(out).entryList(QDir::Files | QDir::Hidden, QDir::Name),
                 (QStringList{"metallic.png", "occlusion.png", "roughness.png"}));
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
