#include "ui/commands/graph_commands.h"

#include "core/graph/graph_json.h"
#include "ui/models/graph_model.h"

#include <QUndoStack>

namespace velvet::ui {
namespace {

QString label(std::string_view typeId) {
    const graph::NodeType* t = graph::findNodeType(typeId);
    return t ? QString::fromUtf8(t->label.data(), qsizetype(t->label.size()))
             : QString::fromStdString(std::string(typeId));
}

/// Adds the snapshot's nodes (ids mapped by @p ids; unmapped ids keep theirs) and its links.
void addFromSnapshot(graph::Graph& g, const std::string& snapshot,
                     const std::map<graph::NodeId, graph::NodeId>& ids, glm::vec2 offset) {
    Problems problems;
    const std::optional<graph::Graph> part =
        graph::graphFromJsonText(snapshot, "snapshot", problems);
    if (!part)
        return;
    auto mapped = [&](graph::NodeId id) {
        const auto it = ids.find(id);
        return it == ids.end() ? id : it->second;
    };
    for (const auto& [id, n] : part->nodes()) {
        const graph::NodeId to = mapped(id);
        if (!g.addNodeWithId(to, n.type->id, n.position + offset))
            continue;
        for (size_t i = 0; i < n.inputValues.size(); ++i)
            if (n.type->inputs[i].fallback == graph::Fallback::Value)
                g.setInputValue(to, graph::PortIndex(i), n.inputValues[i]);
        for (size_t i = 0; i < n.settings.size(); ++i)
            g.setSetting(to, n.type->settings[i].name, n.settings[i]);
    }
    for (graph::Connection c : part->connections()) {
        c.outNode = mapped(c.outNode);
        c.inNode = mapped(c.inNode);
        g.connect(c);
    }
}

} // namespace

AddNodeCommand::AddNodeCommand(GraphModel* model, std::string typeId, glm::vec2 position,
                               QUndoCommand* parent)
    : QUndoCommand(parent), m_model(model), m_typeId(std::move(typeId)), m_position(position) {
    setText(QObject::tr("Add %1 node").arg(label(m_typeId)));
}

void AddNodeCommand::redo() {
    graph::Graph& g = m_model->editableGraph();
    const graph::EditResult r = m_node == graph::kInvalidNodeId
                                    ? g.addNode(m_typeId, m_position)
                                    : g.addNodeWithId(m_node, m_typeId, m_position);
    if (!r) {
        m_model->refuse(QString::fromStdString(r.message));
        setObsolete(true);
        return;
    }
    m_node = r.node != graph::kInvalidNodeId ? r.node : m_node;
}

void AddNodeCommand::undo() {
    if (m_node != graph::kInvalidNodeId)
        m_model->editableGraph().removeNode(m_node);
}

RemoveNodesCommand::RemoveNodesCommand(GraphModel* model, std::vector<graph::NodeId> ids,
                                       QUndoCommand* parent)
    : QUndoCommand(parent), m_model(model), m_ids(std::move(ids)) {
    m_snapshot = model->snapshot(m_ids);
    for (graph::NodeId id : m_ids)
        for (const graph::Connection& c : model->graph().connectionsOf(id))
            if (std::find(m_links.begin(), m_links.end(), c) == m_links.end())
                m_links.push_back(c);
    setText(m_ids.size() == 1 ? QObject::tr("Delete node")
                              : QObject::tr("Delete %n nodes", "", int(m_ids.size())));
}

void RemoveNodesCommand::redo() {
    for (graph::NodeId id : m_ids)
        m_model->editableGraph().removeNode(id);
}

void RemoveNodesCommand::undo() {
    graph::Graph& g = m_model->editableGraph();
    addFromSnapshot(g, m_snapshot, {}, glm::vec2(0.0f));
    for (const graph::Connection& c : m_links)
        if (!g.connectionTo(c.inNode, c.inPort) || *g.connectionTo(c.inNode, c.inPort) != c)
            g.connect(c);
}

PasteNodesCommand::PasteNodesCommand(GraphModel* model, std::string snapshot, glm::vec2 offset,
                                     const QString& text, QUndoCommand* parent)
    : QUndoCommand(text, parent), m_model(model), m_snapshot(std::move(snapshot)),
      m_offset(offset) {}

void PasteNodesCommand::redo() {
    graph::Graph& g = m_model->editableGraph();
    if (m_idMap.empty()) {
        Problems problems;
        const std::optional<graph::Graph> part =
            graph::graphFromJsonText(m_snapshot, "clipboard", problems);
        if (!part || part->nodes().empty()) {
            m_model->refuse(QObject::tr("Nothing to paste: the clipboard holds no graph nodes"));
            setObsolete(true);
            return;
        }
        graph::NodeId next = g.nextId();
        for (const auto& [id, n] : part->nodes()) {
            if (n.type->isOutput && g.outputNode() != graph::kInvalidNodeId)
                continue; // at most one material output: the pasted copy is left out
            m_idMap[id] = next++;
        }
        // Nodes left out (a second output) get an id no one has, so addNodeWithId refuses
        // nothing else; they are simply not added.
        for (const auto& [id, n] : part->nodes())
            if (!m_idMap.count(id))
                m_idMap[id] = graph::kInvalidNodeId;
        for (const auto& [from, to] : m_idMap)
            if (to != graph::kInvalidNodeId)
                m_newIds.push_back(to);
    }
    addFromSnapshot(g, m_snapshot, m_idMap, m_offset);
}

void PasteNodesCommand::undo() {
    for (graph::NodeId id : m_newIds)
        m_model->editableGraph().removeNode(id);
}

MoveNodesCommand::MoveNodesCommand(GraphModel* model, std::map<graph::NodeId, Move> moves,
                                   int dragId, QUndoCommand* parent)
    : QUndoCommand(parent), m_model(model), m_moves(std::move(moves)), m_dragId(dragId) {
    setText(m_moves.size() == 1 ? QObject::tr("Move node")
                                : QObject::tr("Move %n nodes", "", int(m_moves.size())));
}

void MoveNodesCommand::redo() {
    for (const auto& [id, m] : m_moves)
        m_model->editableGraph().moveNode(id, m.to);
}

void MoveNodesCommand::undo() {
    for (const auto& [id, m] : m_moves)
        m_model->editableGraph().moveNode(id, m.from);
}

bool MoveNodesCommand::mergeWith(const QUndoCommand* other) {
    const auto* o = static_cast<const MoveNodesCommand*>(other);
    if (m_dragId == 0 || o->m_dragId != m_dragId || o->m_moves.size() != m_moves.size())
        return false;
    for (const auto& [id, m] : o->m_moves)
        if (!m_moves.count(id))
            return false;
    for (const auto& [id, m] : o->m_moves)
        m_moves[id].to = m.to;
    return true;
}

ConnectCommand::ConnectCommand(GraphModel* model, graph::Connection c, QUndoCommand* parent)
    : QUndoCommand(QObject::tr("Connect"), parent), m_model(model), m_connection(c) {}

void ConnectCommand::redo() {
    const graph::EditResult r = m_model->editableGraph().connect(m_connection);
    if (!r)
        m_model->refuse(QString::fromStdString(r.message));
}

void ConnectCommand::undo() {
    m_model->editableGraph().disconnect(m_connection);
}

DisconnectCommand::DisconnectCommand(GraphModel* model, graph::Connection c, QUndoCommand* parent)
    : QUndoCommand(QObject::tr("Disconnect"), parent), m_model(model), m_connection(c) {}

void DisconnectCommand::redo() {
    m_model->editableGraph().disconnect(m_connection);
}

void DisconnectCommand::undo() {
    m_model->editableGraph().connect(m_connection);
}

SetNodeInputCommand::SetNodeInputCommand(GraphModel* model, graph::NodeId node,
                                         graph::PortIndex input, glm::vec4 oldValue,
                                         glm::vec4 newValue, int mergeKey, QUndoCommand* parent)
    : ValueEditCommand(oldValue, newValue, mergeKey, parent), m_model(model), m_node(node),
      m_input(input) {
    setText(QObject::tr("Set node input"));
}

void SetNodeInputCommand::redo() {
    const graph::EditResult r = m_model->editableGraph().setInputValue(m_node, m_input, m_new);
    if (!r)
        m_model->refuse(QString::fromStdString(r.message));
}

void SetNodeInputCommand::undo() {
    m_model->editableGraph().setInputValue(m_node, m_input, m_old);
}

SetNodeSettingCommand::SetNodeSettingCommand(GraphModel* model, graph::NodeId node,
                                             std::string name, std::string oldValue,
                                             std::string newValue, QUndoCommand* parent)
    : QUndoCommand(parent), m_model(model), m_node(node), m_name(std::move(name)),
      m_old(std::move(oldValue)), m_new(std::move(newValue)) {
    QString what = QString::fromStdString(m_name);
    if (const graph::Node* n = model->graph().node(node)) {
        const int index = n->type->settingIndex(m_name);
        if (index >= 0) {
            const std::string_view l = n->type->settings[size_t(index)].label;
            what = label(n->type->id) + QLatin1Char(' ') +
                   QString::fromUtf8(l.data(), qsizetype(l.size())).toLower();
        }
    }
    setText(QObject::tr("Set %1").arg(what));
}

void SetNodeSettingCommand::redo() {
    const graph::EditResult r = m_model->editableGraph().setSetting(m_node, m_name, m_new);
    if (!r)
        m_model->refuse(QString::fromStdString(r.message));
}

void SetNodeSettingCommand::undo() {
    m_model->editableGraph().setSetting(m_node, m_name, m_old);
}

bool pushConnect(GraphModel* model, const graph::Connection& c) {
    const graph::Graph& g = model->graph();
    const graph::Connection* existing = g.connectionTo(c.inNode, c.inPort);
    if (existing && *existing == c)
        return false;
    graph::EditResult check;
    if (existing) {
        // One link per input: replacing is disconnect + connect, checked on a copy first.
        graph::Graph trial = g;
        trial.disconnect(*existing);
        check = trial.canConnect(c);
    } else {
        check = g.canConnect(c);
    }
    if (!check) {
        model->refuse(
            QObject::tr("Connection refused: %1").arg(QString::fromStdString(check.message)));
        return false;
    }
    if (!existing) {
        model->undoStack()->push(new ConnectCommand(model, c));
        return true;
    }
    auto* macro = new QUndoCommand(QObject::tr("Replace link"));
    new DisconnectCommand(model, *existing, macro);
    new ConnectCommand(model, c, macro);
    model->undoStack()->push(macro);
    return true;
}

} // namespace velvet::ui
