// The node editor in the real main window, driven by key and mouse events: nodes come from the
// palette (Tab, a filter, Enter), links from drags between ports, and every edit is checked in
// the model, on the undo stack and, for a link into base colour, in the viewport's pixels.
#include "core/graph/graph.h"
#include "ui/document_controller.h"
#include "ui/graph/graph_model.h"
#include "ui/graph/graph_panel.h"
#include "ui/graph/graph_scene.h"
#include "ui/graph/graph_view.h"
#include "ui/graph/node_item.h"
#include "ui/graph/node_palette.h"
#include "ui/main_window.h"
#include "ui/viewport_widget.h"

#include <QApplication>
#include <QDockWidget>
#include <QLineEdit>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QStatusBar>
#include <QSurfaceFormat>
#include <QUndoStack>
#include <QtTest>
#include <cmath>

using namespace velvet;
using namespace velvet::ui;

namespace {

constexpr int kFrameTimeoutMs = 120000; // llvmpipe: the first frame compiles every shader

/// Mean colour of a 5x5 block around the centre, in 0..255 units.
QVector<double> centrePixel(const QImage& image) {
    QVector<double> sum(3, 0.0);
    const int cx = image.width() / 2, cy = image.height() / 2;
    for (int y = cy - 2; y <= cy + 2; ++y)
        for (int x = cx - 2; x <= cx + 2; ++x) {
            const QColor c = image.pixelColor(x, y);
            sum[0] += c.red();
            sum[1] += c.green();
            sum[2] += c.blue();
        }
    for (double& s : sum)
        s /= 25.0;
    return sum;
}

double maxDifference(const QVector<double>& a, const QVector<double>& b) {
    double d = 0.0;
    for (int i = 0; i < 3; ++i)
        d = std::max(d, std::abs(a[i] - b[i]));
    return d;
}

} // namespace

class TestUiGraph : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void buildConnectUndoDelete();

private:
    QImage viewportImage() { return m_window->viewport()->grabFramebuffer(); }
    /// Viewport coordinates of scene point @p p.
    QPoint at(QPointF p) const { return m_view->mapFromScene(p); }
    /// Adds a node through the palette: Tab, type @p filter, Enter. Returns its id.
    graph::NodeId addFromPalette(const QString& filter);
    /// A left-button drag on the view's viewport from @p a to @p b.
    void drag(QPoint a, QPoint b);

    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
    GraphPanel* m_panel = nullptr;
    GraphView* m_view = nullptr;
};

void TestUiGraph::initTestCase() {
    m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
    m_doc = m_window->controller();
    ViewportWidget* viewport = m_window->viewport();
    QSignalSpy frames(viewport, &ViewportWidget::frameCompleted);
    m_window->resize(900, 700);
    m_window->show();
    QVERIFY(QTest::qWaitForWindowExposed(m_window.get()));
    QTRY_VERIFY_WITH_TIMEOUT(!frames.isEmpty(), kFrameTimeoutMs);
    m_panel = m_window->findChild<GraphPanel*>();
    QVERIFY(m_panel);
    m_view = m_panel->view();
    // The node editor gets a window of its own, large enough for the material output node.
    auto* dock = m_window->findChild<QDockWidget*>(QStringLiteral("graphDock"));
    QVERIFY(dock);
    dock->setFloating(true);
    dock->resize(1000, 700);
    dock->show();
    QVERIFY(QTest::qWaitForWindowExposed(dock));
    dock->activateWindow();
    QApplication::setActiveWindow(dock);
    m_view->setFocus();
    QTRY_VERIFY(m_view->hasFocus());
}

void TestUiGraph::cleanupTestCase() {
    m_window.reset();
}

graph::NodeId TestUiGraph::addFromPalette(const QString& filter) {
    const graph::NodeId next = m_panel->model()->graph().nextId();
    m_view->setFocus();
    QTest::keyClick(m_view, Qt::Key_Tab);
    NodePalette* palette = m_view->palette();
    if (!palette->isVisible())
        return graph::kInvalidNodeId;
    QTest::keyClicks(palette->filter(), filter);
    QTest::keyClick(palette->filter(), Qt::Key_Return);
    return m_panel->model()->graph().node(next) ? next : graph::kInvalidNodeId;
}

void TestUiGraph::drag(QPoint a, QPoint b) {
    QWidget* vp = m_view->viewport();
    QTest::mousePress(vp, Qt::LeftButton, {}, a);
    for (int i = 1; i <= 4; ++i)
        QTest::mouseMove(vp, a + (b - a) * i / 4);
    QTest::mouseRelease(vp, Qt::LeftButton, {}, b);
}

