#include "ui/models/graph_model.h"

#include "core/graph/graph_json.h"
#include "ui/commands/graph_commands.h"
#include "ui/document_controller.h"

#include <QUndoStack>
#include <algorithm>
#include <memory>

namespace velvet::ui {

GraphModel::GraphModel(DocumentController* controller, QObject* parent)
    : QObject(parent), m_controller(controller) {
    m_graph.addListener(this);
    reloadFromDocument();
    connect(controller, &DocumentController::documentReplaced, this,
            &GraphModel::reloadFromDocument);
    connect(controller, &DocumentController::materialReplaced, this,
            &GraphModel::reloadFromDocument);
}

GraphModel::~GraphModel() {
    m_graph.removeListener(this);
}

QUndoStack* GraphModel::undoStack() const {
    return m_controller->undoStack();
}

void GraphModel::reloadFromDocument() {
    const SharedGraph& g = m_controller->material().graph;
    if (g ? *g == m_graph : m_graph.nodes().empty())
        return; // our own edit coming back, or nothing to do
    // Copy assignment keeps this graph's listeners (graph.h), so no changes are sent: views
    // rebuild on reset().
    m_graph = g ? *g : graph::Graph{};
    emit reset();
}

void GraphModel::pushToDocument() {
    // An empty graph is no graph: a document without one saves and compares as before.
    m_controller->setMaterialGraph(m_graph.nodes().empty()
                                       ? SharedGraph{}
                                       : SharedGraph(std::make_shared<graph::Graph>(m_graph)));
}

void GraphModel::graphChanged(const graph::Change& change) {
    emit changed(change);
    pushToDocument();
}

bool GraphModel::editNodeInput(graph::NodeId node, graph::PortIndex input, glm::vec4 value,
                               int mergeKey, bool reset) {
    const graph::Node* n = m_graph.node(node);
    if (!n || input >= n->type->inputs.size())
        return false;
    const graph::InputSpec& spec = n->type->inputs[input];
    const glm::vec4 next = graph::constrainInputValue(spec, reset ? spec.defaultValue : value);
    const glm::vec4 old = n->inputValues[input];
    if (next == old)
        return false;
    auto* cmd = new SetNodeInputCommand(this, node, input, old, next, reset ? 0 : mergeKey);
    const auto view = [](std::string_view s) {
        return QString::fromUtf8(s.data(), qsizetype(s.size()));
    };
    cmd->setText(
        (reset ? tr("Reset %1 %2") : tr("Set %1 %2")).arg(view(n->type->label), view(spec.label)));
    undoStack()->push(cmd);
    return true;
}

bool GraphModel::editNodeSetting(graph::NodeId node, const std::string& name,
                                 const std::string& value) {
    const graph::Node* n = m_graph.node(node);
    const int index = n ? n->type->settingIndex(name) : -1;
    if (index < 0 || n->settings[size_t(index)] == value)
        return false;
    undoStack()->push(
        new SetNodeSettingCommand(this, node, name, n->settings[size_t(index)], value));
    return true;
}

std::string GraphModel::snapshot(const std::vector<graph::NodeId>& ids) const {
    graph::Graph part;
    for (graph::NodeId id : ids) {
        const graph::Node* n = m_graph.node(id);
        if (!n)
            continue;
        part.addNodeWithId(id, n->type->id, n->position);
        for (size_t i = 0; i < n->inputValues.size(); ++i)
            part.setInputValue(id, graph::PortIndex(i), n->inputValues[i]);
        for (size_t i = 0; i < n->settings.size(); ++i)
            part.setSetting(id, n->type->settings[i].name, n->settings[i]);
    }
    for (const graph::Connection& c : m_graph.connections())
        if (part.node(c.outNode) && part.node(c.inNode))
            part.connect(c);
    return graph::graphToJsonText(part);
}

} // namespace velvet::ui
