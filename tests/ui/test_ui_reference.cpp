// The Reference view (issue 15) in the real MainWindow under xvfb-run: Ctrl+Shift+R shows the
// dock and starts the path tracer in the background; images arrive while the UI keeps
// processing events; an edit restarts the render and changes the image; dragging the divider
// puts the viewport's pixels left of it and the reference's right; hiding the dock stops it.
// The ΔE heat map toggle shows each pixel coloured by the CIEDE2000 between the two images the
// split shows, and the status bar states their mean and 95th percentile as the render converges.
#include "core/image_compare.h"
#include "core/image_ops.h"
#include "ui/document_controller.h"
#include "ui/main_window.h"
#include "ui/reference/reference_job.h"
#include "ui/reference/reference_panel.h"
#include "ui/viewport_widget.h"
#include "ui_test_util.h"
#include "ui_test_window.h"

#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QSignalSpy>
#include <QSlider>
#include <QStandardPaths>
#include <QStatusBar>
#include <QSurfaceFormat>
#include <QTimer>
#include <QToolButton>
#include <QtTest>
#include <memory>

using namespace velvet;
using namespace velvet::ui;

class TestUiReference : public QObject {
    Q_OBJECT
    std::unique_ptr<MainWindow> m_window;

private slots:
    void initTestCase() {
        m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
        const QString up = test::showWithFirstFrame(m_window.get(), {1000, 700});
        QVERIFY2(up.isEmpty(), qPrintable(up));
    }
    void cleanupTestCase() {
        m_window->controller()->newDocument();
        QVERIFY(m_window->close());
        m_window.reset();
    }

