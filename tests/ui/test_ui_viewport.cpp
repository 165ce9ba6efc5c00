// Drives the real MainWindow's viewport toolbars, mouse and keys under xvfb-run: debug views,
// OCIO view and exposure change the viewport's pixels; preview mesh and HDRI changes (combo,
// Shift + right drag, file drop) are undoable document edits; T with a broken shader keeps the
// viewport drawing and logs file:line, and recovers once the file is fixed; the dock layout
// restores; colour pickers round-trip through the OCIO view; recent files keep the newest 8.
// The viewport draws in a QOpenGLWindow inside a window container, so mouse, keys and drops are
// sent to that native window (QTest's QWindow overloads go through the window system path):
// orbit, pan, zoom, fly keys, F, T and Ctrl+Z while it has focus, and a file dropped on it
// reaches the main window; screenshots compose its frame (QWidget::grab leaves it out).
#include "core/color_management.h"
#include "core/image.h"
#include "core/post_effects.h"
#include "core/resources.h"
#include "render/renderer.h"
#include "ui/color_picking.h"
#include "ui/document_controller.h"
#include "ui/log_panel.h"
#include "ui/main_window.h"
#include "ui/screenshot.h"
#include "ui/viewport_toolbar.h"
#include "ui/viewport_widget.h"
#include "ui_test_util.h"

#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFile>
#include <QMimeData>
#include <QRegularExpression>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>
#include <QToolBar>
#include <QUndoStack>
#include <QUrl>
#include <QWindow>
#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>

using namespace velvet;
using namespace velvet::ui;
using velvet::test::centrePixel;
using velvet::test::describe;
using velvet::test::kFrameTimeoutMs;
using velvet::test::luma;
using velvet::test::maxDifference;

namespace {

bool copyTree(const QString& from, const QString& to) {
    std::error_code ec;
    std::filesystem::copy(from.toStdString(), to.toStdString(),
                          std::filesystem::copy_options::recursive, ec);
    return !ec;
}

/// A drag from @p from by @p steps moves of @p step with @p button, on the viewport's GL window.
void drag(QWindow* w, Qt::MouseButton button, Qt::KeyboardModifiers modifiers, QPoint from,
          QPoint step, int steps) {
    QTest::mousePress(w, button, modifiers, from);
    QPoint pos = from;
    for (int i = 0; i < steps; ++i) {
        pos += step;
        QTest::mouseMove(w, pos);
    }
    QTest::mouseRelease(w, button, modifiers, pos);
}

} // namespace

class TestUiViewport : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void init();

    void debugViewComboListsEveryView();
    void debugViewChangesPixel();
    void ocioViewAndExposureChangePixel();
    void previewMeshIsUndoable();
    void shiftRightDragRotatesEnvironment();
    void frameMeshResetsTargetAndDistance();
    void leftDragOrbitsAndFlyKeysMove();
    void orbitUploadsNothingAndAnEditOnlyItsPart();
    void orbitedViewIsSavedWithTheDocument();
    void brokenShaderKeepsDrawingAndLogs();
    void droppedExrSetsHdri();
    void dockLayoutRestores();
    void pickerRoundTripsThroughOcioView();
    void recentFilesKeepNewestEight();
    void lookComboChangesPixelAndPersists();

private:
    QImage viewportImage() { return m_window->viewport()->grabFramebuffer(); }
    /// The native window the viewport draws in: where the window system sends its events.
    QWindow* glWindow() { return m_window->viewport()->glWindow(); }
    /// A click on the viewport, as an artist gives it keyboard focus; true once it has it.
    bool focusViewport();
    template <class T>
    T* find(const QString& name) {
        return test::findNamed<T>(m_window.get(), name);
    }
    /// Resets the view state to the defaults (built-in tone mapper, Final, 0 EV).
    void resetViewState();

    QTemporaryDir m_resources; ///< a copy of resources/ the shader test may break
    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
};

void TestUiViewport::initTestCase() {
    QVERIFY(m_resources.isValid());
    const QString copy = m_resources.filePath(QStringLiteral("resources"));
    QVERIFY(copyTree(QStringLiteral(VELVET_SOURCE_DIR "/resources"), copy));
    // Read by core::resources at every lookup; must be set before the renderer loads shaders.
    qputenv("VELVET_RESOURCES", copy.toUtf8());

    m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
    m_doc = m_window->controller();
    const QString up = test::showWithFirstFrame(m_window.get(), {800, 600});
    QVERIFY2(up.isEmpty(), qPrintable(up));
}

