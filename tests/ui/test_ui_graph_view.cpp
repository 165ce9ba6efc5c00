// The node editor's view in the real main window: F and Home frame every node, a material
// opened or picked from outside the panel is framed whole, and wheel zoom and middle-button pan
// change only the view (never the graph or the undo stack).
#include "core/graph/graph.h"
#include "graph_editor_window.h"
#include "ui/commands/graph_commands.h"
#include "ui/document_controller.h"
#include "ui/graph/graph_panel.h"
#include "ui/graph/graph_scene.h"
#include "ui/graph/graph_view.h"
#include "ui/graph/node_item.h"
#include "ui/main_window.h"
#include "ui/models/graph_model.h"
#include "ui/viewport_widget.h"
#include "ui_test_util.h"

#include <QApplication>
#include <QStandardPaths>
#include <QSurfaceFormat>
#include <QUndoStack>
#include <QWheelEvent>
#include <QtTest>
#include <memory>

using namespace velvet;
using namespace velvet::ui;

class TestUiGraphView : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void frameAllShowsEveryNode();
    void anOpenedGraphIsFramed();
    void anOpenedGraphStaysFramedUntilTheViewIsMoved();
    void wheelZoomAndMiddlePanAreViewOnly();

private:
    /// The part of the scene the viewport shows now.
    QRectF visibleSceneRect() const {
        return m_view->mapToScene(m_view->viewport()->rect()).boundingRect();
    }
    /// Scene rects of every node item.
    std::vector<QRectF> nodeRects() const {
        std::vector<QRectF> rects;
        for (const auto& [id, node] : m_panel->model()->graph().nodes())
            if (NodeItem* item = m_panel->scene()->nodeItem(id))
                rects.push_back(item->sceneBoundingRect());
        return rects;
    }
    /// How many node items the viewport does not show whole.
    int nodesOutsideView() const {
        int n = 0;
        for (const QRectF& r : nodeRects())
            n += visibleSceneRect().contains(r) ? 0 : 1;
        return n;
    }
    /// @p base with a graph of three nodes spread far apart (3,500 x 2,500 scene units): larger
    /// than the view at 1:1.
    static Material withSpreadGraph(Material base) {
        graph::Graph g;
        g.addNode("output.material", glm::vec2(1600.0f, 0.0f));
        g.addNode("constant.color", glm::vec2(-1900.0f, 1200.0f));
        g.addNode("constant.float", glm::vec2(-1900.0f, -1300.0f));
        base.graph = SharedGraph(std::make_shared<graph::Graph>(g));
        return base;
    }

    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
    GraphPanel* m_panel = nullptr;
    GraphView* m_view = nullptr;
};

void TestUiGraphView::initTestCase() {
    const QString up = test::openWindowWithGraphEditor(m_window, m_doc, m_panel, m_view);
    QVERIFY2(up.isEmpty(), qPrintable(up));
}

void TestUiGraphView::cleanupTestCase() {
    m_window.reset();
}

// F and Home fit every node into the view, from a view scrolled far away (and zoomed in).
void TestUiGraphView::frameAllShowsEveryNode() {
    GraphModel* model = m_panel->model();
    QUndoStack* stack = m_doc->undoStack();
    // Two nodes far apart, so the graph is larger than the view at 1:1 whatever came before.
    const int start = stack->index();
    stack->push(new AddNodeCommand(model, "constant.float", glm::vec2(-1800.0f, 1100.0f)));
    stack->push(new AddNodeCommand(model, "constant.color", glm::vec2(1500.0f, -900.0f)));
    QVERIFY(model->graph().nodes().size() >= 2);
    const int count = stack->count();
    m_view->setFocus();
    for (Qt::Key key : {Qt::Key_F, Qt::Key_Home}) {
        m_view->setTransform(QTransform::fromScale(2.0, 2.0));
        m_view->centerOn(4500.0, -4500.0);
        QCOMPARE(nodesOutsideView(), int(nodeRects().size())); // none visible
        QTest::keyClick(m_view, key);
        QVERIFY2(nodesOutsideView() == 0,
                 qPrintable(
                     QStringLiteral("key %1: %2 nodes outside").arg(key).arg(nodesOutsideView())));
        QVERIFY(m_view->transform().m11() < 1.0); // zoomed out to fit
        QCOMPARE(stack->count(), count);          // view state, not an edit
    }
    stack->setIndex(start);
}

