#pragma once
/// @file graph_commands.h
/// Undoable edits of the material graph. Each command's redo()/undo() calls the model API
/// (core/graph/graph.h) on GraphModel's graph, whose listener updates the scene and the document
/// (QtNodes' internal/UndoCommands.hpp works the same way). Nodes keep their ids across undo and
/// redo, so later commands that name them stay valid.

#include "core/graph/graph.h"
#include "ui/commands/value_edit_command.h"

#include <QUndoCommand>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <map>
#include <string>
#include <vector>

namespace velvet::ui {

class GraphModel;

/// Adds one node of a catalogue type.
class AddNodeCommand : public QUndoCommand {
public:
    AddNodeCommand(GraphModel* model, std::string typeId, glm::vec2 position,
                   QUndoCommand* parent = nullptr);
    void redo() override;
    void undo() override;
    /// The node's id once redo() has run (kInvalidNodeId if the model refused it).
    graph::NodeId node() const { return m_node; }

private:
    GraphModel* m_model;
    std::string m_typeId;
    glm::vec2 m_position;
    graph::NodeId m_node = graph::kInvalidNodeId;
};

/// Removes nodes with their links; undo restores them from a JSON snapshot (values, settings,
/// positions, ids) and reconnects every link they had, inside the selection or not.
class RemoveNodesCommand : public QUndoCommand {
public:
    RemoveNodesCommand(GraphModel* model, std::vector<graph::NodeId> ids,
                       QUndoCommand* parent = nullptr);
    void redo() override;
    void undo() override;

private:
    GraphModel* m_model;
    std::vector<graph::NodeId> m_ids;
    std::string m_snapshot;                 ///< graph_json.h text of the nodes
    std::vector<graph::Connection> m_links; ///< every link to or from them
};

/// Adds the nodes of a snapshot (clipboard text) with fresh ids, offset by @p offset, with the
/// links among them (paste, duplicate).
class PasteNodesCommand : public QUndoCommand {
public:
    PasteNodesCommand(GraphModel* model, std::string snapshot, glm::vec2 offset,
                      const QString& text, QUndoCommand* parent = nullptr);
    void redo() override;
    void undo() override;
    const std::vector<graph::NodeId>& nodes() const { return m_newIds; }

private:
    GraphModel* m_model;
    std::string m_snapshot;
    glm::vec2 m_offset;
    std::map<graph::NodeId, graph::NodeId> m_idMap; ///< snapshot id -> pasted id (first redo)
    std::vector<graph::NodeId> m_newIds;
};

/// Moves nodes. Commands with the same non-zero drag id and the same nodes merge (one drag).
class MoveNodesCommand : public QUndoCommand {
public:
    static constexpr int kId = 0x6a01;
    struct Move {
        glm::vec2 from, to;
    };
    MoveNodesCommand(GraphModel* model, std::map<graph::NodeId, Move> moves, int dragId,
                     QUndoCommand* parent = nullptr);
    void redo() override;
    void undo() override;
    int id() const override { return kId; }
    bool mergeWith(const QUndoCommand* other) override;

private:
    GraphModel* m_model;
    std::map<graph::NodeId, Move> m_moves;
    int m_dragId;
};

/// Adds one link (the caller checked Graph::canConnect).
class ConnectCommand : public QUndoCommand {
public:
    ConnectCommand(GraphModel* model, graph::Connection c, QUndoCommand* parent = nullptr);
    void redo() override;
    void undo() override;

private:
    GraphModel* m_model;
    graph::Connection m_connection;
};

/// Removes one link.
class DisconnectCommand : public QUndoCommand {
public:
    DisconnectCommand(GraphModel* model, graph::Connection c, QUndoCommand* parent = nullptr);
    void redo() override;
    void undo() override;

private:
    GraphModel* m_model;
    graph::Connection m_connection;
};

/// Sets an input's value. Commands with the same node, input and non-zero merge key (one slider
/// drag) merge.
class SetNodeInputCommand : public ValueEditCommand<SetNodeInputCommand, glm::vec4> {
public:
    static constexpr int kId = 0x6a02;
    SetNodeInputCommand(GraphModel* model, graph::NodeId node, graph::PortIndex input,
                        glm::vec4 oldValue, glm::vec4 newValue, int mergeKey,
                        QUndoCommand* parent = nullptr);
    void redo() override;
    void undo() override;

private:
    friend ValueEditCommand;
    bool sameTarget(const SetNodeInputCommand& next) const {
        return next.m_node == m_node && next.m_input == m_input;
    }

    GraphModel* m_model;
    graph::NodeId m_node;
    graph::PortIndex m_input;
};

/// Sets a string setting of a node (an image file, a colour space): a texture rebind, never a
/// recompile (graph::ChangeKind::Texture).
class SetNodeSettingCommand : public QUndoCommand {
public:
    SetNodeSettingCommand(GraphModel* model, graph::NodeId node, std::string name,
                          std::string oldValue, std::string newValue,
                          QUndoCommand* parent = nullptr);
    void redo() override;
    void undo() override;

private:
    GraphModel* m_model;
    graph::NodeId m_node;
    std::string m_name;
    std::string m_old, m_new;
};

/// Pushes a connection drag's result: one ConnectCommand, or a "Replace link" macro
/// (disconnect the input's link, then connect) when the input is already fed. A refused link is
/// reported through GraphModel::refuse() and pushes nothing. True when something was pushed.
bool pushConnect(GraphModel* model, const graph::Connection& c);

} // namespace velvet::ui