void TestUiViewport::cleanupTestCase() {
    m_doc->newDocument();
    QVERIFY(m_window->close());
    m_window.reset();
}

void TestUiViewport::init() {
    m_doc->newDocument();
    resetViewState();
}

void TestUiViewport::resetViewState() {
    find<QComboBox>(QStringLiteral("debugViewCombo"))->setCurrentIndex(0);
    find<QComboBox>(QStringLiteral("displayCombo"))->setCurrentIndex(0);
    find<QDoubleSpinBox>(QStringLiteral("exposureSpin"))->setValue(0.0);
}

void TestUiViewport::debugViewComboListsEveryView() {
    // The combo is built from the toolbar's table; every row names a distinct DebugView.
    auto* combo = find<QComboBox>(QStringLiteral("debugViewCombo"));
    QVERIFY(combo);
    const auto views = ViewportToolbar::debugViews();
    QCOMPARE(combo->count(), int(views.size()));
    for (size_t i = 0; i < views.size(); ++i) {
        QCOMPARE(combo->itemData(int(i)).toInt(), int(views[i].view));
        QCOMPARE(int(views[i].view), int(i)); // in enum order, none skipped
    }
}

void TestUiViewport::debugViewChangesPixel() {
    auto* combo = find<QComboBox>(QStringLiteral("debugViewCombo"));
    const QVector<double> final = centrePixel(viewportImage());
    combo->setCurrentIndex(combo->findText(QStringLiteral("Normal")));
    QCOMPARE(m_window->viewport()->frameSettings().view, render::DebugView::Normal);
    const QVector<double> normal = centrePixel(viewportImage());
    QVERIFY2(maxDifference(final, normal) > 10.0,
             qPrintable(describe(final) + " vs " + describe(normal)));
    combo->setCurrentIndex(0);
    QVERIFY(maxDifference(final, centrePixel(viewportImage())) < 2.0);
}

void TestUiViewport::ocioViewAndExposureChangePixel() {
    auto* display = find<QComboBox>(QStringLiteral("displayCombo"));
    auto* view = find<QComboBox>(QStringLiteral("viewCombo"));
    auto* exposure = find<QDoubleSpinBox>(QStringLiteral("exposureSpin"));
    const int srgb = display->findText(QStringLiteral("sRGB"));
    QVERIFY2(srgb > 0, "the shipped config offers the sRGB display");
    display->setCurrentIndex(srgb);
    QVERIFY(view->isEnabled());
    view->setCurrentIndex(view->findText(QStringLiteral("Standard")));
    QCOMPARE(m_window->viewport()->frameSettings().displayView, std::string("Standard"));
    const QVector<double> standard = centrePixel(viewportImage());
    view->setCurrentIndex(view->findText(QStringLiteral("ACES")));
    QCOMPARE(m_window->viewport()->frameSettings().displayView, std::string("ACES"));
    const QVector<double> aces = centrePixel(viewportImage());
    QVERIFY2(maxDifference(standard, aces) > 3.0,
             qPrintable(describe(standard) + " vs " + describe(aces)));

    exposure->setValue(1.0);
    QCOMPARE(m_window->viewport()->frameSettings().exposureEv, 1.0f);
    const QVector<double> brighter = centrePixel(viewportImage());
    QVERIFY2(luma(brighter) > luma(aces) + 5.0,
             qPrintable(describe(aces) + " -> " + describe(brighter)));
    // View state, never a document edit.
    QCOMPARE(m_doc->undoStack()->count(), 0);
}

