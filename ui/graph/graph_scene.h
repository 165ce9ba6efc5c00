#pragma once
/// @file graph_scene.h
/// The node editor's QGraphicsScene: maps NodeId to NodeItem and Connection to ConnectionItem and
/// keeps them in step with GraphModel's change signals (QtNodes' BasicGraphicsScene does the
/// same). It never edits the model.

#include "core/graph/graph.h"

#include <QGraphicsScene>
#include <map>

namespace velvet::ui {

class ConnectionItem;
class GraphModel;
class NodeItem;
class PortItem;

class GraphScene : public QGraphicsScene {
    Q_OBJECT
public:
    explicit GraphScene(GraphModel* model, QObject* parent = nullptr);

    GraphModel* model() const { return m_model; }
    NodeItem* nodeItem(graph::NodeId id) const;
    ConnectionItem* connectionItem(const graph::Connection& c) const;
    /// Selected nodes, in id order.
    std::vector<graph::NodeId> selectedNodes() const;
    /// Selected links.
    std::vector<graph::Connection> selectedConnections() const;
    /// The port item at scene point @p p (within a few pixels), or nullptr.
    PortItem* portAt(QPointF p) const;

private:
    void onChanged(const graph::Change& change);
    void rebuild();
    void addNodeItem(const graph::Node& node);
    void addConnectionItem(const graph::Connection& c);
    void removeConnectionItem(const graph::Connection& c);
    void nodeMoved(graph::NodeId id);

    GraphModel* m_model;
    std::map<graph::NodeId, NodeItem*> m_nodes;
    std::map<graph::Connection, ConnectionItem*> m_connections;
};

} // namespace velvet::ui
