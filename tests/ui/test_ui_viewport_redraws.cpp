// What the viewport draws, and when, in the real MainWindow under xvfb-run: the timing overlay
// leaves the picture as it was; a screenshot composes the viewport's frame (QWidget::grab leaves
// the native GL window out); a scene that reads the time (film grain) keeps frames coming, and
// only it, unless paused; an image edited in another program redraws an idle viewport.
#include "core/image.h"
#include "core/post_effects.h"
#include "ui/document_controller.h"
#include "ui/main_window.h"
#include "ui/screenshot.h"
#include "ui/viewport_widget.h"
#include "ui_test_util.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>
#include <QWindow>

using namespace velvet;
using namespace velvet::ui;
using velvet::test::centrePixel;
using velvet::test::describe;
using velvet::test::kFrameTimeoutMs;
using velvet::test::luma;
using velvet::test::maxDifference;

namespace {

/// A 16 x 16 opaque image of one colour (display-encoded sRGB values, as a PNG holds them).
Image flatImage(glm::vec3 rgb) {
    Image img(16, 16, 4);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            float* p = img.at(x, y);
            p[0] = rgb.r, p[1] = rgb.g, p[2] = rgb.b, p[3] = 1.0f;
        }
    return img;
}

} // namespace

class TestUiViewportRedraws : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void init();

    void timingOverlayKeepsPicture();
    void screenshotIncludesViewport();
    void animationRunsOnlyWhileSceneReadsTime();
    void editedTextureFileRedrawsIdleViewport();

private:
    QImage viewportImage() { return m_window->viewport()->grabFramebuffer(); }
    /// The native window the viewport draws in: where the window system sends its events.
    QWindow* glWindow() { return m_window->viewport()->glWindow(); }

    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
};

void TestUiViewportRedraws::initTestCase() {
    m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
    m_doc = m_window->controller();
    const QString up = test::showWithFirstFrame(m_window.get(), {800, 600});
    QVERIFY2(up.isEmpty(), qPrintable(up));
}

void TestUiViewportRedraws::cleanupTestCase() {
    m_doc->newDocument();
    QVERIFY(m_window->close());
    m_window.reset();
}

void TestUiViewportRedraws::init() {
    m_doc->newDocument();
}

void TestUiViewportRedraws::timingOverlayKeepsPicture() {
    // The overlay is painted over the GL window by Qt's paint engine after the renderer's frame:
    // the frames that follow still draw the same picture.
    ViewportWidget* viewport = m_window->viewport();
    const QVector<double> before = centrePixel(viewportImage());
    viewport->setTimingOverlayVisible(true);
    QVERIFY(viewport->isTimingOverlayVisible());
    for (int i = 0; i < 3; ++i) {
        QSignalSpy swapped(glWindow(), SIGNAL(frameSwapped()));
        viewport->requestFrame();
        QVERIFY(swapped.wait(kFrameTimeoutMs));
    }
    QVERIFY(viewport->errorMessage().isEmpty());
    const QVector<double> during = centrePixel(viewportImage());
    viewport->setTimingOverlayVisible(false);
    QVERIFY2(maxDifference(before, during) < 2.0,
             qPrintable(describe(before) + " vs " + describe(during)));
}

void TestUiViewportRedraws::screenshotIncludesViewport() {
    // QWidget::grab leaves the native GL window out; the screenshot paints the viewport's frame
    // where it sits.
    ViewportWidget* viewport = m_window->viewport();
    const QImage shot = grabWithViewports(m_window.get()).convertToFormat(QImage::Format_RGB32);
    QCOMPARE(shot.size(), m_window->size() * m_window->devicePixelRatio());
    const QImage frame = viewportImage();
    const QPoint origin = viewport->mapTo(m_window.get(), QPoint(0, 0));
    const QImage inShot = shot.copy(QRect(origin, viewport->size()));
    const QVector<double> expected = centrePixel(frame), found = centrePixel(inShot);
    QVERIFY2(maxDifference(expected, found) < 2.0,
             qPrintable(describe(expected) + " vs " + describe(found)));
    QVERIFY2(luma(found) > 5.0, qPrintable(describe(found))); // the lit sphere, not black
}

