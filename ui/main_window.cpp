#include "ui/main_window.h"

#include "core/color_management.h"
#include "core/document_io.h"
#include "ui/ab_split_control.h"
#include "ui/atlas/atlas_panel.h"
#include "ui/autosave.h"
#include "ui/document_controller.h"
#include "ui/graph/graph_panel.h"
#include "ui/import_action.h"
#include "ui/library/library_panel.h"
#include "ui/log_panel.h"
#include "ui/post_chain/post_chain_panel.h"
#include "ui/properties/property_panel.h"
#include "ui/reference/reference_panel.h"
#include "ui/scene/scene_panel.h"
#include "ui/viewport_toolbar.h"
#include "ui/viewport_widget.h"
#include "ui/wheel_guard.h"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDir>
#include <QDockWidget>
#include <QFileDialog>
#include <QLabel>
#include <QMenu>
#include <QMessageBox>
#include <QScrollArea>
#include <QSettings>
#include <QStatusBar>
#include <QTimer>
#include <QToolBar>
#include <QToolButton>
#include <QUndoStack>
#include <QUndoView>
#include <algorithm>
#include <cmath>

namespace velvet::ui {
namespace {

const char* const kGeometryKey = "mainWindow/geometry";
const char* const kStateKey = "mainWindow/state";
const char* const kLastDirKey = "files/lastDirectory";

QString fileFilter() {
    return QObject::tr("Velvet scenes and presets (*.json)");
}

} // namespace

MainWindow::MainWindow(bool restoreLayout, QWidget* parent)
    : QMainWindow(parent), m_controller(new DocumentController(this)),
      m_viewport(new ViewportWidget(this)), m_autosave(new Autosave(m_controller, this)),
      m_saveLayout(restoreLayout) {
    setObjectName(QStringLiteral("mainWindow"));
    setAcceptDrops(true);
    WheelGuard::install(); // the wheel scrolls panels, not the unfocused controls in them
    setCentralWidget(m_viewport);

    // One OCIO config for the toolbar's lists, the renderer's display transform and the pickers.
    auto colorManagement = std::make_shared<ColorManagement>();
    std::string ocioError;
    const bool ocioLoaded = colorManagement->loadDefault(&ocioError);
    m_colorManagement = colorManagement;
    m_viewport->setColorManagement(m_colorManagement);

    createDocks();
    createToolbars();
    createMenus();
    if (!ocioLoaded)
        m_log->warning(tr("OpenColorIO config not loaded, only the built-in tone mapper is "
                          "offered: %1")
                           .arg(QString::fromStdString(ocioError)));

    m_frameLabel = new QLabel(this);
    m_frameLabel->setObjectName(QStringLiteral("frameTime"));
    m_progressLabel = new QLabel(this);
    m_progressLabel->setObjectName(QStringLiteral("environmentProgress"));
    m_progressLabel->setMinimumWidth(
        m_progressLabel->fontMetrics().horizontalAdvance(tr("Prefiltering environment 100 %")) + 8);
    m_progressLabel->hide();
    m_textureLabel = new QLabel(this);
    m_textureLabel->setObjectName(QStringLiteral("textureProgress"));
    m_textureLabel->hide();
    statusBar()->addPermanentWidget(m_textureLabel);
    statusBar()->addPermanentWidget(m_progressLabel);
    statusBar()->addPermanentWidget(m_frameLabel);

    connect(m_controller, &DocumentController::sceneChanged, this,
            [this](ScenePart parts) { m_viewport->setScene(m_controller->scene(), parts); });
    connect(m_controller, &DocumentController::documentReplaced, m_viewport,
            &ViewportWidget::resetView);
    connect(m_viewport, &ViewportWidget::viewCameraChanged, m_controller,
            &DocumentController::setViewCamera);
    connect(m_controller, &DocumentController::fileChanged, this, &MainWindow::updateTitle);
    connect(m_controller, &DocumentController::dirtyChanged, this, &MainWindow::updateTitle);
    connect(m_viewport, &ViewportWidget::frameCompleted, this, &MainWindow::showFrameTime);
    connect(m_viewport, &ViewportWidget::renderFailed, this, [this](const QString& message) {
        statusBar()->showMessage(message);
        m_log->error(message);
    });
    connect(m_viewport, &ViewportWidget::sceneProblems, this, [this](const QStringList& lines) {
        statusBar()->showMessage(lines.join(QStringLiteral("; ")), 10000);
        for (const QString& line : lines)
            m_log->warning(line);
    });
    connect(m_viewport, &ViewportWidget::environmentRotationDragged, this,
            &MainWindow::rotateEnvironment);
    connect(m_autosave, &Autosave::failed, m_log, &LogPanel::warning);
    connect(m_controller, &DocumentController::meshRefused, this, [this](const QString& text) {
        m_log->error(text);
        statusBar()->showMessage(text, 10000);
    });
    connect(m_viewToolbar, &ViewportToolbar::viewStateChanged, this, &MainWindow::applyViewState);
    // The reference's display transform follows the viewport's exposure (and a debug view stops
    // the comparison): a view-state change restarts it like a scene edit.
    connect(m_viewToolbar, &ViewportToolbar::viewStateChanged, m_reference,
            &ReferencePanel::viewStateChanged);
    connect(m_viewToolbar, &ViewportToolbar::timingOverlayToggled, m_viewport,
            &ViewportWidget::setTimingOverlayVisible);
    connect(m_viewToolbar, &ViewportToolbar::progressiveAntialiasToggled, m_viewport,
            &ViewportWidget::setProgressiveAntialiasing);
    connect(m_viewToolbar, &ViewportToolbar::reducedWhileMovingToggled, m_viewport,
            [this](bool on) { m_viewport->setReducedResolution(on); });

    resize(1280, 800);
    // Under the viewport: the graph three fifths of the width, the Log (and Post chain) the rest,
    // above its narrowest so the separator moves both ways; tall enough for a few nodes (it
    // started at about 375x125, issue 17 item 2).
    if (auto* log = findChild<QDockWidget*>(QStringLiteral("logDock")),
        *graph = findChild<QDockWidget*>(QStringLiteral("graphDock"));
        log && graph) {
        resizeDocks({log, graph}, {2, 3}, Qt::Horizontal);
        resizeDocks({graph}, {250}, Qt::Vertical);
    }
    if (restoreLayout) {
        QSettings settings;
        restoreGeometry(settings.value(kGeometryKey).toByteArray());
        restoreState(settings.value(kStateKey).toByteArray(), kLayoutVersion);
        m_viewToolbar->restoreSettings();
    }
    applyViewState();
    m_controller->newDocument();
    updateTitle();
}

MainWindow::~MainWindow() = default;

void MainWindow::createDocks() {
    m_properties = new PropertyPanel(m_controller, this);
    auto* scroll = new QScrollArea(this);
    scroll->setWidget(m_properties);
    scroll->setWidgetResizable(true);
    scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    auto* properties = new QDockWidget(tr("Properties"), this);
    properties->setObjectName(QStringLiteral("propertiesDock"));
    properties->setWidget(scroll);
    properties->setMinimumWidth(320);
    addDockWidget(Qt::RightDockWidgetArea, properties);

    m_atlas = new AtlasPanel(m_controller, this);
    auto* atlas = new QDockWidget(tr("Atlas"), this);
    atlas->setObjectName(QStringLiteral("atlasDock"));
    atlas->setWidget(m_atlas);
    addDockWidget(Qt::RightDockWidgetArea, atlas);
    tabifyDockWidget(properties, atlas);
    properties->raise();

    m_scene = new ScenePanel(m_controller, this);
    auto* sceneScroll = new QScrollArea(this);
    sceneScroll->setWidget(m_scene);
    sceneScroll->setWidgetResizable(true);
    sceneScroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    auto* sceneDock = new QDockWidget(tr("Scene"), this);
    sceneDock->setObjectName(QStringLiteral("sceneDock"));
    sceneDock->setWidget(sceneScroll);
    addDockWidget(Qt::RightDockWidgetArea, sceneDock);
    tabifyDockWidget(properties, sceneDock);
    properties->raise();

    m_history = new QUndoView(m_controller->undoStack(), this);
    m_history->setObjectName(QStringLiteral("historyView"));
    m_history->setEmptyLabel(tr("<opened>"));
    auto* history = new QDockWidget(tr("History"), this);
    history->setObjectName(QStringLiteral("historyDock"));
    history->setWidget(m_history);
    addDockWidget(Qt::RightDockWidgetArea, history);
    resizeDocks({properties}, {460}, Qt::Horizontal);
    resizeDocks({properties, history}, {600, 160}, Qt::Vertical);

    m_log = new LogPanel(this);
    auto* log = new QDockWidget(tr("Log"), this);
    log->setObjectName(QStringLiteral("logDock"));
    log->setWidget(m_log);
    // The right-hand docks keep the full height; the Log sits under the viewport only.
    setCorner(Qt::BottomRightCorner, Qt::RightDockWidgetArea);
    addDockWidget(Qt::BottomDockWidgetArea, log);
    resizeDocks({log}, {120}, Qt::Vertical);

    // Post chain: a tab beside the Log, under the viewport, so the selected effect's parameters
    // (shown in Properties) and the list are visible at once; Library a tab beside Properties;
    // their errors go to the Log.
    m_postChain = new PostChainPanel(m_controller, this);
    auto* postChain = new QDockWidget(tr("Post chain"), this);
    postChain->setObjectName(QStringLiteral("postChainDock"));
    postChain->setWidget(m_postChain);
    tabifyDockWidget(log, postChain);
    log->raise();
    m_library = new LibraryPanel(m_controller, this);
    auto* library = new QDockWidget(tr("Library"), this);
    library->setObjectName(QStringLiteral("libraryDock"));
    library->setWidget(m_library);
    addDockWidget(Qt::RightDockWidgetArea, library);
    tabifyDockWidget(properties, library);
    properties->raise();
    // Reference (issue 15): the path tracer's image against the viewport; renders only while
    // its dock is shown (View > Reference, Ctrl+Shift+R), a tab beside the Log.
    m_reference = new ReferencePanel(m_controller, m_viewport, this);
    auto* referenceDock = new QDockWidget(tr("Reference"), this);
    referenceDock->setObjectName(QStringLiteral("referenceDock"));
    referenceDock->setWidget(m_reference);
    tabifyDockWidget(log, referenceDock);
    log->raise();
    referenceDock->hide();
    referenceDock->toggleViewAction()->setShortcut(QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_R));
    // Shown from the menu or the shortcut, its tab comes to the front; behind another tab it
    // is not visible and stops rendering.
    connect(referenceDock->toggleViewAction(), &QAction::triggered, referenceDock,
            [referenceDock](bool shown) {
                if (shown)
                    referenceDock->raise();
            });
    connect(referenceDock, &QDockWidget::visibilityChanged, m_reference,
            &ReferencePanel::setActive);
    // The reference's samples and ΔE stay in the status bar while it converges (its images come
    // seconds apart); hidden, it clears its line.
    connect(m_reference, &ReferencePanel::status, this, [this](const QString& text) {
        if (text.isEmpty())
            statusBar()->clearMessage();
        else
            statusBar()->showMessage(text);
    });
    connect(m_postChain, &PostChainPanel::problemsReported, m_log, &LogPanel::error);
    connect(m_library, &LibraryPanel::problemsReported, m_log, &LogPanel::warning);

