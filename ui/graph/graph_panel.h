#pragma once
/// @file graph_panel.h
/// The "Material graph" dock's contents: the live graph model, its scene and view. Refused
/// edits come out of message() for the status bar and the Log; the selected node comes out of
/// nodeSelected() for the Properties panel.

#include "core/graph/graph_types.h"

#include <QWidget>

namespace velvet::ui {

class DocumentController;
class GraphModel;
class GraphScene;
class GraphView;

class GraphPanel : public QWidget {
    Q_OBJECT
public:
    explicit GraphPanel(DocumentController* controller, QWidget* parent = nullptr);

    GraphModel* model() const { return m_model; }
    GraphScene* scene() const { return m_scene; }
    GraphView* view() const { return m_view; }

signals:
    /// A refused edit, with the model's reason.
    void message(const QString& text);
    /// The selection became exactly node @p id, or kInvalidNodeId when it became anything else
    /// (nothing, several nodes, links only). The window shows the node in Properties.
    void nodeSelected(velvet::graph::NodeId id);

private:
    GraphModel* m_model;
    GraphScene* m_scene;
    GraphView* m_view;
};

} // namespace velvet::ui
