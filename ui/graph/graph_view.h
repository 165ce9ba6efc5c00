#pragma once
/// @file graph_view.h
/// The node editor's view: zoom on the wheel, pan with the middle button, F or Home frames all,
/// Tab or right click opens the node palette, drag from an output port to an input port connects,
/// Delete removes the selection, Ctrl+C / Ctrl+V / Ctrl+D copy, paste and duplicate. Every gesture
/// becomes one command on the undo stack (ui/commands/graph_commands.h); a node drag is one
/// MoveNodesCommand pushed on release.

#include <QGraphicsView>
#include <memory>

class QGraphicsPathItem;

namespace velvet::ui {

class GraphScene;
class NodePalette;
class PortItem;

class GraphView : public QGraphicsView {
    Q_OBJECT
public:
    explicit GraphView(GraphScene* scene, QWidget* parent = nullptr);
    ~GraphView() override;

    GraphScene* graphScene() const { return m_scene; }
    NodePalette* palette() const { return m_palette; }
    /// Fits every node into the view.
    void frameAll();
    /// frameAll() now if the view has its size, and again at each resize until the artist
    /// zooms, pans, clicks or types in the view: a material opened or picked shows its whole
    /// graph, also while the dock is still being laid out or is resized right after.
    void frameAllWhenSized();
    /// Opens the node palette; a chosen type is added at scene point @p scenePos.
    void openPalette(QPointF scenePos);
    void copySelection();
    void paste();
    void duplicateSelection();
    void deleteSelection();

protected:
    bool event(QEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void contextMenuEvent(QContextMenuEvent* event) override;
    void resizeEvent(QResizeEvent* event) override;
    /// An empty graph says how to start one (and that the parameters apply until then).
    void drawForeground(QPainter* painter, const QRectF& rect) override;

private:
    void pasteText(const std::string& text, const QString& commandText);
    void pushMoves();

    GraphScene* m_scene;
    NodePalette* m_palette;
    QPointF m_paletteScenePos;
    // Link drag: the port it started from and the rubber band curve.
    PortItem* m_dragPort = nullptr;
    QGraphicsPathItem* m_rubberBand = nullptr;
    // Middle-button pan.
    bool m_panning = false;
    QPoint m_panLast;
    int m_dragCounter = 0;
    bool m_keepFramed = false; ///< frameAllWhenSized() until the artist moves the view
};

} // namespace velvet::ui