void TestUiGraph::buildConnectUndoDelete() {
    GraphModel* model = m_panel->model();
    GraphScene* scene = m_panel->scene();
    QUndoStack* stack = m_doc->undoStack();
    ViewportWidget* viewport = m_window->viewport();

    // A dark base colour, so a grey constant fed into it changes the viewport.
    m_doc->editParam(ParamId::BaseColor, glm::vec3(0.02f));
    {
        QSignalSpy frames(viewport, &ViewportWidget::frameCompleted);
        QTRY_VERIFY_WITH_TIMEOUT(!frames.isEmpty(), kFrameTimeoutMs);
    }
    const QVector<double> pixelBefore = centrePixel(viewportImage());

    // Material output from the palette, then dragged 300 px right by its title: one command.
    const graph::NodeId out = addFromPalette(QStringLiteral("material output"));
    QVERIFY(out != graph::kInvalidNodeId);
    QVERIFY(model->graph().node(out)->type->isOutput);
    const glm::vec2 outStart = model->graph().node(out)->position;
    const int beforeDrag = stack->count();
    NodeItem* outItem = scene->nodeItem(out);
    QVERIFY(outItem);
    const QPoint title = at(outItem->scenePos() + QPointF(80, 10));
    drag(title, title + QPoint(300, 0));
    QCOMPARE(stack->count(), beforeDrag + 1);
    const glm::vec2 outMoved = model->graph().node(out)->position;
    QVERIFY2(std::abs(outMoved.x - outStart.x - 300.0f) < 2.0f &&
                 std::abs(outMoved.y - outStart.y) < 2.0f,
             qPrintable(QStringLiteral("moved to %1, %2").arg(outMoved.x).arg(outMoved.y)));

    // A constant colour, then a drag from its output to the output's baseColor input.
    const graph::NodeId colour = addFromPalette(QStringLiteral("colour"));
    QVERIFY(colour != graph::kInvalidNodeId);
    QCOMPARE(std::string(model->graph().node(colour)->type->id), std::string("constant.color"));
    const graph::NodeType* outType = model->graph().node(out)->type;
    const auto baseColor = graph::PortIndex(outType->inputIndex("baseColor"));
    const auto normal = graph::PortIndex(outType->inputIndex("normal"));
    PortItem* from = scene->nodeItem(colour)->outputPort(0);
    PortItem* toBase = scene->nodeItem(out)->inputPort(baseColor);
    PortItem* toNormal = scene->nodeItem(out)->inputPort(normal);
    QVERIFY(from && toBase && toNormal);
    const int beforeConnect = stack->count();
    QSignalSpy frames(viewport, &ViewportWidget::frameCompleted);
    drag(at(from->anchor()), at(toBase->anchor()));
    const graph::Connection link{colour, 0, out, baseColor};
    QCOMPARE(model->graph().connections().size(), size_t(1));
    QVERIFY(*model->graph().connections().begin() == link);
    QCOMPARE(stack->count(), beforeConnect + 1);
    QVERIFY(m_doc->material().graph);
    QCOMPARE(m_doc->material().graph->connections().size(), size_t(1));
    QTRY_VERIFY_WITH_TIMEOUT(!frames.isEmpty(), kFrameTimeoutMs);
    QTRY_VERIFY_WITH_TIMEOUT(maxDifference(pixelBefore, centrePixel(viewportImage())) > 10.0,
                             kFrameTimeoutMs);

    // Colour into a normal input is refused by the model: nothing changes, the reason is shown.
    const graph::Graph beforeRefused = model->graph();
    QSignalSpy refused(model, &GraphModel::editRefused);
    drag(at(from->anchor()), at(toNormal->anchor()));
    QCOMPARE(refused.count(), 1);
    QVERIFY(model->graph() == beforeRefused);
    QCOMPARE(stack->count(), beforeConnect + 1);
    QVERIFY(!m_window->statusBar()->currentMessage().isEmpty());

    // Undo removes the link, undo again removes the node; redo both.
    stack->undo();
    QVERIFY(model->graph().connections().empty());
    QVERIFY(model->graph().node(colour));
    stack->undo();
    QVERIFY(!model->graph().node(colour));
    QVERIFY(!scene->nodeItem(colour));
    stack->redo();
    stack->redo();
    QVERIFY(model->graph().node(colour));
    QCOMPARE(model->graph().connections().size(), size_t(1));
    QVERIFY(scene->connectionItem(link));

    // Delete the constant (selected, Delete key): node and link go; undo restores both.
    const graph::Graph beforeDelete = model->graph();
    scene->clearSelection();
    scene->nodeItem(colour)->setSelected(true);
    m_view->setFocus();
    QTest::keyClick(m_view, Qt::Key_Delete);
    QVERIFY(!model->graph().node(colour));
    QVERIFY(model->graph().connections().empty());
    stack->undo();
    QVERIFY(model->graph() == beforeDelete);
    QVERIFY(scene->nodeItem(colour) && scene->connectionItem(link));

    // Duplicate (Ctrl+D) adds a copy with a new id, not linked to the output (one input, one
    // link); undo removes it.
    scene->clearSelection();
    scene->nodeItem(colour)->setSelected(true);
    const size_t nodes = model->graph().nodes().size();
    QTest::keyClick(m_view, Qt::Key_D, Qt::ControlModifier);
    QCOMPARE(model->graph().nodes().size(), nodes + 1);
    stack->undo();
    QCOMPARE(model->graph().nodes().size(), nodes);
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetTest"));
    TestUiGraph test;
    return QTest::qExec(&test, argc, argv);
}
#include "test_ui_graph.moc"
