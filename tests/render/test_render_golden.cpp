// Golden image of the default scene, and the missing-HDRI fallback.
//
// Regenerating the golden (only after a deliberate change to the image, reviewed by eye):
//   VELVET_UPDATE_GOLDENS=1 ctest --test-dir build -R test_render_golden
// rewrites tests/render/golden/default_scene_128.png and passes; commit the new PNG.
#include "core/image.h"
#include "render/offscreen.h"
#include "render_test_util.h"

#include <QtTest>
#include <cstdlib>

using namespace velvet;

namespace {

const char* kGolden = VELVET_SOURCE_DIR "/tests/render/golden/default_scene_128.png";

} // namespace

class TestRenderGolden : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
    }

    // DESIGN.md's rule: a pixel differs when any channel differs by more than 5/255; the test
    // fails when more than 0.1 % of the pixels differ.
    void defaultSceneMatchesGolden() {
        render::FrameSettings fs;
        fs.width = fs.height = 128;
        Image display;
        std::string error;
        Problems problems;
        QVERIFY2(render::renderSceneOffscreen(test::shippedDefaultScene(), fs, nullptr, &display,
                                              &error, &problems),
                 error.c_str());
        QVERIFY(problems.items.empty());
        if (test::updateGoldens()) {
            QVERIFY2(writeImage(kGolden, display, PixelFormat::UInt8, &error), error.c_str());
            qWarning("VELVET_UPDATE_GOLDENS=1: rewrote %s", kGolden);
            return;
        }
        Image golden;
        QVERIFY2(readImage(kGolden, golden, &error), error.c_str());
        QCOMPARE(golden.width, display.width);
        QCOMPARE(golden.height, display.height);
        int differing = 0;
        float worst = 0.0f;
        for (int y = 0; y < golden.height; ++y)
            for (int x = 0; x < golden.width; ++x) {
                const glm::vec4 a = golden.rgba(x, y), b = display.rgba(x, y);
                float d = 0.0f;
                for (int k = 0; k < 3; ++k)
                    d = std::max(d,
                                 std::abs(std::round(a[k] * 255.0f) - std::round(b[k] * 255.0f)));
                worst = std::max(worst, d);
                differing += d > 5.0f;
            }
        const double fraction = double(differing) / (golden.width * golden.height);
        qInfo("golden: %d pixels differ (%.3f %%), worst channel difference %.0f/255", differing,
              100.0 * fraction, worst);
        if (fraction > 0.001) {
            const std::string actual =
                QDir::tempPath().toStdString() + "/default_scene_128_actual.png";
            writeImage(actual, display, PixelFormat::UInt8, nullptr);
            QFAIL(
                qPrintable(QString("%1 % of pixels differ from the golden; this run's image is %2")
                               .arg(100.0 * fraction)
                               .arg(QString::fromStdString(actual))));
        }
    }

    // A missing HDRI is a warning naming the file, and the frame still renders (grey fallback).
    void missingHdriWarnsAndRenders() {
        Scene scene = test::shippedDefaultScene();
        scene.environment.hdri = "/nonexistent/velvet/missing_studio.exr";
        render::FrameSettings fs;
        fs.width = fs.height = 64;
        Image linear;
        std::string error;
        Problems problems;
        QVERIFY2(render::renderSceneOffscreen(scene, fs, &linear, nullptr, &error, &problems),
                 error.c_str());
        QCOMPARE(problems.items.size(), size_t(1));
        const Problem& p = problems.items.front();
        QCOMPARE(p.severity, Problem::Severity::Warning);
        QVERIFY2(p.toString().find("missing_studio.exr") != std::string::npos,
                 p.toString().c_str());
        qInfo("warning: %s", p.toString().c_str());
        // The background is the uniform grey fallback; the sphere is lit.
        QCOMPARE(linear.rgba(0, 0).x, 0.5f);
        QVERIFY(linear.rgba(32, 32).x > 0.01f);
    }
};

QTEST_GUILESS_MAIN(TestRenderGolden)
#include "test_render_golden.moc"