    // Material graph: under the viewport beside the Log; refused edits go to the status bar
    // and the Log.
    auto* graphPanel = new GraphPanel(m_controller, this);
    auto* graphDock = new QDockWidget(tr("Material graph"), this);
    graphDock->setObjectName(QStringLiteral("graphDock"));
    graphDock->setWidget(graphPanel);
    addDockWidget(Qt::BottomDockWidgetArea, graphDock, Qt::Horizontal);
    const auto showMessage = [this](const QString& text) {
        statusBar()->showMessage(text, 10000);
        m_log->warning(text);
    };
    connect(graphPanel, &GraphPanel::message, this, showMessage);
    // Node thumbnails are drawn by the GPU with the viewport's context (GraphPanel, "Node
    // thumbnails"); a batch that came before the renderer existed runs after its first frame.
    graphPanel->setPreviewSource([this](const graph::Graph& g,
                                        const std::vector<render::PreviewRequest>& requests,
                                        Problems* problems) {
        return m_viewport->renderGraphPreviews(g, requests, problems);
    });
    connect(m_viewport, &ViewportWidget::frameCompleted, graphPanel,
            &GraphPanel::previewSourceReady);
    connect(graphPanel, &GraphPanel::previewProblems, m_log, &LogPanel::warning);
    connect(m_properties, &PropertyPanel::message, this, showMessage);
    // "Driven by <node>" under a material parameter: that node, selected, in the graph dock.
    connect(m_properties, &PropertyPanel::graphNodeRequested, this,
            [graphPanel, graphDock](graph::NodeId id) {
                graphDock->show();
                graphDock->raise();
                graphPanel->showNode(id);
            });