    void referenceRendersInTheBackgroundAndFollowsEdits() {
        auto* dock = m_window->findChild<QDockWidget*>(QStringLiteral("referenceDock"));
        QVERIFY(dock);
        ReferencePanel* panel = m_window->referencePanel();
        QVERIFY(panel);
        QVERIFY(!dock->isVisible());
        QVERIFY(!panel->active());
        // Let the viewport settle (its first frames bake the environment in slices): what is
        // measured below is the UI thread with the reference running, not the viewport's start.
        QSignalSpy frames(m_window->viewport(), &ViewportWidget::frameCompleted);
        QElapsedTimer settle;
        settle.start();
        int seen = -1;
        while (seen != frames.count() && settle.elapsed() < 60000) {
            seen = frames.count();
            QTest::qWait(1000);
        }
        QTest::keyClick(m_window.get(), Qt::Key_R, Qt::ControlModifier | Qt::ShiftModifier);
        QVERIFY(QTest::qWaitFor([&] { return dock->isVisible(); }));
        QVERIFY(panel->active());
        QVERIFY(QTest::qWaitFor([&] { return panel->passes() >= 1; }, 120000));
        // While it converges the UI thread keeps serving events: a 10 ms timer never waits long
        // (a render on the UI thread would hold it for whole passes).
        QElapsedTimer clock;
        clock.start();
        qint64 last = 0, longest = 0;
        int ticks = 0;
        QTimer tick;
        QObject::connect(&tick, &QTimer::timeout, [&] {
            ++ticks;
            longest = std::max(longest, clock.elapsed() - last);
            last = clock.elapsed();
        });
        tick.start(10);
        QVERIFY(QTest::qWaitFor([&] { return panel->passes() >= 64; }, 120000));
        tick.stop();
        // Relative bounds (the machine may be loaded): no wait as long as a quarter of the
        // render, and at least a tenth of the ticks served.
        const qint64 total = clock.elapsed();
        qInfo("64 samples per pixel in %lld ms; %d ticks of 10 ms; longest UI wait %lld ms", total,
              ticks, longest);
        QVERIFY2(longest * 4 < total,
                 qPrintable(QStringLiteral("the UI waited %1 of %2 ms").arg(longest).arg(total)));
        QVERIFY2(ticks * 100 >= total,
                 qPrintable(QStringLiteral("%1 ticks in %2 ms").arg(ticks).arg(total)));
        const QImage first = panel->view()->composed();
        QVERIFY(!first.isNull());
        QCOMPARE(first.width(), ReferencePanel::kWidth);

        // An edit restarts it: a blue base colour instead of the default's.
        m_window->controller()->editParam(ParamId::BaseColor, glm::vec3(0.05f, 0.1f, 0.9f));
        QVERIFY(QTest::qWaitFor([&] { return panel->passes() == 0; }, 10000));
        QVERIFY(QTest::qWaitFor([&] { return panel->passes() >= 2; }, 120000));
        panel->view()->setSplit(0.0); // all reference
        const QImage blue = panel->view()->composed();
        const QPoint centre(blue.width() / 2, blue.height() / 2);
        const QColor c = blue.pixelColor(centre);
        QVERIFY2(c.blue() > c.red() + 20,
                 qPrintable(QStringLiteral("%1 %2 %3").arg(c.red()).arg(c.green()).arg(c.blue())));
        QVERIFY(first.pixelColor(centre) != c);

        // Dragging the divider (mouse on the view) moves the split; the slider follows.
        auto* slider = panel->findChild<QSlider*>(QStringLiteral("referenceSplit"));
        QVERIFY(slider);
        ReferenceSplitView* view = panel->view();
        const QRect drawn = view->imageRect();
        const QPoint at(drawn.left() + drawn.width() * 3 / 4, drawn.center().y());
        QTest::mousePress(view, Qt::LeftButton, {}, at);
        QTest::mouseRelease(view, Qt::LeftButton, {}, at);
        QVERIFY2(view->split() > 0.55 && view->split() < 0.95,
                 qPrintable(QString::number(view->split())));
        QCOMPARE(slider->value(), int(std::lround(view->split() * 100)));
        // Left of the divider the viewport's snapshot, right of it the reference.
        const QImage split = view->composed();
        const int cut = int(std::lround(view->split() * split.width()));
        const QImage refOnly = [&] {
            view->setSplit(0.0);
            return view->composed();
        }();
        const QImage vpOnly = [&] {
            view->setSplit(1.0);
            return view->composed();
        }();
        const int y = split.height() / 2;
        QCOMPARE(split.pixel(cut / 2, y), vpOnly.pixel(cut / 2, y));
        QCOMPARE(split.pixel((cut + split.width()) / 2, y),
                 refOnly.pixel((cut + split.width()) / 2, y));

        if (const QByteArray shots = qgetenv("VELVET_TEST_SCREENSHOTS"); !shots.isEmpty()) {
            view->setSplit(0.5);
            QApplication::processEvents();
            panel->grab().save(QString::fromUtf8(shots) + QStringLiteral("/reference_panel.png"));
        }
        // Hidden, it stops.
        QTest::keyClick(m_window.get(), Qt::Key_R, Qt::ControlModifier | Qt::ShiftModifier);
        QVERIFY(QTest::qWaitFor([&] { return !panel->active(); }));
    }

