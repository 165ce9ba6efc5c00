#pragma once
/// @file node_item.h
/// Graphics items of the node editor: a node (title, ports, a thumbnail for texture nodes), its
/// ports and the links between them. Items draw and hit-test; they never edit the model (the
/// view turns gestures into commands).

#include "core/graph/graph.h"
#include "core/image.h"

#include <QGraphicsItem>
#include <QImage>
#include <QString>
#include <functional>
#include <vector>

namespace velvet::ui {

/// One port circle, child of its NodeItem.
class PortItem : public QGraphicsItem {
public:
    enum { Type = UserType + 0x6a1 };
    PortItem(graph::NodeId node, graph::PortIndex index, bool output, graph::PortType type,
             QGraphicsItem* parent);
    int type() const override { return Type; }
    QRectF boundingRect() const override;
    void paint(QPainter* painter, const QStyleOptionGraphicsItem*, QWidget*) override;

    graph::NodeId node() const { return m_node; }
    graph::PortIndex index() const { return m_index; }
    bool isOutput() const { return m_output; }
    /// The port centre in scene coordinates (where links attach).
    QPointF anchor() const { return scenePos(); }

    static constexpr qreal kRadius = 6.0;

private:
    graph::NodeId m_node;
    graph::PortIndex m_index;
    bool m_output;
    graph::PortType m_portType;
};

/// One node: a box with a title, its connectable inputs on the left, outputs on the right, and
/// for nodes that make a texture-like value (hasPreview) a thumbnail of their first output, as the
/// GPU renders it (GraphPanel asks for it; render/graph_preview.h draws it).
class NodeItem : public QGraphicsItem {
public:
    enum { Type = UserType + 0x6a2 };
    explicit NodeItem(const graph::Node& node);
    int type() const override { return Type; }
    QRectF boundingRect() const override;
    void paint(QPainter* painter, const QStyleOptionGraphicsItem* option, QWidget*) override;

    graph::NodeId node() const { return m_node; }
    /// The port item of input / output @p index, or nullptr (inputs that refuse links have none).
    PortItem* inputPort(graph::PortIndex index) const;
    PortItem* outputPort(graph::PortIndex index) const;
    /// Re-reads settings (a texture node's file, shown as the tooltip) and repaints.
    void refresh(const graph::Node& node);
    /// Where input label @p i / output label @p i is drawn, in item coordinates (each column as
    /// wide as its longest label, so none is cut).
    QRectF inputLabelRect(size_t i) const;
    QRectF outputLabelRect(size_t i) const;
    const std::vector<QString>& inputLabels() const { return m_inputLabels; }
    const std::vector<QString>& outputLabels() const { return m_outputLabels; }
    /// Whether the node shows a thumbnail: the Texture, Noise, Math and Channels categories.
    bool hasPreview() const { return m_hasPreview; }
    /// Shows @p image (RGBA holding display values in [0, 1], render/graph_preview.h) as the
    /// thumbnail; an empty image clears it.
    void setPreview(const Image& image);
    /// The thumbnail shown (null until the first preview arrives).
    const QImage& preview() const { return m_preview; }
    /// Called when the item moved (links follow).
    std::function<void()> onMoved;

protected:
    QVariant itemChange(GraphicsItemChange change, const QVariant& value) override;

private:
    graph::NodeId m_node;
    QString m_title;
    std::vector<QString> m_inputLabels, m_outputLabels;
    std::vector<PortItem*> m_inputs, m_outputs; ///< indexed like the type's ports
    qreal m_width = 160, m_height = 60;
    qreal m_inputColumn = 70, m_outputColumn = 70; ///< the label columns' widths
    bool m_hasPreview = false;
    bool m_texture = false; ///< samples a file: without one its thumbnail says "no image"
    bool m_hasFile = false;
    QImage m_preview;
};

/// One link, a cubic curve from an output port to an input port. Selectable (Delete removes it).
class ConnectionItem : public QGraphicsPathItem {
public:
    enum { Type = UserType + 0x6a3 };
    ConnectionItem(const graph::Connection& c, PortItem* from, PortItem* to);
    int type() const override { return Type; }
    const graph::Connection& connection() const { return m_connection; }
    /// Follows the ports after a node moved.
    void updatePath();
    /// A curve from @p a to @p b (also the rubber band of a drag).
    static QPainterPath curve(QPointF a, QPointF b);

private:
    graph::Connection m_connection;
    PortItem* m_from;
    PortItem* m_to;
};

} // namespace velvet::ui