    // The selected effect or node shows its parameters in Properties.
    connect(m_postChain, &PostChainPanel::effectSelected, m_properties, &PropertyPanel::showEffect);
    connect(graphPanel, &GraphPanel::nodeSelected, m_properties,
            [this, graphPanel](graph::NodeId id) {
                m_properties->showGraphNode(graphPanel->model(), id);
            });
    connect(m_properties, &PropertyPanel::subjectChanged, properties, [this, properties] {
        if (m_properties->subject() != PropertyPanel::Subject::Material)
            properties->raise();
    });
}

void MainWindow::createToolbars() {
    m_viewToolbar = new ViewportToolbar(m_colorManagement, this);
    addToolBar(Qt::TopToolBarArea, m_viewToolbar);

    // A/B split: view state beside the debug view and overlay toggles (ui/ab_split_control.h).
    m_abSplit = new AbSplitControl(this, m_controller, m_viewport, m_log);
    connect(m_abSplit, &AbSplitControl::status, this,
            [this](const QString& text) { statusBar()->showMessage(text, 6000); });
    m_viewToolbar->addSeparator();
    m_viewToolbar->addWidget(m_abSplit->button());
    addToolBarBreak(Qt::TopToolBarArea);
    m_sceneToolbar = new SceneToolbar(m_controller, this);
    addToolBar(Qt::TopToolBarArea, m_sceneToolbar);
}

