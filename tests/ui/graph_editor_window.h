#pragma once
/// @file graph_editor_window.h
/// The node editor of a widget test's MainWindow in a floating window of its own, large enough
/// for the material output node, active and focused (test_ui_graph, test_ui_graph_view).

#include "ui/graph/graph_panel.h"
#include "ui/graph/graph_view.h"
#include "ui/main_window.h"

#include <QApplication>
#include <QDockWidget>
#include <QString>
#include <QTest>

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

} // namespace velvet::test
