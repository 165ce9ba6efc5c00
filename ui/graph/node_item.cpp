#include "ui/graph/node_item.h"

#include <QFont>
#include <QFontMetricsF>
#include <QGraphicsScene>
#include <QPainter>
#include <QStyleOptionGraphicsItem>
#include <algorithm>
#include <cmath>

namespace velvet::ui {
namespace {

constexpr qreal kTitleHeight = 22;
constexpr qreal kRowHeight = 18;
constexpr int kThumbnailSide = 64;

QString qs(std::string_view s) {
    return QString::fromUtf8(s.data(), qsizetype(s.size()));
}

QColor portColor(graph::PortType t) {
    switch (t) {
    case graph::PortType::Float:
        return QColor(160, 160, 160);
    case graph::PortType::Vec2:
        return QColor(90, 160, 230);
    case graph::PortType::Color:
        return QColor(230, 200, 60);
    case graph::PortType::Vec4:
        return QColor(220, 120, 60);
    case graph::PortType::Normal:
        return QColor(150, 110, 230);
    default:
        return Qt::white;
    }
}

/// Node categories whose first output is a texture-like value worth a thumbnail.
bool previewedCategory(std::string_view category) {
    return category == "Texture" || category == "Noise" || category == "Math" ||
           category == "Channels";
}

} // namespace

PortItem::PortItem(graph::NodeId node, graph::PortIndex index, bool output, graph::PortType type,
                   QGraphicsItem* parent)
    : QGraphicsItem(parent), m_node(node), m_index(index), m_output(output), m_portType(type) {
    setAcceptHoverEvents(true);
    setToolTip(qs(graph::portTypeName(type)));
}

QRectF PortItem::boundingRect() const {
    return QRectF(-kRadius - 2, -kRadius - 2, 2 * kRadius + 4, 2 * kRadius + 4);
}

void PortItem::paint(QPainter* painter, const QStyleOptionGraphicsItem*, QWidget*) {
    painter->setRenderHint(QPainter::Antialiasing);
    painter->setPen(QPen(Qt::black, 1));
    painter->setBrush(portColor(m_portType));
    painter->drawEllipse(QPointF(0, 0), kRadius, kRadius);
}

NodeItem::NodeItem(const graph::Node& node) : m_node(node.id) {
    setFlags(ItemIsMovable | ItemIsSelectable | ItemSendsGeometryChanges);
    const graph::NodeType& t = *node.type;
    m_title = qs(t.label);
    setToolTip(qs(t.tooltip));
    m_texture = t.samplesTexture;
    m_hasPreview = previewedCategory(t.category) && !t.outputs.empty();
    // Wide enough for the longest input label beside the longest output label and the title
    // ("Specular weight", "Normal strength" were cut at half of a fixed 160 px).
    const QFontMetricsF metrics{QFont()};
    qreal inputWidth = 0, outputWidth = 0;
    for (const graph::InputSpec& in : t.inputs)
        if (in.connectable)
            inputWidth = std::max(inputWidth, metrics.horizontalAdvance(qs(in.label)));
    for (const graph::OutputSpec& out : t.outputs)
        outputWidth = std::max(outputWidth, metrics.horizontalAdvance(qs(out.label)));
    m_inputColumn = std::ceil(inputWidth) + 2;
    m_outputColumn = std::ceil(outputWidth) + 2;
    m_width = std::max<qreal>({160, 10 + m_inputColumn + 16 + m_outputColumn + 10,
                               std::ceil(metrics.horizontalAdvance(m_title)) + 20});
    size_t rows = 0;
    m_inputs.resize(t.inputs.size(), nullptr);
    for (size_t i = 0; i < t.inputs.size(); ++i) {
        if (!t.inputs[i].connectable)
            continue;
        const qreal y = kTitleHeight + kRowHeight * (qreal(rows) + 0.5);
        auto* p = new PortItem(m_node, graph::PortIndex(i), false, t.inputs[i].type, this);
        p->setPos(0, y);
        m_inputs[i] = p;
        m_inputLabels.push_back(qs(t.inputs[i].label));
        ++rows;
    }
    for (size_t i = 0; i < t.outputs.size(); ++i) {
        const qreal y = kTitleHeight + kRowHeight * (qreal(i) + 0.5);
        auto* p = new PortItem(m_node, graph::PortIndex(i), true, t.outputs[i].type, this);
        p->setPos(m_width, y);
        m_outputs.push_back(p);
        m_outputLabels.push_back(qs(t.outputs[i].label));
    }
    const size_t portRows = std::max(rows, t.outputs.size());
    m_height =
        kTitleHeight + kRowHeight * qreal(portRows) + 6 + (m_hasPreview ? kThumbnailSide + 6 : 0);
    setPos(node.position.x, node.position.y);
    refresh(node);
}

QRectF NodeItem::boundingRect() const {
    return QRectF(-PortItem::kRadius, 0, m_width + 2 * PortItem::kRadius, m_height)
        .adjusted(-2, -2, 2, 2);
}

void NodeItem::paint(QPainter* painter, const QStyleOptionGraphicsItem* option, QWidget*) {
    painter->setRenderHint(QPainter::Antialiasing);
    const QRectF box(0, 0, m_width, m_height);
    const bool selected = option->state & QStyle::State_Selected;
    painter->setPen(QPen(selected ? QColor(255, 170, 40) : QColor(20, 20, 20), selected ? 2 : 1));
    painter->setBrush(QColor(58, 58, 62));
    painter->drawRoundedRect(box, 6, 6);
    painter->setBrush(QColor(80, 80, 110));
    painter->setPen(Qt::NoPen);
    painter->drawRoundedRect(QRectF(1, 1, m_width - 2, kTitleHeight - 2), 5, 5);
    painter->setPen(Qt::white);
    painter->drawText(QRectF(8, 0, m_width - 16, kTitleHeight), Qt::AlignVCenter, m_title);
    painter->setPen(QColor(220, 220, 220));
    for (size_t i = 0; i < m_inputLabels.size(); ++i)
        painter->drawText(inputLabelRect(i), Qt::AlignVCenter | Qt::AlignLeft, m_inputLabels[i]);
    for (size_t i = 0; i < m_outputLabels.size(); ++i)
        painter->drawText(outputLabelRect(i), Qt::AlignVCenter | Qt::AlignRight, m_outputLabels[i]);
    if (m_hasPreview) {
        const QRectF r((m_width - kThumbnailSide) / 2, m_height - kThumbnailSide - 6,
                       kThumbnailSide, kThumbnailSide);
        if (m_texture && !m_hasFile) {
            painter->setPen(QColor(120, 120, 120));
            painter->drawRect(r);
            painter->drawText(r, Qt::AlignCenter, QObject::tr("no image"));
        } else if (m_preview.isNull()) {
            painter->setPen(QColor(120, 120, 120));
            painter->drawRect(r);
        } else {
            painter->drawImage(r, m_preview);
        }
    }
}

QRectF NodeItem::inputLabelRect(size_t i) const {
    return QRectF(10, kTitleHeight + kRowHeight * qreal(i), m_inputColumn, kRowHeight);
}

QRectF NodeItem::outputLabelRect(size_t i) const {
    return QRectF(m_width - 10 - m_outputColumn, kTitleHeight + kRowHeight * qreal(i),
                  m_outputColumn, kRowHeight);
}

PortItem* NodeItem::inputPort(graph::PortIndex index) const {
    return index < m_inputs.size() ? m_inputs[index] : nullptr;
}

PortItem* NodeItem::outputPort(graph::PortIndex index) const {
    return index < m_outputs.size() ? m_outputs[index] : nullptr;
}

void NodeItem::refresh(const graph::Node& node) {
    if (!m_texture)
        return;
    const int file = node.type->settingIndex("file");
    const std::string path = file >= 0 ? node.settings[size_t(file)] : std::string();
    m_hasFile = !path.empty();
    setToolTip(m_hasFile ? QString::fromStdString(path) : qs(node.type->tooltip));
    update();
}

void NodeItem::setPreview(const Image& image) {
    m_preview = QImage();
    if (!image.empty()) {
        // The values are already display-encoded bytes / 255 (render/graph_preview.h); row 0 of
        // the image is the top row of the thumbnail.
        m_preview = QImage(image.width, image.height, QImage::Format_RGB32);
        const auto byte = [](float v) { return int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255)); };
        for (int y = 0; y < image.height; ++y) {
            auto* line = reinterpret_cast<QRgb*>(m_preview.scanLine(y));
            for (int x = 0; x < image.width; ++x) {
                const glm::vec4 c = image.rgba(x, y);
                line[x] = qRgb(byte(c.r), byte(c.g), byte(c.b));
            }
        }
    }
    update();
}

QVariant NodeItem::itemChange(GraphicsItemChange change, const QVariant& value) {
    if (change == ItemPositionHasChanged && onMoved)
        onMoved();
    return QGraphicsItem::itemChange(change, value);
}

ConnectionItem::ConnectionItem(const graph::Connection& c, PortItem* from, PortItem* to)
    : m_connection(c), m_from(from), m_to(to) {
    setFlag(ItemIsSelectable);
    setZValue(-1);
    setPen(QPen(QColor(200, 200, 200), 2));
    updatePath();
}

void ConnectionItem::updatePath() {
    setPath(curve(m_from->anchor(), m_to->anchor()));
    setPen(QPen(isSelected() ? QColor(255, 170, 40) : QColor(200, 200, 200), 2));
}

QPainterPath ConnectionItem::curve(QPointF a, QPointF b) {
    QPainterPath p(a);
    const qreal dx = std::max<qreal>(40.0, std::abs(b.x() - a.x()) * 0.5);
    p.cubicTo(a + QPointF(dx, 0), b - QPointF(dx, 0), b);
    return p;
}

} // namespace velvet::ui
