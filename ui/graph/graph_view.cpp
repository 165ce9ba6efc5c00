#include "ui/graph/graph_view.h"

#include "ui/commands/graph_commands.h"
#include "ui/graph/graph_scene.h"
#include "ui/graph/node_item.h"
#include "ui/graph/node_palette.h"
#include "ui/models/graph_model.h"

#include <QApplication>
#include <QClipboard>
#include <QContextMenuEvent>
#include <QGraphicsPathItem>
#include <QKeyEvent>
#include <QPainter>
#include <QScrollBar>
#include <QUndoStack>
#include <QWheelEvent>
#include <cmath>

namespace velvet::ui {
namespace {

/// Offset of pasted and duplicated nodes, in scene units.
constexpr float kPasteOffset = 30.0f;

bool isGraphKey(const QKeyEvent* e) {
    const int key = e->key();
    const Qt::KeyboardModifiers mods = e->modifiers() & ~Qt::KeypadModifier;
    if (mods == Qt::NoModifier)
        return key == Qt::Key_F || key == Qt::Key_Home || key == Qt::Key_Delete ||
               key == Qt::Key_Backspace || key == Qt::Key_Tab;
    if (mods == Qt::ControlModifier)
        return key == Qt::Key_C || key == Qt::Key_V || key == Qt::Key_D;
    return false;
}

} // namespace

GraphView::GraphView(GraphScene* scene, QWidget* parent)
    : QGraphicsView(scene, parent), m_scene(scene), m_palette(new NodePalette(this)) {
    setObjectName(QStringLiteral("graphView"));
    setRenderHint(QPainter::Antialiasing);
    setDragMode(QGraphicsView::RubberBandDrag);
    setTransformationAnchor(QGraphicsView::AnchorUnderMouse);
    setViewportUpdateMode(QGraphicsView::FullViewportUpdate);
    setSceneRect(-5000, -5000, 10000, 10000);
    setFocusPolicy(Qt::StrongFocus);
    connect(m_palette, &NodePalette::chosen, this, [this](const QString& typeId) {
        auto* cmd = new AddNodeCommand(m_scene->model(), typeId.toStdString(),
                                       glm::vec2(m_paletteScenePos.x(), m_paletteScenePos.y()));
        m_scene->model()->undoStack()->push(cmd);
        if (NodeItem* item = m_scene->nodeItem(cmd->node())) {
            m_scene->clearSelection();
            item->setSelected(true);
        }
        setFocus();
    });
}

GraphView::~GraphView() = default;

void GraphView::frameAll() {
    const QRectF bounds = m_scene->itemsBoundingRect();
    if (bounds.isEmpty())
        return;
    fitInView(bounds.adjusted(-40, -40, 40, 40), Qt::KeepAspectRatio);
    // Never zoom in past 1:1 for a small graph.
    if (transform().m11() > 1.0)
        setTransform(QTransform());
    centerOn(bounds.center());
}

void GraphView::frameAllWhenSized() {
    m_keepFramed = true;
    // A view smaller than a node would zoom out to nothing: wait for the dock's layout.
    if (viewport()->width() >= 100 && viewport()->height() >= 60)
        frameAll();
}

void GraphView::resizeEvent(QResizeEvent* event) {
    QGraphicsView::resizeEvent(event);
    if (m_keepFramed) // the dock's layout settling, or a resize before the artist moved the view
        frameAllWhenSized();
}

void GraphView::openPalette(QPointF scenePos) {
    m_paletteScenePos = scenePos;
    m_palette->popup(mapToGlobal(mapFromScene(scenePos)));
}

void GraphView::copySelection() {
    const std::vector<graph::NodeId> ids = m_scene->selectedNodes();
    if (ids.empty())
        return;
    QApplication::clipboard()->setText(QString::fromStdString(m_scene->model()->snapshot(ids)));
}

void GraphView::paste() {
    pasteText(QApplication::clipboard()->text().toStdString(), tr("Paste nodes"));
}

void GraphView::duplicateSelection() {
    const std::vector<graph::NodeId> ids = m_scene->selectedNodes();
    if (!ids.empty())
        pasteText(m_scene->model()->snapshot(ids), tr("Duplicate nodes"));
}

void GraphView::pasteText(const std::string& text, const QString& commandText) {
    auto* cmd = new PasteNodesCommand(m_scene->model(), text, glm::vec2(kPasteOffset, kPasteOffset),
                                      commandText);
    m_scene->model()->undoStack()->push(cmd);
    m_scene->clearSelection();
    for (graph::NodeId id : cmd->nodes())
        if (NodeItem* item = m_scene->nodeItem(id))
            item->setSelected(true);
}

void GraphView::deleteSelection() {
    const std::vector<graph::NodeId> nodes = m_scene->selectedNodes();
    std::vector<graph::Connection> links;
    for (const graph::Connection& c : m_scene->selectedConnections())
        if (std::find(nodes.begin(), nodes.end(), c.outNode) == nodes.end() &&
            std::find(nodes.begin(), nodes.end(), c.inNode) == nodes.end())
            links.push_back(c); // links of deleted nodes go with them
    if (nodes.empty() && links.empty())
        return;
    GraphModel* model = m_scene->model();
    if (links.empty()) {
        model->undoStack()->push(new RemoveNodesCommand(model, nodes));
        return;
    }
    auto* macro = new QUndoCommand(tr("Delete"));
    for (const graph::Connection& c : links)
        new DisconnectCommand(model, c, macro);
    if (!nodes.empty())
        new RemoveNodesCommand(model, nodes, macro);
    model->undoStack()->push(macro);
}

bool GraphView::event(QEvent* event) {
    // The window's own shortcuts (F frames the mesh, Tab moves focus) give way while the graph
    // has focus.
    if (event->type() == QEvent::ShortcutOverride && isGraphKey(static_cast<QKeyEvent*>(event))) {
        event->accept();
        return true;
    }
    if (event->type() == QEvent::KeyPress && static_cast<QKeyEvent*>(event)->key() == Qt::Key_Tab) {
        keyPressEvent(static_cast<QKeyEvent*>(event));
        return true;
    }
    return QGraphicsView::event(event);
}

void GraphView::keyPressEvent(QKeyEvent* event) {
    m_keepFramed = false;
    if (!isGraphKey(event)) {
        QGraphicsView::keyPressEvent(event);
        return;
    }
    const bool ctrl = event->modifiers() & Qt::ControlModifier;
    switch (event->key()) {
    case Qt::Key_F:
    case Qt::Key_Home:
        frameAll();
        break;
    case Qt::Key_Delete:
    case Qt::Key_Backspace:
        deleteSelection();
        break;
    case Qt::Key_Tab: {
        const QPoint local = mapFromGlobal(QCursor::pos());
        openPalette(mapToScene(rect().contains(local) ? local : rect().center()));
        break;
    }
    case Qt::Key_C:
        if (ctrl)
            copySelection();
        break;
    case Qt::Key_V:
        if (ctrl)
            paste();
        break;
    case Qt::Key_D:
        if (ctrl)
            duplicateSelection();
        break;
    default:
        break;
    }
    event->accept();
}

void GraphView::wheelEvent(QWheelEvent* event) {
    m_keepFramed = false;
    const double factor = std::pow(1.0015, event->angleDelta().y());
    const double zoom = transform().m11() * factor;
    if (zoom > 0.1 && zoom < 4.0)
        scale(factor, factor);
    event->accept();
}

void GraphView::mousePressEvent(QMouseEvent* event) {
    m_keepFramed = false;
    if (event->button() == Qt::MiddleButton) {
        m_panning = true;
        m_panLast = event->position().toPoint();
        setCursor(Qt::ClosedHandCursor);
        event->accept();
        return;
    }
    if (event->button() == Qt::LeftButton) {
        PortItem* port = m_scene->portAt(mapToScene(event->position().toPoint()));
        if (port && port->isOutput()) {
            m_dragPort = port;
            m_rubberBand = m_scene->addPath(ConnectionItem::curve(port->anchor(), port->anchor()),
                                            QPen(QColor(255, 200, 80), 2, Qt::DashLine));
            event->accept();
            return;
        }
    }
    QGraphicsView::mousePressEvent(event);
}

void GraphView::mouseMoveEvent(QMouseEvent* event) {
    if (m_panning) {
        const QPoint p = event->position().toPoint();
        const QPoint d = p - m_panLast;
        m_panLast = p;
        horizontalScrollBar()->setValue(horizontalScrollBar()->value() - d.x());
        verticalScrollBar()->setValue(verticalScrollBar()->value() - d.y());
        event->accept();
        return;
    }
    if (m_dragPort) {
        m_rubberBand->setPath(
            ConnectionItem::curve(m_dragPort->anchor(), mapToScene(event->position().toPoint())));
        event->accept();
        return;
    }
    QGraphicsView::mouseMoveEvent(event);
}

void GraphView::mouseReleaseEvent(QMouseEvent* event) {
    if (m_panning && event->button() == Qt::MiddleButton) {
        m_panning = false;
        unsetCursor();
        event->accept();
        return;
    }
    if (m_dragPort && event->button() == Qt::LeftButton) {
        PortItem* from = m_dragPort;
        m_dragPort = nullptr;
        delete m_rubberBand;
        m_rubberBand = nullptr;
        PortItem* to = m_scene->portAt(mapToScene(event->position().toPoint()));
        if (to && !to->isOutput())
            pushConnect(m_scene->model(),
                        graph::Connection{from->node(), from->index(), to->node(), to->index()});
        else if (to)
            m_scene->model()->refuse(tr("Connection refused: drag from an output to an input"));
        event->accept();
        return;
    }
    QGraphicsView::mouseReleaseEvent(event);
    if (event->button() == Qt::LeftButton)
        pushMoves();
}

void GraphView::pushMoves() {
    // Items move freely during the drag; the model (and the undo stack) learns the result once.
    std::map<graph::NodeId, MoveNodesCommand::Move> moves;
    const graph::Graph& g = m_scene->model()->graph();
    for (const auto& [id, node] : g.nodes()) {
        NodeItem* item = m_scene->nodeItem(id);
        if (!item)
            continue;
        const glm::vec2 at(float(item->pos().x()), float(item->pos().y()));
        if (at != node.position)
            moves[id] = {node.position, at};
    }
    if (!moves.empty())
        m_scene->model()->undoStack()->push(
            new MoveNodesCommand(m_scene->model(), std::move(moves), ++m_dragCounter));
}

void GraphView::contextMenuEvent(QContextMenuEvent* event) {
    openPalette(mapToScene(event->pos()));
    event->accept();
}

void GraphView::drawForeground(QPainter* painter, const QRectF& rect) {
    QGraphicsView::drawForeground(painter, rect);
    if (!scene() || !scene()->items().isEmpty())
        return;
    painter->save();
    painter->resetTransform(); // viewport coordinates: the hint stays put while panning
    painter->setPen(QColor(170, 170, 178)); // readable on the canvas's dark background
    painter->drawText(viewport()->rect().adjusted(16, 16, -16, -16),
                      Qt::AlignCenter | Qt::TextWordWrap,
                      tr("No material graph: the Properties values apply.\nTab or right-click "
                         "to add a node; connect it to the Material output to drive a "
                         "parameter."));
    painter->restore();
}

} // namespace velvet::ui
