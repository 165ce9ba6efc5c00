#include "ui/main_window.h"

#include "ui/document_controller.h"
#include "ui/properties/property_panel.h"
#include "ui/viewport_widget.h"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDockWidget>
#include <QFileDialog>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QScrollArea>
#include <QSettings>
#include <QStatusBar>
#include <QUndoStack>
#include <QUndoView>

namespace velvet::ui {
namespace {

const char* const kGeometryKey = "mainWindow/geometry";
const char* const kStateKey = "mainWindow/state";
const char* const kLastDirKey = "files/lastDirectory";
constexpr int kLayoutVersion = 1; ///< bump when docks are added or renamed

QString fileFilter() {
    return QObject::tr("Velvet scenes and presets (*.json)");
}

} // namespace

MainWindow::MainWindow(bool restoreLayout, QWidget* parent)
    : QMainWindow(parent), m_controller(new DocumentController(this)),
      m_viewport(new ViewportWidget(this)), m_saveLayout(restoreLayout) {
    setObjectName(QStringLiteral("mainWindow"));
    setCentralWidget(m_viewport);
    createDocks();
    createMenus();

    m_frameLabel = new QLabel(this);
    m_frameLabel->setObjectName(QStringLiteral("frameTime"));
    statusBar()->addPermanentWidget(m_frameLabel);

    connect(m_controller, &DocumentController::sceneChanged, this,
            [this] { m_viewport->setScene(m_controller->scene()); });
    connect(m_controller, &DocumentController::documentReplaced, m_viewport,
            &ViewportWidget::resetView);
    connect(m_controller, &DocumentController::fileChanged, this, &MainWindow::updateTitle);
    connect(m_controller, &DocumentController::dirtyChanged, this, &MainWindow::updateTitle);
    connect(m_viewport, &ViewportWidget::frameCompleted, this, &MainWindow::showFrameTime);
    connect(m_viewport, &ViewportWidget::renderFailed, this,
            [this](const QString& message) { statusBar()->showMessage(message); });
    connect(m_viewport, &ViewportWidget::sceneProblems, this, [this](const QStringList& lines) {
        statusBar()->showMessage(lines.join(QStringLiteral("; ")), 10000);
    });

    resize(1280, 800);
    if (restoreLayout) {
        QSettings settings;
        restoreGeometry(settings.value(kGeometryKey).toByteArray());
        restoreState(settings.value(kStateKey).toByteArray(), kLayoutVersion);
    }
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

    m_history = new QUndoView(m_controller->undoStack(), this);
    m_history->setObjectName(QStringLiteral("historyView"));
    m_history->setEmptyLabel(tr("<opened>"));
    auto* history = new QDockWidget(tr("History"), this);
    history->setObjectName(QStringLiteral("historyDock"));
    history->setWidget(m_history);
    addDockWidget(Qt::RightDockWidgetArea, history);
    resizeDocks({properties}, {460}, Qt::Horizontal);
    resizeDocks({properties, history}, {600, 160}, Qt::Vertical);
}

void MainWindow::createMenus() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    QAction* act = file->addAction(tr("&New"), this, &MainWindow::newDocument);
    act->setShortcut(QKeySequence::New);
    act = file->addAction(tr("&Open…"), this, &MainWindow::openDocument);
    act->setShortcut(QKeySequence::Open);
    act = file->addAction(tr("&Save"), this, &MainWindow::saveDocument);
    act->setShortcut(QKeySequence::Save);
    act = file->addAction(tr("Save &As…"), this, &MainWindow::saveDocumentAs);
    act->setShortcut(QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_S));
    file->addSeparator();
    act = file->addAction(tr("&Quit"), this, &QWidget::close);
    act->setShortcut(QKeySequence::Quit);

    QMenu* edit = menuBar()->addMenu(tr("&Edit"));
    QUndoStack* stack = m_controller->undoStack();
    QAction* undo = stack->createUndoAction(this, tr("&Undo"));
    undo->setObjectName(QStringLiteral("undoAction"));
    undo->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_Z));
    QAction* redo = stack->createRedoAction(this, tr("&Redo"));
    redo->setObjectName(QStringLiteral("redoAction"));
    redo->setShortcuts(
        {QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_Z), QKeySequence(Qt::CTRL | Qt::Key_Y)});
    edit->addAction(undo);
    edit->addAction(redo);

    QMenu* view = menuBar()->addMenu(tr("&View"));
    for (QDockWidget* dock : findChildren<QDockWidget*>())
        view->addAction(dock->toggleViewAction());
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
    m_frameLabel->setText(text);
}

bool MainWindow::openFile(const QString& path) {
    QStringList problems;
    if (m_controller->openFile(path, &problems))
        return true;
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
    if (m_controller->save(&error))
        return true;
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
    if (m_controller->saveAs(path, &error))
        return true;
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
    }
    event->accept();
}

} // namespace velvet::ui