    void heatMapShowsTheDeltaEAndTheStatusBarItsMean() {
        auto* dock = m_window->findChild<QDockWidget*>(QStringLiteral("referenceDock"));
        ReferencePanel* panel = m_window->referencePanel();
        QVERIFY(dock && panel && !panel->active());
        QSignalSpy lines(panel, &ReferencePanel::status);
        QTest::keyClick(m_window.get(), Qt::Key_R, Qt::ControlModifier | Qt::ShiftModifier);
        QVERIFY(QTest::qWaitFor([&] { return panel->active(); }));
        QVERIFY(QTest::qWaitFor([&] { return panel->passes() >= 1; }, 120000));
        const double meanAtFirst = panel->deltaEStats().mean;
        QVERIFY(QTest::qWaitFor([&] { return panel->passes() >= 32; }, 240000));

        // The toggle (a click on the real button) swaps the split for the heat map.
        auto* toggle = panel->findChild<QToolButton*>(QStringLiteral("referenceHeatMap"));
        auto* slider = panel->findChild<QSlider*>(QStringLiteral("referenceSplit"));
        QVERIFY(toggle && slider);
        ReferenceSplitView* view = panel->view();
        QVERIFY(!view->heatMapShown());
        QTest::mouseClick(toggle, Qt::LeftButton);
        QVERIFY(view->heatMapShown());
        QVERIFY(!slider->isEnabled());
        // No event is processed from here on, so the images and the ΔE below are one frame's.
        QVERIFY(QTest::qWaitFor([&] { return !view->coverage().pixels.empty(); }));
        const QImage heat = view->composed();
        view->setHeatMapShown(false);
        view->setSplit(1.0);
        const QImage viewportShown = view->composed();
        view->setSplit(0.0);
        const QImage referenceShown = view->composed();
        view->setHeatMapShown(true);
        QVERIFY(!heat.isNull());
        QCOMPARE(heat.size(), referenceShown.size());

        // The ΔE recomputed here from the two images the split shows (one display transform for
        // both: the panel compares exactly what it shows).
        Image deltaE;
        DeltaEStats stats;
        std::string error;
        QVERIFY2(compareImages(ReferenceJob::fromQImage(viewportShown),
                               ReferenceJob::fromQImage(referenceShown), deltaE, stats, &error),
                 error.c_str());
        // ... over the pixels the mesh covers (the sphere: a disc of them, the corners not).
        const Image& coverage = view->coverage();
        QCOMPARE(coverage.width, heat.width());
        const QPoint centre(heat.width() / 2, heat.height() / 2);
        QCOMPARE(*coverage.at(centre.x(), centre.y()), 1.0f);
        QCOMPARE(*coverage.at(0, 0), 0.0f);
        stats = deltaEStats(deltaE, coverage);
        QVERIFY(stats.pixels > 100);
        QCOMPARE(stats.pixels, panel->deltaEStats().pixels);
        QVERIFY(std::abs(stats.mean - panel->deltaEStats().mean) < 1e-9);
        QVERIFY(std::abs(stats.p95 - panel->deltaEStats().p95) < 1e-9);
        // Each covered pixel coloured by its ΔE on the scale black 0 .. red kHeatMapMax; the
        // others grey (the viewport dimmed).
        int wrong = 0, coloured = 0, grey = 0;
        for (int y = 0; y < heat.height(); ++y)
            for (int x = 0; x < heat.width(); ++x) {
                const QColor got = heat.pixelColor(x, y);
                if (*coverage.at(x, y) < 1.0f) {
                    const int g = qGray(viewportShown.pixel(x, y)) / 2;
                    wrong += got == QColor(g, g, g) ? 0 : 1;
                    ++grey;
                    continue;
                }
                const glm::vec3 want =
                    heatMapColor(*deltaE.at(x, y), ReferenceSplitView::kHeatMapMax) * 255.0f;
                if (std::abs(got.red() - want.r) > 1.0f || std::abs(got.green() - want.g) > 1.0f ||
                    std::abs(got.blue() - want.b) > 1.0f)
                    ++wrong;
                if (got.red() != got.green() || got.green() != got.blue())
                    ++coloured; // a hue: ΔE above 0 (black is 0)
            }
        QCOMPARE(wrong, 0);
        qInfo("ΔE on the mesh at %d spp: mean %.3f, p95 %.3f, max %.3f over %zu pixels; %d grey",
              panel->passes(), stats.mean, stats.p95, stats.max, stats.pixels, grey);
        QVERIFY(grey > 0 && coloured > 0);

        // The status bar states the mean and the 95th percentile of the image shown.
        const QString shown = m_window->statusBar()->currentMessage();
        QVERIFY2(shown.contains(QStringLiteral("mean %1").arg(stats.mean, 0, 'f', 2)) &&
                     shown.contains(QStringLiteral("p95 %1").arg(stats.p95, 0, 'f', 2)),
                 qPrintable(shown));
        // ... updated as the reference converged: a line per image, its noise falling.
        QVERIFY2(lines.count() >= 6, qPrintable(QString::number(lines.count())));
        QVERIFY2(stats.mean < meanAtFirst,
                 qPrintable(QStringLiteral("%1 -> %2").arg(meanAtFirst).arg(stats.mean)));

        if (const QByteArray shots = qgetenv("VELVET_TEST_SCREENSHOTS"); !shots.isEmpty())
            panel->grab().save(QString::fromUtf8(shots) + QStringLiteral("/reference_heatmap.png"));

        // One display transform for both: +1 EV typed into the toolbar's exposure restarts the
        // reference and brightens both images; the ΔE stays about what it was (exposing only one
        // side would shift L* by ten or more everywhere).
        auto* exposure = m_window->findChild<QDoubleSpinBox*>(QStringLiteral("exposureSpin"));
        QVERIFY(exposure);
        const QColor vpBefore = viewportShown.pixelColor(heat.width() / 2, heat.height() / 2);
        const QColor refBefore = referenceShown.pixelColor(heat.width() / 2, heat.height() / 2);
        exposure->setFocus();
        QTest::keyClick(exposure, Qt::Key_A, Qt::ControlModifier);
        QTest::keyClicks(exposure, QStringLiteral("1"));
        QTest::keyClick(exposure, Qt::Key_Return);
        QCOMPARE(m_window->viewport()->frameSettings().exposureEv, 1.0f);
        QVERIFY(QTest::qWaitFor([&] { return panel->passes() == 0; }, 10000));
        QVERIFY(QTest::qWaitFor([&] { return panel->passes() >= 32; }, 240000));
        view->setHeatMapShown(false);
        view->setSplit(1.0);
        const QColor vpAfter = view->composed().pixelColor(heat.width() / 2, heat.height() / 2);
        view->setSplit(0.0);
        const QColor refAfter = view->composed().pixelColor(heat.width() / 2, heat.height() / 2);
        QVERIFY2(vpAfter.lightness() > vpBefore.lightness() + 10 &&
                     refAfter.lightness() > refBefore.lightness() + 10,
                 qPrintable(QStringLiteral("viewport %1 -> %2, reference %3 -> %4")
                                .arg(vpBefore.lightness())
                                .arg(vpAfter.lightness())
                                .arg(refBefore.lightness())
                                .arg(refAfter.lightness())));
        const DeltaEStats exposed = panel->deltaEStats();
        qInfo("+1 EV: ΔE on the mesh mean %.3f, p95 %.3f (was %.3f, %.3f)", exposed.mean,
              exposed.p95, stats.mean, stats.p95);
        QVERIFY2(exposed.pixels > 0 && exposed.mean < stats.mean * 1.5 + 1.0,
                 qPrintable(QString::number(exposed.mean)));
        // A debug view's image holds raw values, not light: no ΔE, and the panel says why.
        auto* debugView = m_window->findChild<QComboBox*>(QStringLiteral("debugViewCombo"));
        QVERIFY(debugView && debugView->count() > 1);
        debugView->setCurrentIndex(1);
        QVERIFY(QTest::qWaitFor([&] { return panel->passes() == 0; }, 10000));
        QVERIFY(QTest::qWaitFor([&] { return panel->passes() >= 1; }, 120000));
        QCOMPARE(panel->deltaEStats().pixels, size_t(0));
        QVERIFY2(m_window->statusBar()->currentMessage().contains(QStringLiteral("debug view")),
                 qPrintable(m_window->statusBar()->currentMessage()));
        debugView->setCurrentIndex(0);
        exposure->setValue(0.0);
        view->setHeatMapShown(true);
        QTest::mouseClick(toggle, Qt::LeftButton); // back to the split
        QVERIFY(!view->heatMapShown() && slider->isEnabled());
        QTest::keyClick(m_window.get(), Qt::Key_R, Qt::ControlModifier | Qt::ShiftModifier);
        QVERIFY(QTest::qWaitFor([&] { return !panel->active(); }));
        QVERIFY(m_window->statusBar()->currentMessage().isEmpty());
    }

