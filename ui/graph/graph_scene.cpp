#include "ui/graph/graph_scene.h"

#include "ui/graph/node_item.h"
#include "ui/models/graph_model.h"

namespace velvet::ui {

GraphScene::GraphScene(GraphModel* model, QObject* parent)
    : QGraphicsScene(parent), m_model(model) {
    setBackgroundBrush(QColor(38, 38, 40));
    connect(model, &GraphModel::changed, this, &GraphScene::onChanged);
    connect(model, &GraphModel::reset, this, &GraphScene::rebuild);
    connect(this, &QGraphicsScene::selectionChanged, this, [this] {
        for (auto& [c, item] : m_connections)
            item->updatePath();
    });
    rebuild();
}

NodeItem* GraphScene::nodeItem(graph::NodeId id) const {
    const auto it = m_nodes.find(id);
    return it == m_nodes.end() ? nullptr : it->second;
}

ConnectionItem* GraphScene::connectionItem(const graph::Connection& c) const {
    const auto it = m_connections.find(c);
    return it == m_connections.end() ? nullptr : it->second;
}

std::vector<graph::NodeId> GraphScene::selectedNodes() const {
    std::vector<graph::NodeId> ids;
    for (const auto& [id, item] : m_nodes)
        if (item->isSelected())
            ids.push_back(id);
    return ids;
}

std::vector<graph::Connection> GraphScene::selectedConnections() const {
    std::vector<graph::Connection> links;
    for (const auto& [c, item] : m_connections)
        if (item->isSelected())
            links.push_back(c);
    return links;
}

PortItem* GraphScene::portAt(QPointF p) const {
    const QRectF area(p - QPointF(PortItem::kRadius + 3, PortItem::kRadius + 3),
                      QSizeF(2 * PortItem::kRadius + 6, 2 * PortItem::kRadius + 6));
    for (QGraphicsItem* item : items(area))
        if (item->type() == PortItem::Type)
            return static_cast<PortItem*>(item);
    return nullptr;
}

void GraphScene::rebuild() {
    // Forget the items first: clear() deletes a selected node, which emits selectionChanged,
    // and the slot above must not touch links already deleted (a crash on File > New with a
    // node selected).
    m_nodes.clear();
    m_connections.clear();
    clear();
    for (const auto& [id, node] : m_model->graph().nodes())
        addNodeItem(node);
    for (const graph::Connection& c : m_model->graph().connections())
        addConnectionItem(c);
}

void GraphScene::addNodeItem(const graph::Node& node) {
    auto* item = new NodeItem(node);
    const graph::NodeId id = node.id;
    item->onMoved = [this, id] { nodeMoved(id); };
    addItem(item);
    m_nodes[id] = item;
}

void GraphScene::addConnectionItem(const graph::Connection& c) {
    NodeItem* from = nodeItem(c.outNode);
    NodeItem* to = nodeItem(c.inNode);
    if (!from || !to || !from->outputPort(c.outPort) || !to->inputPort(c.inPort))
        return;
    auto* item = new ConnectionItem(c, from->outputPort(c.outPort), to->inputPort(c.inPort));
    addItem(item);
    m_connections[c] = item;
}

void GraphScene::removeConnectionItem(const graph::Connection& c) {
    if (ConnectionItem* item = connectionItem(c)) {
        m_connections.erase(c);
        delete item;
    }
}

void GraphScene::nodeMoved(graph::NodeId id) {
    for (auto& [c, item] : m_connections)
        if (c.outNode == id || c.inNode == id)
            item->updatePath();
}

void GraphScene::onChanged(const graph::Change& change) {
    using What = graph::Change::What;
    const graph::Graph& g = m_model->graph();
    switch (change.what) {
    case What::NodeAdded:
        if (const graph::Node* n = g.node(change.node))
            addNodeItem(*n);
        break;
    case What::NodeRemoved:
        if (NodeItem* item = nodeItem(change.node)) {
            m_nodes.erase(change.node);
            delete item;
        }
        break;
    case What::Connected:
        addConnectionItem(change.connection);
        break;
    case What::Disconnected:
        removeConnectionItem(change.connection);
        break;
    case What::Moved:
        if (NodeItem* item = nodeItem(change.node))
            if (const graph::Node* n = g.node(change.node))
                item->setPos(n->position.x, n->position.y);
        break;
    case What::ValueSet:
    case What::SettingSet:
        if (NodeItem* item = nodeItem(change.node))
            if (const graph::Node* n = g.node(change.node))
                item->refresh(*n);
        break;
    }
}

} // namespace velvet::ui
