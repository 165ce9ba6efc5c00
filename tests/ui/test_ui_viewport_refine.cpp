// The still viewport's progressive anti-aliasing in the real MainWindow under xvfb-run
// (ui/viewport_progressive.cpp, render/progressive_accumulation.h): at rest the viewport refines
// and then stops drawing; a change or a resize shows the plain frame at once; screenshots take
// the settled mean, plain grabs the plain frame; the toolbar's Refine turns it off and is
// remembered with the Timings toggle; a glossy metal settles to its sampled reflections; a slider
// dragged on the default velvet draws the lighting alone, the G-buffer kept.
#include "render/renderer.h"
#include "ui/document_controller.h"
#include "ui/main_window.h"
#include "ui/viewport_toolbar.h"
#include "ui/viewport_widget.h"
#include "ui_test_util.h"

#include <QAction>
#include <QApplication>
#include <QColor>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QLabel>
#include <QSettings>
#include <QStandardPaths>
#include <QTest>
#include <QUndoStack>
#include <algorithm>
#include <cstdlib>

using namespace velvet;
using namespace velvet::ui;
using velvet::test::kFrameTimeoutMs;

class TestUiViewportRefine : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void stillViewRefinesThenStops();
    void aResizeWhileRefiningShowsThePlainFrame();
    void aGrabLeavesTheSettledViewSettled();
    void aGlossyMetalSettlesToItsSampledReflections();
    void aSliderDragKeepsTheGBuffer();

private:
    QImage viewportImage() { return m_window->viewport()->grabFramebuffer(); }
    template <class T>
    T* find(const QString& name) {
        return test::findNamed<T>(m_window.get(), name);
    }

    std::unique_ptr<MainWindow> m_window;
};

void TestUiViewportRefine::initTestCase() {
    m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
    const QString up = test::showWithFirstFrame(m_window.get(), {800, 600});
    QVERIFY2(up.isEmpty(), qPrintable(up));
}

void TestUiViewportRefine::cleanupTestCase() {
    QVERIFY(m_window->close());
    m_window.reset();
}