    // The panel compares the view the artist judges at rest: with the viewport's refinement on,
    // a glossy metal's reflections are sampled as the settled view samples them, which the path
    // tracer agrees with more closely than the split sum a moving view draws (refinement off).
    void aGlossyMetalIsComparedAsItStandsAtRest() {
        ReferencePanel* panel = m_window->referencePanel();
        auto* refine = m_window->findChild<QAction*>(QStringLiteral("progressiveAntialiasAction"));
        QVERIFY(panel && refine && refine->isChecked());
        m_window->controller()->setMaterial(test::glossyCopper(), "copper");
        QTest::keyClick(m_window.get(), Qt::Key_R, Qt::ControlModifier | Qt::ShiftModifier);
        QVERIFY(QTest::qWaitFor([&] { return panel->active(); }));
        const auto meanAfterRestart = [&] {
            m_window->controller()->setParam(ParamId::Roughness, glm::vec3(0.25f));
            // A wait that times out gives no mean (the comparison below then fails).
            if (!QTest::qWaitFor([&] { return panel->passes() == 0; }, 10000) ||
                !QTest::qWaitFor([&] { return panel->passes() >= 64; }, 240000))
                return -1.0;
            return panel->deltaEStats().mean;
        };
        m_window->controller()->setParam(ParamId::Roughness, glm::vec3(0.3f));
        const double atRest = meanAfterRestart();
        refine->trigger(); // off: the viewport shows the split sum's frames
        m_window->controller()->setParam(ParamId::Roughness, glm::vec3(0.3f));
        const double moving = meanAfterRestart();
        refine->trigger();
        qInfo("glossy copper against the reference: mean ΔE2000 %.3f as at rest, %.3f with the "
              "split sum",
              atRest, moving);
        QVERIFY2(atRest > 0.0 && atRest < moving * 0.7,
                 qPrintable(QString::number(atRest) + " " + QString::number(moving)));
        QTest::keyClick(m_window.get(), Qt::Key_R, Qt::ControlModifier | Qt::ShiftModifier);
        QVERIFY(QTest::qWaitFor([&] { return !panel->active(); }));
    }

