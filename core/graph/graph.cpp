#include "core/graph/graph.h"

#include <algorithm>
#include <cmath>

namespace velvet::graph {
namespace {

std::string nodeName(const Node& n) {
    return std::string(n.type->id) + " " + std::to_string(n.id);
}

std::string inputName(const Node& n, PortIndex i) {
    return nodeName(n) + " input \"" + std::string(n.type->inputs[i].name) + "\"";
}

std::string outputName(const Node& n, PortIndex i) {
    return nodeName(n) + " output \"" + std::string(n.type->outputs[i].name) + "\"";
}

} // namespace

bool Node::operator==(const Node& o) const {
    return id == o.id && type == o.type && position == o.position && inputValues == o.inputValues &&
           settings == o.settings;
}

Graph::Graph(const Graph& other)
    : m_nodes(other.m_nodes), m_connections(other.m_connections), m_nextId(other.m_nextId) {}

Graph& Graph::operator=(const Graph& other) {
    m_nodes = other.m_nodes;
    m_connections = other.m_connections;
    m_nextId = other.m_nextId;
    return *this;
}

EditResult Graph::addNode(std::string_view typeId, glm::vec2 position) {
    return addNodeWithId(m_nextId, typeId, position);
}

EditResult Graph::addNodeWithId(NodeId id, std::string_view typeId, glm::vec2 position) {
    const NodeType* type = findNodeType(typeId);
    if (!type)
        return EditResult::refuse("unknown node type \"" + std::string(typeId) + "\"");
    if (id == kInvalidNodeId)
        return EditResult::refuse("node id 0 is not valid");
    if (m_nodes.count(id))
        return EditResult::refuse("node id " + std::to_string(id) + " is already used");
    if (type->isOutput && outputNode() != kInvalidNodeId)
        return EditResult::refuse("the graph already has a material output (node " +
                                  std::to_string(outputNode()) + ")");
    if (!std::isfinite(position.x) || !std::isfinite(position.y))
        return EditResult::refuse("node position is not a finite number");
    Node n;
    n.id = id;
    n.type = type;
    n.position = position;
    for (const InputSpec& in : type->inputs)
        n.inputValues.push_back(in.defaultValue);
    for (const SettingSpec& s : type->settings)
        n.settings.emplace_back(s.defaultValue);
    m_nodes.emplace(id, std::move(n));
    m_nextId = std::max(m_nextId, id + 1);
    Change c;
    c.what = Change::What::NodeAdded;
    c.kind = ChangeKind::Structure;
    c.node = id;
    notify(c);
    EditResult r;
    r.node = id;
    return r;
}

EditResult Graph::removeNode(NodeId id) {
    if (!m_nodes.count(id))
        return EditResult::refuse("no node " + std::to_string(id));
    for (const Connection& link : connectionsOf(id)) {
        m_connections.erase(link);
        Change c;
        c.what = Change::What::Disconnected;
        c.kind = ChangeKind::Structure;
        c.node = link.inNode;
        c.connection = link;
        notify(c);
    }
    m_nodes.erase(id);
    Change c;
    c.what = Change::What::NodeRemoved;
    c.kind = ChangeKind::Structure;
    c.node = id;
    notify(c);
    return {};
}

EditResult Graph::canConnect(const Connection& c) const {
    const Node* from = node(c.outNode);
    const Node* to = node(c.inNode);
    if (!from)
        return EditResult::refuse("no node " + std::to_string(c.outNode));
    if (!to)
        return EditResult::refuse("no node " + std::to_string(c.inNode));
    if (c.outPort >= from->type->outputs.size())
        return EditResult::refuse(nodeName(*from) + " has no output " + std::to_string(c.outPort) +
                                  " (it has " + std::to_string(from->type->outputs.size()) + ")");
    if (c.inPort >= to->type->inputs.size())
        return EditResult::refuse(nodeName(*to) + " has no input " + std::to_string(c.inPort) +
                                  " (it has " + std::to_string(to->type->inputs.size()) + ")");
    const InputSpec& in = to->type->inputs[c.inPort];
    const OutputSpec& out = from->type->outputs[c.outPort];
    if (!in.connectable)
        return EditResult::refuse(inputName(*to, c.inPort) + " is a setting and takes no link");
    if (!canConvert(out.type, in.type))
        return EditResult::refuse("cannot connect " + outputName(*from, c.outPort) + " (" +
                                  std::string(portTypeName(out.type)) + ") to " +
                                  inputName(*to, c.inPort) + " (" +
                                  std::string(portTypeName(in.type)) + ")");
    if (const Connection* taken = connectionTo(c.inNode, c.inPort))
        return EditResult::refuse(inputName(*to, c.inPort) + " is already fed by node " +
                                  std::to_string(taken->outNode) + "; disconnect it first");
    if (c.outNode == c.inNode || reaches(c.inNode, c.outNode))
        return EditResult::refuse("connecting " + nodeName(*from) + " to " + nodeName(*to) +
                                  " would make a cycle");
    return {};
}

EditResult Graph::connect(const Connection& c) {
    EditResult r = canConnect(c);
    if (!r)
        return r;
    m_connections.insert(c);
    Change ch;
    ch.what = Change::What::Connected;
    ch.kind = ChangeKind::Structure;
    ch.node = c.inNode;
    ch.connection = c;
    notify(ch);
    return r;
}

EditResult Graph::disconnect(const Connection& connection) {
    // A copy first: callers pass references into m_connections (connectionTo(), connections()),
    // which the erase frees before the change below is reported (ASan, test_core_graph).
    const Connection c = connection;
    if (!m_connections.erase(c))
        return EditResult::refuse("no link " + toString(c));
    Change ch;
    ch.what = Change::What::Disconnected;
    ch.kind = ChangeKind::Structure;
    ch.node = c.inNode;
    ch.connection = c;
    notify(ch);
    return {};
}

EditResult Graph::setInputValue(NodeId id, PortIndex input, glm::vec4 value) {
    Node* n = findNode(id);
    if (!n)
        return EditResult::refuse("no node " + std::to_string(id));
    if (input >= n->type->inputs.size())
        return EditResult::refuse(nodeName(*n) + " has no input " + std::to_string(input));
    const InputSpec& spec = n->type->inputs[input];
    if (spec.fallback != Fallback::Value)
        return EditResult::refuse(inputName(*n, input) + " has no value of its own" +
                                  (spec.fallback == Fallback::Material
                                       ? " (it keeps the material's parameter)"
                                       : " (it reads the mesh's UVs)"));
    for (int i = 0; i < portTypeComponents(spec.type); ++i)
        if (!std::isfinite(value[i]))
            return EditResult::refuse(inputName(*n, input) + ": value is not a finite number");
    n->inputValues[input] = constrainInputValue(spec, value);
    Change c;
    c.what = Change::What::ValueSet;
    c.kind = ChangeKind::Value;
    c.node = id;
    c.index = input;
    notify(c);
    return {};
}

EditResult Graph::setSetting(NodeId id, std::string_view name, std::string value) {
    Node* n = findNode(id);
    if (!n)
        return EditResult::refuse("no node " + std::to_string(id));
    const int index = n->type->settingIndex(name);
    if (index < 0)
        return EditResult::refuse(nodeName(*n) + " has no setting \"" + std::string(name) + "\"");
    n->settings[size_t(index)] = std::move(value);
    Change c;
    c.what = Change::What::SettingSet;
    c.kind = n->type->samplesTexture ? ChangeKind::Texture : ChangeKind::Structure;
    c.node = id;
    c.index = PortIndex(index);
    notify(c);
    return {};
}

EditResult Graph::moveNode(NodeId id, glm::vec2 position) {
    Node* n = findNode(id);
    if (!n)
        return EditResult::refuse("no node " + std::to_string(id));
    if (!std::isfinite(position.x) || !std::isfinite(position.y))
        return EditResult::refuse("node position is not a finite number");
    n->position = position;
    Change c;
    c.what = Change::What::Moved;
    c.kind = ChangeKind::Layout;
    c.node = id;
    notify(c);
    return {};
}

void Graph::clear() {
    while (!m_nodes.empty())
        removeNode(m_nodes.begin()->first);
    m_nextId = 1;
}

const Node* Graph::node(NodeId id) const {
    const auto it = m_nodes.find(id);
    return it == m_nodes.end() ? nullptr : &it->second;
}

Node* Graph::findNode(NodeId id) {
    const auto it = m_nodes.find(id);
    return it == m_nodes.end() ? nullptr : &it->second;
}

const Connection* Graph::connectionTo(NodeId id, PortIndex input) const {
    for (const Connection& c : m_connections)
        if (c.inNode == id && c.inPort == input)
            return &c;
    return nullptr;
}

std::vector<Connection> Graph::connectionsOf(NodeId id) const {
    std::vector<Connection> out;
    for (const Connection& c : m_connections)
        if (c.inNode == id || c.outNode == id)
            out.push_back(c);
    return out;
}

NodeId Graph::outputNode() const {
    for (const auto& [id, n] : m_nodes)
        if (n.type->isOutput)
            return id;
    return kInvalidNodeId;
}

bool Graph::reaches(NodeId from, NodeId to) const {
    std::vector<NodeId> stack{from};
    std::set<NodeId> seen;
    while (!stack.empty()) {
        const NodeId n = stack.back();
        stack.pop_back();
        if (n == to)
            return true;
        if (!seen.insert(n).second)
            continue;
        // Links are ordered by outNode first: the links leaving n are one contiguous range.
        for (auto it = m_connections.lower_bound(Connection{n, 0, 0, 0});
             it != m_connections.end() && it->outNode == n; ++it)
            stack.push_back(it->inNode);
    }
    return false;
}

bool Graph::operator==(const Graph& other) const {
    return m_nodes == other.m_nodes && m_connections == other.m_connections;
}

void Graph::addListener(GraphListener* listener) {
    if (listener &&
        std::find(m_listeners.begin(), m_listeners.end(), listener) == m_listeners.end())
        m_listeners.push_back(listener);
}

void Graph::removeListener(GraphListener* listener) {
    m_listeners.erase(std::remove(m_listeners.begin(), m_listeners.end(), listener),
                      m_listeners.end());
}

void Graph::notify(const Change& change) {
    // A copy, so a listener may remove itself while being told.
    const std::vector<GraphListener*> listeners = m_listeners;
    for (GraphListener* l : listeners)
        l->graphChanged(change);
}

} // namespace velvet::graph