void TestUiViewport::previewMeshIsUndoable() {
    auto* combo = find<QComboBox>(QStringLiteral("meshCombo"));
    QVERIFY(combo);
    QCOMPARE(m_doc->scene().mesh.kind, PreviewMeshKind::Sphere);
    const int cube = combo->findData(int(PreviewMeshKind::Cube));
    QVERIFY(cube >= 0);
    combo->setCurrentIndex(cube);
    emit combo->activated(cube); // what a click on the item does
    QCOMPARE(m_doc->scene().mesh.kind, PreviewMeshKind::Cube);
    QCOMPARE(m_doc->undoStack()->count(), 1);
    m_doc->undoStack()->undo();
    QCOMPARE(m_doc->scene().mesh.kind, PreviewMeshKind::Sphere);
    QCOMPARE(combo->currentData().toInt(), int(PreviewMeshKind::Sphere));
    m_doc->undoStack()->redo();
    QCOMPARE(m_doc->scene().mesh.kind, PreviewMeshKind::Cube);
}

void TestUiViewport::shiftRightDragRotatesEnvironment() {
    ViewportWidget* viewport = m_window->viewport();
    const float before = m_doc->scene().environment.rotationDeg;
    const Camera camera = viewport->viewCamera();
    const QPoint start = viewport->rect().center() - QPoint(50, 0);
    drag(glWindow(), Qt::RightButton, Qt::ShiftModifier, start, QPoint(20, 0), 5);
    const float after = m_doc->scene().environment.rotationDeg;
    QVERIFY2(std::abs(after - before) > 10.0f, qPrintable(QString::number(after)));
    QCOMPARE(m_doc->undoStack()->count(), 1);  // five moves, one command
    QVERIFY(viewport->viewCamera() == camera); // the camera did not move
    // Ctrl+Z while the viewport has keyboard focus: the main window's shortcut still undoes.
    QVERIFY(focusViewport());
    QTest::keyClick(glWindow(), Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(m_doc->scene().environment.rotationDeg, before);

    // A plain right drag looks around (view state): no document edit.
    drag(glWindow(), Qt::RightButton, Qt::NoModifier, start, QPoint(30, 10), 1);
    QVERIFY(!m_doc->undoStack()->canUndo());
    QVERIFY(!(viewport->viewCamera() == camera));
}

void TestUiViewport::frameMeshResetsTargetAndDistance() {
    ViewportWidget* viewport = m_window->viewport();
    // Middle drag pans: the target moves.
    const QPoint c = viewport->rect().center();
    drag(glWindow(), Qt::MiddleButton, Qt::NoModifier, c, QPoint(40, 25), 1);
    QVERIFY(glm::length(viewport->viewCamera().target) > 0.01f);
    // The wheel zooms (QTest has no wheel for a QWindow: the event goes to it directly).
    const float distance = viewport->viewCamera().distance;
    QWheelEvent wheel(QPointF(c), glWindow()->mapToGlobal(QPointF(c)), QPoint(), QPoint(0, 240),
                      Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
    QCoreApplication::sendEvent(glWindow(), &wheel);
    QVERIFY(viewport->viewCamera().distance < distance);
    // F, the main window's shortcut, pressed while the viewport has keyboard focus.
    QVERIFY(focusViewport());
    QTest::keyClick(glWindow(), Qt::Key_F);
    const Camera framed = viewport->viewCamera();
    QVERIFY(glm::length(framed.target) < 1e-6f);
    QCOMPARE(framed.distance, Camera{}.distance);
    QCOMPARE(m_doc->undoStack()->count(), 0);
}

bool TestUiViewport::focusViewport() {
    QTest::mouseClick(glWindow(), Qt::LeftButton, Qt::NoModifier, QPoint(5, 5));
    return QTest::qWaitFor([this] { return QGuiApplication::focusWindow() == glWindow(); }, 5000);
}

void TestUiViewport::leftDragOrbitsAndFlyKeysMove() {
    ViewportWidget* viewport = m_window->viewport();
    const Camera before = viewport->viewCamera();
    const QPoint c = viewport->rect().center();
    // Left drag orbits: yaw and pitch turn about the same target at the same distance.
    drag(glWindow(), Qt::LeftButton, Qt::NoModifier, c, QPoint(10, 5), 4);
    const Camera orbited = viewport->viewCamera();
    QVERIFY(std::abs(orbited.yawDeg - before.yawDeg) > 5.0f);
    QVERIFY(std::abs(orbited.pitchDeg - before.pitchDeg) > 2.0f);
    QVERIFY(glm::length(orbited.target - before.target) < 1e-5f);
    QCOMPARE(orbited.distance, before.distance);

    // Right button held (look), W held: the camera flies forward, then stops with the key.
    QVERIFY(focusViewport());
    QTest::mousePress(glWindow(), Qt::RightButton, Qt::NoModifier, c);
    QTest::keyPress(glWindow(), Qt::Key_W);
    QTest::qWait(150);
    QTest::keyRelease(glWindow(), Qt::Key_W);
    const Camera flown = viewport->viewCamera();
    QTest::qWait(50);
    QVERIFY(viewport->viewCamera() == flown);
    QTest::mouseRelease(glWindow(), Qt::RightButton, Qt::NoModifier, c);
    QVERIFY2(glm::length(flown.target - orbited.target) > 0.05f,
             qPrintable(QString::number(glm::length(flown.target - orbited.target))));
    QCOMPARE(flown.yawDeg, orbited.yawDeg);
    QCOMPARE(m_doc->undoStack()->count(), 0); // view state only
}

void TestUiViewport::orbitUploadsNothingAndAnEditOnlyItsPart() {
    // An orbit is a per-frame camera (FrameSettings::camera), not a scene edit: it uploads no
    // material, texture, light, mesh, graph or environment. A roughness edit re-packs the
    // material record and nothing else (ScenePart::MaterialValues).
    ViewportWidget* viewport = m_window->viewport();
    const QImage still = viewportImage(); // the document's parts are uploaded by now
    const render::Renderer* renderer = viewport->renderer();
    QVERIFY(renderer);
    const render::UploadStats before = renderer->uploadStats();
    drag(glWindow(), Qt::LeftButton, Qt::NoModifier, viewport->rect().center(), QPoint(12, 4), 5);
    const QImage orbited = viewportImage();
    QVERIFY(orbited != still); // the view did turn
    const render::UploadStats afterOrbit = renderer->uploadStats();
    QCOMPARE(afterOrbit.materialUploads, before.materialUploads);
    QCOMPARE(afterOrbit.textureSlotRefreshes, before.textureSlotRefreshes);
    QCOMPARE(afterOrbit.lightUploads, before.lightUploads);
    QCOMPARE(afterOrbit.meshSelections, before.meshSelections);
    QCOMPARE(afterOrbit.graphCompiles, before.graphCompiles);
    QCOMPARE(afterOrbit.graphValueUploads, before.graphValueUploads);
    QCOMPARE(afterOrbit.environmentRequests, before.environmentRequests);

    m_doc->editParam(ParamId::Roughness, glm::vec3(0.9f));
    const QImage rougher = viewportImage();
    QVERIFY(rougher != orbited);
    const render::UploadStats afterEdit = renderer->uploadStats();
    QCOMPARE(afterEdit.materialUploads, afterOrbit.materialUploads + 1);
    QCOMPARE(afterEdit.textureSlotRefreshes, afterOrbit.textureSlotRefreshes);
    QCOMPARE(afterEdit.lightUploads, afterOrbit.lightUploads);
    QCOMPARE(afterEdit.meshSelections, afterOrbit.meshSelections);
    QCOMPARE(afterEdit.graphCompiles, afterOrbit.graphCompiles);
    QCOMPARE(afterEdit.environmentRequests, afterOrbit.environmentRequests);
}

void TestUiViewport::orbitedViewIsSavedWithTheDocument() {
    // Orbit and zoom, Save As, reopen: the view the artist left comes back (issue 17, item 10),
    // and moving the view is no undo step and does not dirty the document.
    ViewportWidget* viewport = m_window->viewport();
    const Camera initial = viewport->viewCamera();
    drag(glWindow(), Qt::LeftButton, Qt::NoModifier, viewport->rect().center(), QPoint(-9, 6), 5);
    const QPoint c = viewport->rect().center();
    QWheelEvent wheelEvent(QPointF(c), QPointF(glWindow()->mapToGlobal(c)), QPoint(),
                           QPoint(0, 240), Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
    QCoreApplication::sendEvent(glWindow(), &wheelEvent);
    const Camera moved = viewport->viewCamera();
    QVERIFY(std::abs(moved.yawDeg - initial.yawDeg) > 5.0f);
    QVERIFY(moved.distance < initial.distance);
    QCOMPARE(m_doc->undoStack()->count(), 0);
    QVERIFY(!m_doc->isDirty());

    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("view.json"));
    QString error;
    QVERIFY2(m_doc->saveAs(path, &error), qPrintable(error));
    m_doc->newDocument();
    QVERIFY(std::abs(viewport->viewCamera().yawDeg - moved.yawDeg) > 5.0f); // the default view
    QVERIFY(m_window->openFile(path));
    const Camera reopened = viewport->viewCamera();
    QVERIFY2(std::abs(reopened.yawDeg - moved.yawDeg) < 1e-3f,
             qPrintable(QStringLiteral("%1 vs %2").arg(reopened.yawDeg).arg(moved.yawDeg)));
    QVERIFY(std::abs(reopened.pitchDeg - moved.pitchDeg) < 1e-3f);
    QVERIFY(std::abs(reopened.distance - moved.distance) < 1e-4f);
}

void TestUiViewport::brokenShaderKeepsDrawingAndLogs() {
    ViewportWidget* viewport = m_window->viewport();
    LogPanel* log = m_window->logPanel();
    const QString file = QString::fromStdString(resources::path("shaders/lighting.frag").string());
    QVERIFY2(file.startsWith(m_resources.path()), qPrintable(file));
    QFile f(file);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QByteArray good = f.readAll();
    f.close();

    // Insert a syntax error right after the output declaration; remember its line.
    QList<QByteArray> lines = good.split('\n');
    int brokenLine = -1;
    for (int i = 0; i < lines.size(); ++i)
        if (lines[i].contains("out vec4 outColor")) {
            lines.insert(i + 1, "float velvetBroken = ;");
            brokenLine = i + 2; // 1-based
            break;
        }
    QVERIFY(brokenLine > 0);
    QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
    f.write(lines.join('\n'));
    f.close();

    const QVector<double> before = centrePixel(viewportImage());
    const int compiles = viewport->renderer()->shaderCompileCount();
    const size_t logged = log->entries().size();
    QTest::keyClick(m_window.get(), Qt::Key_T);
    QCOMPARE(log->entries().size(), logged + 1);
    const LogPanel::Entry& entry = log->entries().back();
    QCOMPARE(entry.severity, LogPanel::Severity::Error);
    const QRegularExpressionMatch match =
        QRegularExpression(QStringLiteral("lighting\\.frag:(\\d+)")).match(entry.text);
    QVERIFY2(match.hasMatch(), qPrintable(entry.text));
    QCOMPARE(match.captured(1).toInt(), brokenLine);
    // The last good programs keep drawing the same picture.
    QVERIFY(viewport->renderer() != nullptr);
    QVERIFY(viewport->errorMessage().isEmpty());
    const int frames = viewport->frameCount();
    const QVector<double> during = centrePixel(viewportImage());
    QVERIFY(maxDifference(before, during) < 2.0);
    QVERIFY(viewport->frameCount() > frames);

    // Fixed on disk: T recovers (every program rebuilt, no error logged).
    QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
    f.write(good);
    f.close();
    QVERIFY(focusViewport()); // T also works while the viewport has keyboard focus
    QTest::keyClick(glWindow(), Qt::Key_T);
    QCOMPARE(log->entries().back().severity, LogPanel::Severity::Info);
    QVERIFY(viewport->renderer()->shaderCompileCount() > compiles);
    QVERIFY(maxDifference(before, centrePixel(viewportImage())) < 2.0);
}

void TestUiViewport::droppedExrSetsHdri() {
    QTemporaryDir dir;
    const QString exr = dir.filePath(QStringLiteral("dropped.exr"));
    QVERIFY(QFile::copy(QString::fromStdString(resources::path("hdri/studio.exr").string()), exr));
    const Environment before = m_doc->scene().environment;

    // Dropped on the viewport: its GL window is a native window of its own, which forwards the
    // drag to the main window.
    QMimeData mime;
    mime.setUrls({QUrl::fromLocalFile(exr)});
    const QPointF pos = QPointF(m_window->viewport()->rect().center());
    QDragEnterEvent enter(pos.toPoint(), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    enter.setAccepted(false);
    QCoreApplication::sendEvent(glWindow(), &enter);
    QVERIFY(enter.isAccepted());
    // As QGuiApplication sends it after an accepted enter.
    QDragMoveEvent move(pos.toPoint() + QPoint(3, 3), Qt::CopyAction, &mime, Qt::LeftButton,
                        Qt::NoModifier);
    move.setDropAction(enter.dropAction());
    move.setAccepted(enter.isAccepted());
    QCoreApplication::sendEvent(glWindow(), &move);
    QVERIFY(move.isAccepted());
    QDropEvent drop(pos, Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    drop.setAccepted(false);
    QCoreApplication::sendEvent(glWindow(), &drop);
    QVERIFY(drop.isAccepted());

    QCOMPARE(QString::fromStdString(m_doc->scene().environment.hdri),
             QFileInfo(exr).absoluteFilePath());
    QCOMPARE(find<QComboBox>(QStringLiteral("hdriCombo"))->currentText(),
             QStringLiteral("dropped.exr"));
    QCOMPARE(m_doc->undoStack()->count(), 1);
    m_doc->undoStack()->undo();
    QVERIFY(m_doc->scene().environment == before);

    // Dropped on the window elsewhere: the main window's own handling.
    const QPointF windowPos = QPointF(m_window->rect().center());
    QDragEnterEvent enterWindow(windowPos.toPoint(), Qt::CopyAction, &mime, Qt::LeftButton,
                                Qt::NoModifier);
    QCoreApplication::sendEvent(m_window.get(), &enterWindow);
    QVERIFY(enterWindow.isAccepted());

    // Not a file Velvet takes: refused at the door, on the window and on the viewport.
    QMimeData text;
    text.setUrls({QUrl::fromLocalFile(dir.filePath(QStringLiteral("notes.txt")))});
    QDragEnterEvent refused(pos.toPoint(), Qt::CopyAction, &text, Qt::LeftButton, Qt::NoModifier);
    refused.setAccepted(false);
    QCoreApplication::sendEvent(m_window.get(), &refused);
    QVERIFY(!refused.isAccepted());
    QDragEnterEvent refusedOnViewport(pos.toPoint(), Qt::CopyAction, &text, Qt::LeftButton,
                                      Qt::NoModifier);
    refusedOnViewport.setAccepted(false);
    QCoreApplication::sendEvent(glWindow(), &refusedOnViewport);
    QVERIFY(!refusedOnViewport.isAccepted());
    QVERIFY(!m_doc->undoStack()->canUndo()); // only the undone HDRI edit, nothing new
}

/// One line per dock: object name, area, hidden, floating and the docks tabbed with it.
static QStringList describeDocks(const QMainWindow& window) {
    QStringList lines;
    for (QDockWidget* dock : window.findChildren<QDockWidget*>()) {
        QStringList tabbed;
        for (QDockWidget* other : window.tabifiedDockWidgets(dock))
            tabbed << other->objectName();
        tabbed.sort();
        lines << QStringLiteral("%1 area=%2 hidden=%3 floating=%4 tabs=%5")
                     .arg(dock->objectName())
                     .arg(int(window.dockWidgetArea(dock)))
                     .arg(dock->isHidden())
                     .arg(dock->isFloating())
                     .arg(tabbed.join(QLatin1Char(',')));
    }
    lines.sort();
    return lines;
}

void TestUiViewport::dockLayoutRestores() {
    QStringList saved;
    {
        MainWindow first(/*restoreLayout=*/true);
        first.resize(800, 600);
        auto* log = first.findChild<QDockWidget*>(QStringLiteral("logDock"));
        auto* history = first.findChild<QDockWidget*>(QStringLiteral("historyDock"));
        QVERIFY(log && history);
        first.addDockWidget(Qt::LeftDockWidgetArea, log); // the artist moved the Log
        history->hide();                                  // and closed History
        saved = describeDocks(first);
        QVERIFY(first.close()); // saves the layout to QSettings
    }
    MainWindow second(/*restoreLayout=*/true);
    second.resize(800, 600);
    auto* log = second.findChild<QDockWidget*>(QStringLiteral("logDock"));
    auto* history = second.findChild<QDockWidget*>(QStringLiteral("historyDock"));
    QCOMPARE(second.dockWidgetArea(log), Qt::LeftDockWidgetArea);
    QVERIFY(history->isHidden());
    // Every dock comes back in its area, visibility and tab group. (Raw saveState() bytes also
    // hold splitter sizes, which differ between a laid-out and a never-shown window.)
    QCOMPARE(describeDocks(second), saved);
    QVERIFY(second.close());
}

void TestUiViewport::pickerRoundTripsThroughOcioView() {
    auto cm = std::make_shared<ColorManagement>();
    std::string error;
    QVERIFY2(cm->loadDefault(&error), error.c_str());
    PickerColorSpace srgb;
    const glm::vec3 linear(0.18f, 0.5f, 0.02f);
    QVERIFY(glm::length(srgb.toLinear(srgb.toDisplay(linear)) - linear) < 1e-5f);

    PickerColorSpace aces{cm, DisplaySettings{"sRGB", "ACES", "", 0.0f}};
    QVERIFY(!aces.isSrgb());
    const glm::vec3 shown = aces.toDisplay(linear);
    QVERIFY(glm::length(shown - srgb.toDisplay(linear)) > 0.01f); // the view is not plain sRGB
    const glm::vec3 back = aces.toLinear(shown);
    const glm::vec3 again = aces.toDisplay(back);
    for (int c = 0; c < 3; ++c)
        QVERIFY2(
            std::abs(again[c] - shown[c]) < 1.0f / 255.0f,
            qPrintable(QStringLiteral("channel %1: %2 -> %3").arg(c).arg(shown[c]).arg(again[c])));
}

void TestUiViewport::recentFilesKeepNewestEight() {
    for (int i = 0; i < 10; ++i)
        MainWindow::addRecentFile(QStringLiteral("/tmp/velvet-recent-%1.json").arg(i));
    MainWindow::addRecentFile(QStringLiteral("/tmp/velvet-recent-5.json")); // again: to the top
    const QStringList files = MainWindow::recentFiles();
    QCOMPARE(files.size(), MainWindow::kMaxRecentFiles);
    QCOMPARE(files.front(), QStringLiteral("/tmp/velvet-recent-5.json"));
    QCOMPARE(files.count(QStringLiteral("/tmp/velvet-recent-5.json")), 1);
    QVERIFY(!files.contains(QStringLiteral("/tmp/velvet-recent-0.json")));
}

// The look combo: choosing a look changes the viewport (OCIO applies it in scene-linear before
// the view), is view state saved to QSettings as the toolbar saves the display and view (never
// a document edit), and choosing "No look" again gives the earlier frame back.
void TestUiViewport::lookComboChangesPixelAndPersists() {
    // A saturated Rec.709 blue: what the ACES blue-light LMT exists to desaturate.
    m_doc->setParam(ParamId::BaseColor, glm::vec3(0.0f, 0.0f, 1.0f));
    auto* display = find<QComboBox>(QStringLiteral("displayCombo"));
    auto* view = find<QComboBox>(QStringLiteral("viewCombo"));
    auto* look = find<QComboBox>(QStringLiteral("lookCombo"));
    display->setCurrentIndex(display->findText(QStringLiteral("sRGB")));
    view->setCurrentIndex(view->findText(QStringLiteral("ACES")));
    QVERIFY(look->isEnabled());
    const QImage without = viewportImage();
    const int undoCount = m_doc->undoStack()->count();

    const QString name = QStringLiteral("ACES Blue Light Fix");
    const int index = look->findData(name);
    QVERIFY2(index > 0, "the shipped config offers the look");
    look->setCurrentIndex(index);
    QCOMPARE(m_window->viewport()->frameSettings().look, name.toStdString());
    const QImage with = viewportImage();
    const int changed = test::maxImageDifference(without, with);
    QVERIFY2(changed > 5, qPrintable(QStringLiteral("largest change %1").arg(changed)));
    QCOMPARE(QSettings().value(QStringLiteral("viewport/look")).toString(), name);
    QCOMPARE(m_doc->undoStack()->count(), undoCount); // view state, not an edit

    look->setCurrentIndex(0);
    QVERIFY(m_window->viewport()->frameSettings().look.empty());
    QCOMPARE(QSettings().value(QStringLiteral("viewport/look")).toString(), QString());
    QVERIFY(test::maxImageDifference(without, viewportImage()) <= 1);
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetViewportTest"));
    QApplication::setOrganizationName(QStringLiteral("VelvetTest"));
    TestUiViewport test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_ui_viewport.moc"