void TestUiViewportRefine::stillViewRefinesThenStops() {
    // At rest the viewport averages kProgressiveSamples jittered frames, then draws nothing; the
    // mean smooths the silhouette and leaves the sphere's inside as it was; a change shows the
    // plain frame at once; the toolbar's Refine turns it off and is remembered.
    ViewportWidget* viewport = m_window->viewport();
    auto* refine = m_window->findChild<QAction*>(QStringLiteral("progressiveAntialiasAction"));
    QVERIFY(refine);
    QVERIFY2(refine->isChecked(), "on by default");
    QElapsedTimer settling;
    settling.start();
    viewport->requestFrame();
    QVERIFY(QTest::qWaitFor(
        [&] { return viewport->progressiveSamples() >= ViewportWidget::kProgressiveSamples; },
        kFrameTimeoutMs));
    qInfo("refined in %lld ms after a change (%dx%d)", settling.elapsed(), viewport->width(),
          viewport->height());
    // The status bar says so.
    auto* frameTime = m_window->findChild<QLabel*>(QStringLiteral("frameTime"));
    QVERIFY(frameTime);
    QVERIFY2(frameTime->text().contains(QStringLiteral("Refined 16/16")),
             qPrintable(frameTime->text()));
    const int frames = viewport->frameCount();
    QTest::qWait(4 * ViewportWidget::kProgressiveDelayMs);
    QCOMPARE(viewport->frameCount(), frames); // converged: the idle editor costs nothing
    // What a screenshot takes: the settled mean; a plain grab stays the plain frame.
    const QImage refined = viewport->grabDecorated().convertToFormat(QImage::Format_RGB32);
    const QImage unrefined = viewportImage();

    // A change: the next frame is a plain one, and the refinement starts over after it.
    int samplesAfterChange = -1;
    const auto afterChange = connect(viewport, &ViewportWidget::frameCompleted, this, [&] {
        if (samplesAfterChange < 0)
            samplesAfterChange = viewport->progressiveSamples();
    });
    find<QDoubleSpinBox>(QStringLiteral("exposureSpin"))->setValue(0.5);
    QVERIFY(QTest::qWaitFor([&] { return samplesAfterChange >= 0; }, kFrameTimeoutMs));
    disconnect(afterChange);
    QCOMPARE(samplesAfterChange, 0); // the first frame after the change is a plain one
    find<QDoubleSpinBox>(QStringLiteral("exposureSpin"))->setValue(0.0);
    QVERIFY(QTest::qWaitFor(
        [&] { return viewport->progressiveSamples() >= ViewportWidget::kProgressiveSamples; },
        kFrameTimeoutMs));

    refine->trigger();
    QVERIFY(!viewport->progressiveAntialiasing());
    QCOMPARE(QSettings().value(QStringLiteral("viewport/progressiveAntialias")).toBool(), false);
    const QImage plain = viewportImage();
    QVERIFY2(plain == unrefined, "a plain grab is the plain frame, refined view or not");
    QCOMPARE(viewport->progressiveSamples(), 0);
    QTest::qWait(4 * ViewportWidget::kProgressiveDelayMs);
    QCOMPARE(viewport->progressiveSamples(), 0);

    // The silhouette's pixels change (the plain frame's steps become blends), the sphere's
    // inside does not.
    QCOMPARE(refined.size(), plain.size());
    int total = 0, changed = 0;
    const int cx = plain.width() / 2, cy = plain.height() / 2;
    for (int y = 0; y < plain.height(); ++y)
        for (int x = 0; x < plain.width(); ++x) {
            const QColor a = refined.pixelColor(x, y), b = plain.pixelColor(x, y);
            const int d = std::max({std::abs(a.red() - b.red()), std::abs(a.green() - b.green()),
                                    std::abs(a.blue() - b.blue())});
            if (d > 8)
                ++changed;
            if (std::abs(x - cx) < 20 && std::abs(y - cy) < 20)
                QVERIFY2(d <= 3, qPrintable(QStringLiteral("inside the sphere: %1").arg(d)));
            ++total;
        }
    QVERIFY2(changed > 50, qPrintable(QStringLiteral("%1 pixels smoothed").arg(changed)));
    QVERIFY2(changed * 20 < total, "only the edges and fine detail change");

    refine->trigger();
    QVERIFY(viewport->progressiveAntialiasing());
    QCOMPARE(QSettings().value(QStringLiteral("viewport/progressiveAntialias")).toBool(), true);

    // Refine off with Timings on comes back as it was saved (restoring the one toggle saved the
    // whole toolbar, the other's default included, over the stored state).
    auto* toolbar = m_window->findChild<ViewportToolbar*>();
    QVERIFY(toolbar);
    {
        QSettings settings;
        settings.setValue(QStringLiteral("viewport/timingOverlay"), true);
        settings.setValue(QStringLiteral("viewport/progressiveAntialias"), false);
    }
    toolbar->restoreSettings();
    QVERIFY(toolbar->timingOverlay());
    QVERIFY(!refine->isChecked());
    QVERIFY(!viewport->progressiveAntialiasing());
    QCOMPARE(QSettings().value(QStringLiteral("viewport/progressiveAntialias")).toBool(), false);
    refine->trigger();
    find<QAction>(QStringLiteral("timingOverlayAction"))->trigger();
    QVERIFY(!toolbar->timingOverlay());
    QVERIFY(viewport->progressiveAntialiasing());
}

void TestUiViewportRefine::aResizeWhileRefiningShowsThePlainFrame() {
    // Resized part way through the refinement: the first frame at the new size is a plain one
    // (not the next jittered frame starting a mean of its own), and the refinement starts over.
    ViewportWidget* viewport = m_window->viewport();
    const QSize before = viewport->glWindow()->size();
    bool resized = false;
    int samplesWhenResized = -1, firstAtNewSize = -1;
    const auto watch = connect(viewport, &ViewportWidget::frameCompleted, this, [&] {
        if (!resized && viewport->progressiveSamples() == 3) {
            resized = true; // between two refinement frames, synchronously; fixed, so that the
                            // main window's next layout keeps it
            samplesWhenResized = viewport->progressiveSamples();
            viewport->setFixedSize(viewport->width() + 24, viewport->height());
        } else if (resized && firstAtNewSize < 0 && viewport->glWindow()->size() != before) {
            firstAtNewSize = viewport->progressiveSamples();
        }
    });
    viewport->requestFrame();
    const bool seen = QTest::qWaitFor([&] { return firstAtNewSize >= 0; }, kFrameTimeoutMs);
    disconnect(watch);
    viewport->setMinimumSize(0, 0);
    viewport->setMaximumSize(QWIDGETSIZE_MAX, QWIDGETSIZE_MAX);
    QVERIFY2(seen, "no frame at the new size");
    QCOMPARE(samplesWhenResized, 3);
    QCOMPARE(firstAtNewSize, 0);
    QVERIFY(QTest::qWaitFor(
        [&] { return viewport->progressiveSamples() >= ViewportWidget::kProgressiveSamples; },
        kFrameTimeoutMs));
}

