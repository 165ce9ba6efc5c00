#pragma once
/// @file graph_editor_window.h
/// The node editor of a widget test's MainWindow in a floating window of its own, large enough
/// for the material output node, active and focused, and the main window around it
/// (test_ui_graph, test_ui_graph_view).

#include "ui/document_controller.h"
#include "ui/graph/graph_panel.h"
#include "ui/graph/graph_view.h"
#include "ui/main_window.h"
#include "ui_test_window.h"

#include <QApplication>
#include <QDockWidget>
#include <QString>
#include <QTest>
#include <memory>

namespace velvet::test {

/// Floats @p window's graph dock at 1000 x 700 and focuses its view; its panel into @p panel.
/// Empty when it is up; otherwise what went wrong.
inline QString openGraphEditor(ui::MainWindow* window, ui::GraphPanel*& panel) {
    panel = window->findChild<ui::GraphPanel*>();
    auto* dock = window->findChild<QDockWidget*>(QStringLiteral("graphDock"));
    if (!panel || !dock)
        return QStringLiteral("no graph panel or dock");
    dock->setFloating(true);
    dock->resize(1000, 700);
    dock->show();
    if (!QTest::qWaitForWindowExposed(dock))
        return QStringLiteral("the graph dock was not exposed");
    dock->activateWindow();
    QApplication::setActiveWindow(dock);
    ui::GraphView* view = panel->view();
    view->setFocus();
    if (!QTest::qWaitFor([view] { return view->hasFocus(); }))
        return QStringLiteral("the graph view did not take the focus");
    return {};
}

/// A new main window (no saved layout) shown at 900 x 700 with its first frame, and its node
/// editor opened (openGraphEditor): the set-up of test_ui_graph and test_ui_graph_view. Empty
/// when it is up; otherwise what went wrong.
inline QString openWindowWithGraphEditor(std::unique_ptr<ui::MainWindow>& window,
                                         ui::DocumentController*& doc, ui::GraphPanel*& panel,
                                         ui::GraphView*& view) {
    window = std::make_unique<ui::MainWindow>(/*restoreLayout=*/false);
    doc = window->controller();
    if (const QString up = showWithFirstFrame(window.get(), {900, 700}); !up.isEmpty())
        return up;
    if (const QString editor = openGraphEditor(window.get(), panel); !editor.isEmpty())
        return editor;
    view = panel->view();
    return {};
}

} // namespace velvet::test