void MainWindow::applyViewState() {
    m_viewport->setFrameSettings(m_viewToolbar->frameSettings());
    m_viewport->setTimingOverlayVisible(m_viewToolbar->timingOverlay());
    m_viewport->setProgressiveAntialiasing(m_viewToolbar->progressiveAntialias());
    if (m_viewport->reducedResolutionEnabled() != m_viewToolbar->reducedWhileMoving())
        m_viewport->setReducedResolution(m_viewToolbar->reducedWhileMoving());
    m_properties->setPickerColorSpace(m_viewToolbar->pickerColorSpace());
}

void MainWindow::setAbSplit(bool on, std::optional<Material> b) {
    m_abSplit->setSplit(on, std::move(b));
}

void MainWindow::setAbSplitTerm(ParamId term, int choice) {
    m_abSplit->setSplitTerm(term, choice);
}

bool MainWindow::setAbSplitPreset(const QString& path) {
    return m_abSplit->setSplitPreset(path);
}

QAction* MainWindow::abSplitAction() const {
    return m_abSplit->action();
}

void MainWindow::rotateEnvironment(float deltaDeg, int gestureKey) {
    Environment env = m_controller->scene().environment;
    env.rotationDeg = std::fmod(env.rotationDeg + deltaDeg, 360.0f);
    if (env.rotationDeg < 0.0f)
        env.rotationDeg += 360.0f;
    m_controller->editEnvironment(env, tr("Rotate environment"), gestureKey);
}

bool MainWindow::reloadShaders() {
    QString error;
    if (m_viewport->reloadShaders(&error)) {
        m_log->info(tr("Shaders reloaded from disk"));
        statusBar()->showMessage(tr("Shaders reloaded"), 3000);
        return true;
    }
    m_log->error(tr("Shader reload failed; the last good shaders stay in use:\n%1").arg(error));
    statusBar()->showMessage(tr("Shader reload failed (see the Log)"), 10000);
    return false;
}

bool MainWindow::reloadScene() {
    const QString path = m_controller->filePath();
    if (path.isEmpty()) {
        m_log->info(tr("Reload: the document has no file yet"));
        return false;
    }
    if (m_controller->isDirty()) {
        const auto answer =
            QMessageBox::question(this, tr("Reload %1").arg(m_controller->displayName()),
                                  tr("Discard the unsaved changes and read %1 again from disk?")
                                      .arg(m_controller->displayName()),
                                  QMessageBox::Discard | QMessageBox::Cancel, QMessageBox::Cancel);
        if (answer != QMessageBox::Discard)
            return false;
    }
    if (!openFile(path))
        return false;
    m_log->info(tr("Reloaded %1").arg(path));
    return true;
}

void MainWindow::updateTitle() {
    // "[*]" is where Qt puts the modified marker.
    setWindowTitle(tr("%1[*] — Velvet").arg(m_controller->displayName()));
    setWindowModified(m_controller->isDirty());
}