void TestUiViewportRefine::aGrabLeavesTheSettledViewSettled() {
    // A grab that takes a pending change the window does not draw (an atlas document) leaves the
    // settled mean on screen, its count in the status bar and no frame to come.
    ViewportWidget* viewport = m_window->viewport();
    viewport->requestFrame();
    QVERIFY(QTest::qWaitFor(
        [&] { return viewport->progressiveSamples() >= ViewportWidget::kProgressiveSamples; },
        kFrameTimeoutMs));
    viewport->setScene(m_window->controller()->scene(), ScenePart::Atlases);
    const QImage grabbed = viewportImage();
    QVERIFY(!grabbed.isNull());
    QCOMPARE(viewport->progressiveSamples(), ViewportWidget::kProgressiveSamples);
    const int frames = viewport->frameCount();
    QTest::qWait(4 * ViewportWidget::kProgressiveDelayMs);
    QCOMPARE(viewport->frameCount(), frames);
    QCOMPARE(viewport->progressiveSamples(), ViewportWidget::kProgressiveSamples);
}

void TestUiViewportRefine::aGlossyMetalSettlesToItsSampledReflections() {
    // The refinement's frames sample a glossy lobe's reflections (FrameSettings::
    // reflectionSamples) where the plain frame takes the split sum's one lookup: for a glossy
    // metal the settled mean differs from the plain frame over the sphere's whole grazing ring,
    // not only on the silhouette as for the rough velvet above (under 5 % of the pixels there).
    m_window->controller()->setMaterial(test::glossyCopper(), "copper");
    ViewportWidget* viewport = m_window->viewport();
    QVERIFY(QTest::qWaitFor([&] { return viewport->progressiveSamples() == 0; }, kFrameTimeoutMs));
    QVERIFY(QTest::qWaitFor(
        [&] { return viewport->progressiveSamples() >= ViewportWidget::kProgressiveSamples; },
        kFrameTimeoutMs));
    const QImage refined = viewport->grabDecorated().convertToFormat(QImage::Format_RGB32);
    const QImage plain = viewportImage().convertToFormat(QImage::Format_RGB32);
    QCOMPARE(refined.size(), plain.size());
    int total = 0, changed = 0;
    for (int y = 0; y < plain.height(); ++y)
        for (int x = 0; x < plain.width(); ++x) {
            const QColor a = refined.pixelColor(x, y), b = plain.pixelColor(x, y);
            changed += std::max({std::abs(a.red() - b.red()), std::abs(a.green() - b.green()),
                                 std::abs(a.blue() - b.blue())}) > 8;
            ++total;
        }
    qInfo("glossy copper: %d of %d pixels changed by the refinement", changed, total);
    QVERIFY2(changed * 20 > total, qPrintable(QStringLiteral("%1 pixels").arg(changed)));
}

void TestUiViewportRefine::aSliderDragKeepsTheGBuffer() {
    // A drag of the roughness slider: edits in quick succession under one merge key. The
    // velvet's values are the same at every pixel, so after the drag's first (reduced) frame
    // every frame keeps the G-buffer (render::FramePasses::gbufferKept) and draws the lighting
    // alone; the refinement at rest, jittered, draws it again.
    ViewportWidget* viewport = m_window->viewport();
    DocumentController* doc = m_window->controller();
    doc->newDocument();
    QTRY_VERIFY_WITH_TIMEOUT(viewport->frameCount() > 0, kFrameTimeoutMs);
    int kept = 0, frames = 0;
    const QMetaObject::Connection noted =
        connect(viewport, &ViewportWidget::frameCompleted, this, [&] {
            ++frames;
            kept += viewport->renderer()->lastFramePasses().gbufferKept ? 1 : 0;
        });
    for (int i = 0; i < 8; ++i) {
        doc->editParam(ParamId::Roughness, glm::vec3(0.5f + 0.03f * float(i)), 4343);
        const int before = frames;
        QTRY_VERIFY_WITH_TIMEOUT(frames > before, kFrameTimeoutMs);
    }
    disconnect(noted);
    qInfo("%d of %d frames of the drag kept the G-buffer", kept, frames);
    QVERIFY2(kept >= 4, qPrintable(QString::number(kept)));
    QCOMPARE(doc->undoStack()->count(), 1); // one merged step
    doc->undoStack()->undo();                // clean again: the window closes without asking
    QVERIFY(doc->undoStack()->isClean());
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetViewportRefineTest"));
    QApplication::setOrganizationName(QStringLiteral("VelvetTest"));
    TestUiViewportRefine test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_ui_viewport_refine.moc"