    // On a mesh that lights itself (the shader ball's cavities) the view at rest is the mean of
    // the refinement's frames, each with one bounce more than the one before: the panel compares
    // the reference with that mean once the view settles, not with a single frame, which holds
    // one bounce and is darker in the cavities.
    void theShaderBallIsComparedWithEveryBounceItShowsAtRest() {
        ReferencePanel* panel = m_window->referencePanel();
        ViewportWidget* viewport = m_window->viewport();
        QVERIFY(panel && viewport->progressiveAntialiasing());
        Material white;
        white.setColor(ParamId::BaseColor, glm::vec3(0.9f));
        white.setScalar(ParamId::Roughness, 1.0f); // the split sum's reflections: no samples' noise
        white.setScalar(ParamId::SheenWeight, 0.0f);
        m_window->controller()->setMaterial(white, "white");
        m_window->controller()->setMesh(MeshRef{PreviewMeshKind::ShaderBall, {}});
        // The view at rest before the panel opens, as the artist sees it.
        QVERIFY(QTest::qWaitFor(
            [&] { return viewport->progressiveSamples() == ViewportWidget::kProgressiveSamples; },
            240000));
        const QImage shownBefore = viewport->grabFramebuffer(nullptr, /*settled=*/true);
        QTest::keyClick(m_window.get(), Qt::Key_R, Qt::ControlModifier | Qt::ShiftModifier);
        QVERIFY(QTest::qWaitFor([&] { return panel->active(); }));
        QVERIFY(viewport->keepsSettledLinear());
        QVERIFY(QTest::qWaitFor([&] { return panel->comparesSettledView(); }, 240000));
        const Image settled = viewport->settledLinear();
        QVERIFY(!settled.empty());
        QCOMPARE(viewport->progressiveSamples(), ViewportWidget::kProgressiveSamples);
        // Keeping the refinement's linear frames (no display step inside the lighting pass)
        // leaves what the viewport shows at rest as it was.
        const QImage shownAfter = viewport->grabFramebuffer(nullptr, /*settled=*/true);
        QCOMPARE(shownAfter.size(), shownBefore.size());
        int worst = 0;
        for (int y = 0; y < shownAfter.height(); ++y)
            for (int x = 0; x < shownAfter.width(); ++x) {
                const QRgb a = shownBefore.pixel(x, y), b = shownAfter.pixel(x, y);
                worst = std::max({worst, std::abs(qRed(a) - qRed(b)),
                                  std::abs(qGreen(a) - qGreen(b)), std::abs(qBlue(a) - qBlue(b))});
            }
        qInfo("the view at rest with the panel open against before it: worst %d/255", worst);
        QVERIFY2(worst <= 2, qPrintable(QString::number(worst)));
        // The viewport's side of the split is the settled mean through the reference's display.
        const int height = panel->view()->composed().height();
        std::string error;
        const QImage expected = ReferenceJob::toQImage(ReferenceJob::displayImage(
            velvet::resize(settled, ReferencePanel::kWidth, height, &error, ResizeFilter::Box),
            viewport->frameSettings().exposureEv));
        panel->view()->setHeatMapShown(false);
        panel->view()->setSplit(1.0);
        QCOMPARE(panel->view()->composed(), expected.convertToFormat(QImage::Format_RGB888));
        // A single frame drawn now: one bounce. At the panel's size the settled mean is brighter
        // where the ball lights itself (under the ring, the neck); the single frame's few traced
        // rays are grainy, so it is brighter in places too, but by far less in all.
        Image single;
        viewport->grabFramebuffer(&single);
        QCOMPARE(single.width, settled.width);
        QCOMPARE(single.height, settled.height);
        const Image a =
            velvet::resize(single, ReferencePanel::kWidth, height, &error, ResizeFilter::Box);
        const Image b =
            velvet::resize(settled, ReferencePanel::kWidth, height, &error, ResizeFilter::Box);
        int brighter = 0;
        double gained = 0.0, lost = 0.0;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x) {
                const float one = a.at(x, y)[1], mean = b.at(x, y)[1];
                brighter += mean > one * 1.03f + 1e-3f;
                (mean > one ? gained : lost) += std::abs(mean - one);
            }
        qInfo("settled against one frame at %dx%d: %d pixels 3 %% brighter; green gained %.3f, "
              "lost %.3f",
              a.width, a.height, brighter, gained, lost);
        QVERIFY2(brighter > 100 && gained > 2.0 * lost,
                 qPrintable(QStringLiteral("%1 brighter; gained %2, lost %3")
                                .arg(brighter)
                                .arg(gained)
                                .arg(lost)));
        // Off with the panel: the viewport goes back to its display-only refinement.
        QTest::keyClick(m_window.get(), Qt::Key_R, Qt::ControlModifier | Qt::ShiftModifier);
        QVERIFY(QTest::qWaitFor([&] { return !panel->active(); }));
        QVERIFY(!viewport->keepsSettledLinear());
        QVERIFY(viewport->settledLinear().empty());
        m_window->controller()->setMesh(MeshRef{});
    }
};

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true);
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetReferenceTest"));
    QApplication::setOrganizationName(QStringLiteral("VelvetTest"));
    TestUiReference test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_ui_reference.moc"