// Film grain reads time: the viewport keeps drawing and its time advances; paused, or with a
// still chain, no frame comes without a change and the time stays where it was.
void TestUiViewportRedraws::animationRunsOnlyWhileSceneReadsTime() {
    ViewportWidget* viewport = m_window->viewport();
    // True once no frame has come for 500 ms (the frame a change asks for may take a while on a
    // loaded llvmpipe); false if frames keep coming for @p deadlineMs.
    const auto settles = [viewport](int deadlineMs = 30000) {
        QElapsedTimer deadline;
        deadline.start();
        int frames = viewport->frameCount();
        QElapsedTimer quiet;
        quiet.start();
        while (deadline.elapsed() < deadlineMs) {
            QTest::qWait(50);
            if (viewport->frameCount() != frames) {
                frames = viewport->frameCount();
                quiet.restart();
            } else if (quiet.elapsed() >= 500) {
                return true;
            }
        }
        return false;
    };
    Scene still = m_doc->scene();
    still.environment.background = BackgroundMode::Sharp;
    still.post = defaultPostChain();
    QVERIFY(!sceneReadsTime(still));
    viewport->setScene(still);
    QVERIFY(!viewport->isAnimating());
    const double stillTime = viewport->animationTime();
    QVERIFY(settles());
    QCOMPARE(viewport->animationTime(), stillTime);

    Scene grain = still;
    grain.post.effects.push_back(makeEffect("film_grain"));
    grain.post.effects.back().params["intensity"] = {0.5f};
    QVERIFY(sceneReadsTime(grain));
    viewport->setScene(grain);
    QVERIFY(viewport->isAnimating());
    const int frames = viewport->frameCount();
    QTRY_VERIFY_WITH_TIMEOUT(viewport->frameCount() >= frames + 3, 20000);
    QVERIFY(!settles(2000)); // frames keep coming without any change
    QVERIFY(viewport->animationTime() > stillTime);
    // Two grabs at different times differ (the grain moved).
    const QImage a = viewportImage();
    QTest::qWait(120); // > 1/24 s: a new grain pattern
    const QImage b = viewportImage();
    QVERIFY(a != b);

    viewport->setAnimationPaused(true);
    QVERIFY(!viewport->isAnimating());
    const double paused = viewport->animationTime();
    QVERIFY(settles());
    QCOMPARE(viewport->animationTime(), paused);
    QVERIFY(viewportImage() == viewportImage()); // a paused frame is repeatable
    viewport->setAnimationPaused(false);
    QVERIFY(viewport->isAnimating());

    // Disabling the only time-dependent effect stops the clock too.
    grain.post.effects.back().enabled = false;
    viewport->setScene(grain);
    QVERIFY(!viewport->isAnimating());
    QVERIFY(settles());
    viewport->setScene(m_doc->scene());
}

// An image edited in another program shows in an idle viewport: the texture file watcher
// (ui/texture_file_watcher.h) asks for a frame when the base colour's file changes on disk, and
// that frame re-uploads it (nothing else asks for one while the test waits).
void TestUiViewportRedraws::editedTextureFileRedrawsIdleViewport() {
    QTemporaryDir dir;
    const std::string file = dir.filePath(QStringLiteral("base.png")).toStdString();
    std::string error;
    QVERIFY2(writeImage(file, flatImage({1.0f, 0.0f, 0.0f}), PixelFormat::UInt8, &error),
             error.c_str());
    TextureRef ref;
    ref.file = file;
    m_doc->setTexture(TextureSlot::BaseColor, ref);
    // Textures load off the drawing thread (issue 16): the map shows a few frames later.
    QVector<double> red;
    const auto isRed = [&] {
        red = centrePixel(viewportImage());
        return red[0] > red[2] + 20.0;
    };
    QTRY_VERIFY2_WITH_TIMEOUT(isRed(), qPrintable(describe(red)), 20000);

    // Idle: no frame for a second (the environment bake and the refine timer are done).
    ViewportWidget* viewport = m_window->viewport();
    QSignalSpy frames(viewport, &ViewportWidget::frameCompleted);
    QElapsedTimer quiet;
    quiet.start();
    while (quiet.elapsed() < 1000) {
        const qsizetype before = frames.count();
        QTest::qWait(100);
        if (frames.count() != before)
            quiet.restart();
        QVERIFY2(frames.count() < 2000, "the viewport never goes idle");
    }
    frames.clear();
    QVERIFY2(writeImage(file, flatImage({0.0f, 0.0f, 1.0f}), PixelFormat::UInt8, &error),
             error.c_str());
    QTRY_VERIFY_WITH_TIMEOUT(!frames.isEmpty(), 10000); // drawn without anyone asking
    // That frame starts the reload; the viewport keeps drawing until the new map is complete.
    QTRY_VERIFY_WITH_TIMEOUT(viewport->textureProgress().loading == 0 && frames.count() >= 2,
                             20000);
    const QVector<double> blue = centrePixel(viewportImage());
    QVERIFY2(blue[2] > blue[0] + 20.0, qPrintable(describe(red) + " -> " + describe(blue)));
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetViewportRedrawsTest"));
    QApplication::setOrganizationName(QStringLiteral("VelvetTest"));
    TestUiViewportRedraws test;
    return QTest::qExec(&test, argc, argv);
}
#include "test_ui_viewport_redraws.moc"