void MainWindow::showFrameTime(double cpuMs) {
    QString text = tr("Frame %1 ms").arg(cpuMs, 0, 'f', 1);
    if (const render::Renderer* renderer = m_viewport->renderer()) {
        const double gpuMs = renderer->lastTimings().totalMs; // 0 where timer queries are missing
        if (gpuMs > 0.0)
            text += tr(" · GPU %1 ms").arg(gpuMs, 0, 'f', 1);
    }
    // The still view's refinement (ViewportWidget's progressive anti-aliasing), as it goes.
    if (const int samples = m_viewport->progressiveSamples(); samples > 0)
        text += tr(" · Refined %1/%2")
                    .arg(std::min(samples, ViewportWidget::kProgressiveSamples))
                    .arg(ViewportWidget::kProgressiveSamples);
    m_frameLabel->setText(text);

    // Textures loading off the drawing thread (the viewport keeps frames coming meanwhile).
    const render::TextureLoadProgress textures = m_viewport->textureProgress();
    if (textures.loading > 0) {
        m_textureLabel->setText(tr("Loading textures: %1 of %2 · %3 %")
                                    .arg(textures.total - textures.loading)
                                    .arg(textures.total)
                                    .arg(int(textures.fraction * 100.0)));
        m_textureLabel->show();
    } else {
        m_textureLabel->hide();
    }

    // Environment prefiltering, where the renderer reports it (negative: it does not).
    const double progress = m_viewport->environmentProgress();
    if (progress >= 0.0 && progress < 1.0) {
        m_progressLabel->setText(tr("Prefiltering environment %1 %").arg(int(progress * 100.0)));
        m_progressLabel->show();
        // The renderer bakes a slice per frame: keep frames coming until it is done.
        QTimer::singleShot(15, m_viewport, &ViewportWidget::requestFrame);
    } else {
        m_progressLabel->setMinimumWidth(
            m_progressLabel->fontMetrics().horizontalAdvance(tr("Prefiltering environment 100 %")) +
            8);
        m_progressLabel->hide();
    }
}

bool MainWindow::openFile(const QString& path) {
    QStringList problems;
    if (m_controller->openFile(path, &problems)) {
        addRecentFile(path);
        fillRecentMenu(); // an empty menu is disabled and never asks to be filled
        // A crash (or kill) left unsaved changes of this file behind: offer them.
        if (m_autosave->offerRecovery(m_controller->filePath()))
            m_log->info(tr("Recovered unsaved changes of %1 from the autosave").arg(path));
        return true;
    }
    m_log->error(tr("Could not open %1:\n%2").arg(path, problems.join(QLatin1Char('\n'))));
    QMessageBox box(QMessageBox::Warning, tr("Could not open %1").arg(path),
                    tr("%1 could not be opened; the current document is unchanged.").arg(path),
                    QMessageBox::Ok, this);
    box.setInformativeText(problems.mid(0, 8).join(QLatin1Char('\n')));
    if (problems.size() > 8)
        box.setDetailedText(problems.join(QLatin1Char('\n')));
    box.exec();
    return false;
}

void MainWindow::newDocument() {
    if (maybeSave())
        m_controller->newDocument();
}

void MainWindow::openDocument() {
    if (!maybeSave())
        return;
    QSettings settings;
    const QString path = QFileDialog::getOpenFileName(
        this, tr("Open"), settings.value(kLastDirKey).toString(), fileFilter());
    if (path.isEmpty())
        return;
    settings.setValue(kLastDirKey, QFileInfo(path).absolutePath());
    openFile(path);
}

bool MainWindow::saveDocument() {
    if (m_controller->filePath().isEmpty())
        return saveDocumentAs();
    QString error;
    if (m_controller->save(&error)) {
        m_autosave->discard();
        return true;
    }
    m_log->error(tr("Save failed: %1").arg(error));
    QMessageBox::warning(this, tr("Save failed"), error);
    return false;
}

bool MainWindow::saveDocumentAs() {
    QSettings settings;
    QString path = QFileDialog::getSaveFileName(
        this, tr("Save As"), settings.value(kLastDirKey).toString(), fileFilter());
    if (path.isEmpty())
        return false;
    if (QFileInfo(path).suffix().isEmpty())
        path += QStringLiteral(".json");
    settings.setValue(kLastDirKey, QFileInfo(path).absolutePath());
    QString error;
    if (m_controller->saveAs(path, &error)) {
        m_autosave->discard();
        addRecentFile(path);
        fillRecentMenu(); // now, not at the next start: a disabled menu never shows
        return true;
    }
    m_log->error(tr("Save failed: %1").arg(error));
    QMessageBox::warning(this, tr("Save failed"), error);
    return false;
}

bool MainWindow::maybeSave() {
    if (!m_controller->isDirty())
        return true;
    const auto answer = QMessageBox::warning(
        this, tr("Unsaved changes"),
        tr("%1 has unsaved changes. Save them?").arg(m_controller->displayName()),
        QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, QMessageBox::Save);
    if (answer == QMessageBox::Save)
        return saveDocument();
    return answer == QMessageBox::Discard;
}

void MainWindow::closeEvent(QCloseEvent* event) {
    if (!maybeSave()) {
        event->ignore();
        return;
    }
    if (m_saveLayout) {
        QSettings settings;
        settings.setValue(kGeometryKey, saveGeometry());
        settings.setValue(kStateKey, saveState(kLayoutVersion));
        m_viewToolbar->saveSettings();
    }
    m_autosave->finish(); // saved or discarded by the artist: nothing to recover
    event->accept();
}

} // namespace velvet::ui
