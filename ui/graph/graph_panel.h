#pragma once
/// @file graph_panel.h
/// The "Material graph" dock's contents: the live graph model, its scene and view. Refused
/// edits come out of message() for the status bar and the Log.

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

private:
    GraphModel* m_model;
    GraphScene* m_scene;
    GraphView* m_view;
};

} // namespace velvet::ui
