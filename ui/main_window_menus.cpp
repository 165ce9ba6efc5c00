// MainWindow's menu bar (File, Edit, View) and File > Open Recent, kept apart from the window's
// docks, toolbars and document actions (main_window.cpp).
#include "ui/document_controller.h"
#include "ui/export_action.h"
#include "ui/import_action.h"
#include "ui/main_window.h"
#include "ui/render_dialog.h"
#include "ui/undo_shortcuts.h"
#include "ui/viewport_widget.h"

#include <QAction>
#include <QDockWidget>
#include <QFileInfo>
#include <QMenu>
#include <QMenuBar>
#include <QSettings>
#include <QToolBar>
#include <QUndoStack>

namespace velvet::ui {
namespace {

const char* const kRecentKey = "files/recent";

} // namespace

void MainWindow::createMenus() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    QAction* act = file->addAction(tr("&New"), this, &MainWindow::newDocument);
    act->setShortcut(QKeySequence::New);
    act = file->addAction(tr("&Open…"), this, &MainWindow::openDocument);
    act->setShortcut(QKeySequence::Open);
    m_recentMenu = file->addMenu(tr("Open &Recent"));
    m_recentMenu->setObjectName(QStringLiteral("recentMenu"));
    connect(m_recentMenu, &QMenu::aboutToShow, this, &MainWindow::fillRecentMenu);
    fillRecentMenu(); // an empty menu is disabled until something is opened
    act = file->addAction(tr("&Save"), this, &MainWindow::saveDocument);
    act->setShortcut(QKeySequence::Save);
    act = file->addAction(tr("Save &As…"), this, &MainWindow::saveDocumentAs);
    act->setShortcut(QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_S));
    act = file->addAction(tr("&Export…"), this,
                          [this] { exportDocumentInteractively(this, *m_controller, m_log); });
    act->setObjectName(QStringLiteral("exportAction"));
    act->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_E));
    act = file->addAction(tr("&Import…"), this,
                          [this] { importFileInteractively(this, *m_controller, m_log); });
    act->setObjectName(QStringLiteral("importAction"));
    act->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_I));
    // A still at any size or a turntable, through `velvet render`'s code (ui/render_dialog.h);
    // F12 as in Blender.
    act = file->addAction(tr("&Render…"), this,
                          [this] { renderInteractively(this, *m_controller, m_viewport, m_log); });
    act->setObjectName(QStringLiteral("renderAction"));
    act->setShortcut(QKeySequence(Qt::Key_F12));
    file->addSeparator();
    act = file->addAction(tr("&Quit"), this, &QWidget::close);
    act->setShortcut(QKeySequence::Quit);

    QMenu* edit = menuBar()->addMenu(tr("&Edit"));
    QUndoStack* stack = m_controller->undoStack();
    QAction* undo = stack->createUndoAction(this, tr("&Undo"));
    undo->setObjectName(QStringLiteral("undoAction"));
    QAction* redo = stack->createRedoAction(this, tr("&Redo"));
    redo->setObjectName(QStringLiteral("redoAction"));
    UndoShortcuts::install(undo, redo); // Ctrl+Z, Ctrl+Shift+Z, Ctrl+Y wherever the focus is
    edit->addAction(undo);
    edit->addAction(redo);

    QMenu* view = menuBar()->addMenu(tr("&View"));
    act = view->addAction(tr("&Frame Mesh"), m_viewport, &ViewportWidget::frameMesh);
    act->setObjectName(QStringLiteral("frameMeshAction"));
    act->setShortcut(QKeySequence(Qt::Key_F));
    act = view->addAction(tr("Reload &Shaders"), this, &MainWindow::reloadShaders);
    act->setObjectName(QStringLiteral("reloadShadersAction"));
    act->setShortcut(QKeySequence(Qt::Key_T));
    act = view->addAction(tr("&Reload Scene"), this, &MainWindow::reloadScene);
    act->setObjectName(QStringLiteral("reloadSceneAction"));
    act->setShortcut(QKeySequence(Qt::Key_R));
    view->addSeparator();
    for (QDockWidget* dock : findChildren<QDockWidget*>())
        view->addAction(dock->toggleViewAction());
    for (QToolBar* bar : findChildren<QToolBar*>())
        view->addAction(bar->toggleViewAction());
}

void MainWindow::fillRecentMenu() {
    m_recentMenu->clear();
    const QStringList files = recentFiles();
    for (const QString& path : files) {
        QAction* act = m_recentMenu->addAction(QFileInfo(path).fileName());
        act->setToolTip(path);
        act->setStatusTip(path);
        connect(act, &QAction::triggered, this, [this, path] {
            if (maybeSave())
                openFile(path);
        });
    }
    if (!files.isEmpty()) {
        m_recentMenu->addSeparator();
        m_recentMenu->addAction(tr("Clear Menu"), this, [this] {
            QSettings().remove(kRecentKey);
            fillRecentMenu();
        });
    }
    m_recentMenu->setEnabled(!files.isEmpty());
}

QStringList MainWindow::recentFiles() {
    return QSettings().value(kRecentKey).toStringList();
}

void MainWindow::addRecentFile(const QString& path) {
    const QString absolute = QFileInfo(path).absoluteFilePath();
    QStringList files = recentFiles();
    files.removeAll(absolute);
    files.prepend(absolute);
    while (files.size() > kMaxRecentFiles)
        files.removeLast();
    QSettings().setValue(kRecentKey, files);
}

} // namespace velvet::ui