// A material replaced from outside the panel (a preset picked, a file opened) shows its whole
// graph, wherever the view was; an edit in the panel leaves the view where the artist put it.
void TestUiGraphView::anOpenedGraphIsFramed() {
    const Material before = m_doc->material();
    const Material spread = withSpreadGraph(before);
    m_view->setTransform(QTransform::fromScale(2.0, 2.0));
    m_view->centerOn(4500.0, -4500.0);
    m_doc->setMaterial(spread, "spread");
    QCOMPARE(int(nodeRects().size()), 3);
    QVERIFY2(nodesOutsideView() == 0,
             qPrintable(QStringLiteral("%1 nodes outside").arg(nodesOutsideView())));
    QVERIFY(m_view->transform().m11() < 1.0);
    // The panel's own edit: the view stays.
    const QTransform framed = m_view->transform();
    m_view->centerOn(4500.0, -4500.0);
    const QRectF away = visibleSceneRect();
    m_doc->undoStack()->push(
        new AddNodeCommand(m_panel->model(), "constant.float", glm::vec2(0.0f, 0.0f)));
    QCOMPARE(m_view->transform(), framed);
    QCOMPARE(visibleSceneRect(), away);
    m_doc->undoStack()->undo();
    m_doc->setMaterial(before, "");
}

// The dock may still be settling when a material opens, or the artist widens it at once: until
// the artist moves the view, each resize frames the whole graph again; after a wheel zoom a
// resize leaves the scale alone.
void TestUiGraphView::anOpenedGraphStaysFramedUntilTheViewIsMoved() {
    const Material before = m_doc->material();
    const Material spread = withSpreadGraph(before);
    const QSize docked = m_view->size();
    m_doc->setMaterial(spread, "spread");
    const double openedScale = m_view->transform().m11();
    // The view grows to twice its size: framed again, so the scale grows with it.
    m_view->resize(docked * 2);
    QCOMPARE(m_view->size(), docked * 2);
    QCOMPARE(nodesOutsideView(), 0);
    const double grownScale = m_view->transform().m11();
    QVERIFY2(grownScale > openedScale * 1.5,
             qPrintable(QStringLiteral("scale %1 -> %2").arg(openedScale).arg(grownScale)));
    // The artist zooms: the next resize keeps the zoom.
    QWidget* vp = m_view->viewport();
    const QPoint centre = vp->rect().center();
    QWheelEvent wheel(QPointF(centre), QPointF(vp->mapToGlobal(centre)), QPoint(), QPoint(0, 120),
                      Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(vp, &wheel);
    const double zoomed = m_view->transform().m11();
    QVERIFY(zoomed > grownScale);
    m_view->resize(docked);
    QCOMPARE(m_view->transform().m11(), zoomed);
    m_doc->setMaterial(before, "");
}

// The wheel scales the view about the cursor and back; a middle drag scrolls the view by the
// drag, in scene units at the current scale. Neither touches the graph or the undo stack.
void TestUiGraphView::wheelZoomAndMiddlePanAreViewOnly() {
    GraphModel* model = m_panel->model();
    QUndoStack* stack = m_doc->undoStack();
    const graph::Graph before = model->graph();
    const int count = stack->count();
    m_view->setTransform(QTransform());
    m_view->centerOn(0.0, 0.0);
    QWidget* vp = m_view->viewport();
    const QPoint centre = vp->rect().center();
    const auto wheel = [&](int delta) {
        QWheelEvent e(QPointF(centre), QPointF(vp->mapToGlobal(centre)), QPoint(), QPoint(0, delta),
                      Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
        QApplication::sendEvent(vp, &e);
    };
    wheel(120);
    const double zoomed = m_view->transform().m11();
    QVERIFY2(std::abs(zoomed - std::pow(1.0015, 120)) < 1e-6, qPrintable(QString::number(zoomed)));
    QCOMPARE(m_view->transform().m22(), zoomed);
    wheel(-120);
    QVERIFY2(std::abs(m_view->transform().m11() - 1.0) < 1e-9,
             qPrintable(QString::number(m_view->transform().m11())));
    QCOMPARE(stack->count(), count);

    // Pan at scale 0.8: 120 x 80 px of drag is 150 x 100 scene units.
    m_view->setTransform(QTransform::fromScale(0.8, 0.8));
    m_view->centerOn(0.0, 0.0);
    const QRectF start = visibleSceneRect();
    const QPoint a = centre, b = centre + QPoint(-120, -80);
    QTest::mousePress(vp, Qt::MiddleButton, {}, a);
    for (int i = 1; i <= 4; ++i)
        QTest::mouseMove(vp, a + (b - a) * i / 4);
    QTest::mouseRelease(vp, Qt::MiddleButton, {}, b);
    const QPointF moved = visibleSceneRect().topLeft() - start.topLeft();
    QVERIFY2(std::abs(moved.x() - 150.0) < 1.5 && std::abs(moved.y() - 100.0) < 1.5,
             qPrintable(QStringLiteral("moved %1, %2").arg(moved.x()).arg(moved.y())));
    QCOMPARE(visibleSceneRect().size(), start.size()); // a pan does not zoom
    QCOMPARE(stack->count(), count);
    QVERIFY(model->graph() == before); // no node moved with it
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetTest"));
    TestUiGraphView test;
    return QTest::qExec(&test, argc, argv);
}
#include "test_ui_graph_view.moc"
