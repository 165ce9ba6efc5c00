#pragma once
/// @file graph_model.h
/// The editor's live material graph: one graph::Graph that undo commands edit through its API,
/// forwarded as Qt signals to the graph scene, and copied into the document (Material::graph)
/// after every change so the renderer and the file see it. Reloads itself when the document's
/// material is replaced (open, new, preset). No GL.

#include "core/graph/graph.h"

#include <QObject>
#include <QString>
#include <vector>

class QUndoStack;

namespace velvet::ui {

class DocumentController;

class GraphModel : public QObject, private graph::GraphListener {
    Q_OBJECT
public:
    explicit GraphModel(DocumentController* controller, QObject* parent = nullptr);
    ~GraphModel() override;

    /// The graph, read-only: edits go through commands (ui/commands/graph_commands.h).
    const graph::Graph& graph() const { return m_graph; }
    /// For commands only: their redo()/undo() call the model API on it.
    graph::Graph& editableGraph() { return m_graph; }
    QUndoStack* undoStack() const;
    DocumentController* controller() const { return m_controller; }

    /// Reports a refused edit (the model's one-line reason) to whoever shows messages.
    void refuse(const QString& message) { emit editRefused(message); }

    /// @name Edits the Properties panel asks for (one undo command each; none for a no-op)
    /// Sets input @p input of node @p node, constrained by core (constrainInputValue); edits
    /// with the same non-zero @p mergeKey (one slider drag) merge. @p reset: back to the input's
    /// default. False when nothing changes.
    /// @{
    bool editNodeInput(graph::NodeId node, graph::PortIndex input, glm::vec4 value, int mergeKey,
                       bool reset = false);
    bool editNodeSetting(graph::NodeId node, const std::string& name, const std::string& value);
    /// @}

    /// @name Snapshots (clipboard, delete and its undo)
    /// The nodes @p ids with their values, settings and the links among them, as the JSON text
    /// of graph_json.h.
    /// @{
    std::string snapshot(const std::vector<graph::NodeId>& ids) const;
    /// @}

signals:
    /// One change, after it was applied (graph.h's Change).
    void changed(const velvet::graph::Change& change);
    /// The whole graph was replaced (a document opened): views rebuild.
    void reset();
    /// An edit was refused; @p message says why.
    void editRefused(const QString& message);

private:
    void graphChanged(const graph::Change& change) override;
    void reloadFromDocument();
    void pushToDocument();

    DocumentController* m_controller;
    graph::Graph m_graph;
    bool m_reloading = false;
};

} // namespace velvet::ui
