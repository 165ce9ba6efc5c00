// The node editor in the real main window, driven by key and mouse events: nodes come from the
// palette (Tab, a filter, Enter), links from drags between ports, and every edit is checked in
// the model, on the undo stack and, for a link into base colour, in the viewport's pixels.
// Selecting a node shows its inputs in the Properties dock: a slider drag there is one command,
// reaches the viewport as a uniform (the renderer compiles nothing) and undo restores it; vector
// inputs and settings (an image node's UV scale and file) are edited there too. A right click on
// the canvas opens the palette and adds at the click; Ctrl+C / Ctrl+V paste linked copies in one
// command. The view's own gestures (framing, zoom, pan) are test_ui_graph_view's.
#include "core/graph/graph.h"
#include "graph_editor_window.h"
#include "ui/commands/graph_commands.h"
#include "ui/document_controller.h"
#include "ui/graph/graph_panel.h"
#include "ui/graph/graph_scene.h"
#include "ui/graph/graph_view.h"
#include "ui/graph/node_item.h"
#include "ui/graph/node_palette.h"
#include "ui/main_window.h"
#include "ui/models/graph_model.h"
#include "ui/properties/param_editor.h"
#include "ui/properties/property_panel.h"
#include "ui/viewport_widget.h"
#include "ui_test_util.h"

#include <QApplication>
#include <QClipboard>
#include <QDoubleSpinBox>
#include <QLineEdit>
#include <QSignalSpy>
#include <QSlider>
#include <QStandardPaths>
#include <QStatusBar>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QSurfaceFormat>
#include <QUndoStack>
#include <QtTest>
#include <cmath>

using namespace velvet;
using namespace velvet::ui;
using velvet::test::centrePixel;
using velvet::test::handleCentre;
using velvet::test::kFrameTimeoutMs;
using velvet::test::maxDifference;

namespace {} // namespace

class TestUiGraph : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void buildConnectUndoDelete();
    void nodeInputsInPropertiesAreUniformEdits();
    void nodeThumbnailsAreLive();
    void rightClickPaletteAddsAtClick();
    void copyPasteKeepsValuesAndLinks();

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
    // The node editor gets a window of its own, large enough for the material output node.
    const QString up = test::openWindowWithGraphEditor(m_window, m_doc, m_panel, m_view);
    QVERIFY2(up.isEmpty(), qPrintable(up));
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

void TestUiGraph::nodeInputsInPropertiesAreUniformEdits() {
    GraphModel* model = m_panel->model();
    GraphScene* scene = m_panel->scene();
    QUndoStack* stack = m_doc->undoStack();
    ViewportWidget* viewport = m_window->viewport();
    PropertyPanel* properties = m_window->propertyPanel();

    // A constant value into the output's metallic input (structural: one recompile).
    const graph::NodeId out = model->graph().outputNode();
    QVERIFY(out != graph::kInvalidNodeId);
    const auto metallic = graph::PortIndex(model->graph().node(out)->type->inputIndex("metallic"));
    auto* add = new AddNodeCommand(model, "constant.float", glm::vec2(-260.0f, 40.0f));
    stack->push(add);
    const graph::NodeId value = add->node();
    QVERIFY(value != graph::kInvalidNodeId);
    QVERIFY(pushConnect(model, {value, 0, out, metallic}));
    QSignalSpy frames(viewport, &ViewportWidget::frameCompleted);
    QTRY_VERIFY_WITH_TIMEOUT(frames.count() >= 2 && !viewport->renderer()->graphPending(),
                             kFrameTimeoutMs);
    QVERIFY2(viewport->renderer()->graphError().empty(),
             viewport->renderer()->graphError().c_str());
    // The new structure's specialised programs are built once the edits pause (the viewport
    // draws again by itself: render/lighting_features.h), and the lighting's once the
    // environment bake completes (the generic program draws while it bakes); only then count.
    QTRY_VERIFY_WITH_TIMEOUT(viewport->environmentProgress() >= 1.0 &&
                                 !viewport->renderer()->specialisationPending(),
                             kFrameTimeoutMs);
    const QVector<double> pixelBefore = centrePixel(viewportImage());
    const int compiles = viewport->renderer()->shaderCompileCount();

    // Click the node's title: Properties shows its inputs.
    NodeItem* item = scene->nodeItem(value);
    QVERIFY(item);
    scene->clearSelection();
    const int beforeClick = stack->count();
    QTest::mouseClick(m_view->viewport(), Qt::LeftButton, {},
                      at(item->scenePos() + QPointF(40, 10)));
    QCOMPARE(stack->count(), beforeClick); // a click moves nothing
    QCOMPARE(properties->subject(), PropertyPanel::Subject::GraphNode);
    QCOMPARE(properties->graphNode(), value);
    ParamEditor* editor = properties->subjectEditor(QStringLiteral("value"));
    QVERIFY(editor);
    auto* slider = editor->findChild<QSlider*>(QStringLiteral("nodeInput:value/slider"));
    QVERIFY(slider);
    m_window->activateWindow();
    QTRY_VERIFY(slider->isVisible());
    QCOMPARE(slider->value(), 500); // 0.5 on the soft range [0, 1]

    // A drag of the handle: one command, however many moves, a new value in the graph.
    const float valueBefore = model->graph().node(value)->inputValues[0].x;
    QPoint pos = handleCentre(slider);
    QTest::mousePress(slider, Qt::LeftButton, Qt::NoModifier, pos);
    for (int i = 0; i < 8; ++i) {
        pos.rx() += slider->width() / 20;
        QTest::mouseMove(slider, pos);
    }
    QTest::mouseRelease(slider, Qt::LeftButton, Qt::NoModifier, pos);
    QCOMPARE(stack->count(), beforeClick + 1);
    const float valueAfter = model->graph().node(value)->inputValues[0].x;
    QVERIFY2(valueAfter > valueBefore + 0.2f, qPrintable(QString::number(valueAfter)));
    QCOMPARE(m_doc->material().graph->node(value)->inputValues[0].x, valueAfter);

    // The viewport changes through the uniform block: nothing is compiled.
    frames.clear();
    QTRY_VERIFY_WITH_TIMEOUT(!frames.isEmpty(), kFrameTimeoutMs);
    // Metallic 0.5 -> 0.9 at a pixel near white after the tone map: 3.6/255 with the direct
    // light's multiple-scattering energy (15 before it); an unchanged frame differs by 0.
    QTRY_VERIFY_WITH_TIMEOUT(maxDifference(pixelBefore, centrePixel(viewportImage())) > 2.5,
                             kFrameTimeoutMs);
    QCOMPARE(viewport->renderer()->shaderCompileCount(), compiles);

    // Undo: the value, the slider and the pixel come back, still without a compile.
    stack->undo();
    QCOMPARE(model->graph().node(value)->inputValues[0].x, valueBefore);
    QCOMPARE(slider->value(), 500);
    QTRY_VERIFY_WITH_TIMEOUT(maxDifference(pixelBefore, centrePixel(viewportImage())) < 2.0,
                             kFrameTimeoutMs);
    QCOMPARE(viewport->renderer()->shaderCompileCount(), compiles);

    // A linked input is shown but not editable (the link feeds it).
    const graph::NodeId colour =
        model->graph()
            .connectionTo(out,
                          graph::PortIndex(model->graph().node(out)->type->inputIndex("baseColor")))
            ->outNode;
    auto* mix = new AddNodeCommand(model, "math.mix", glm::vec2(-520.0f, 200.0f));
    stack->push(mix);
    QVERIFY(pushConnect(model, {colour, 0, mix->node(), 0}));
    scene->clearSelection();
    scene->nodeItem(mix->node())->setSelected(true);
    QCOMPARE(properties->graphNode(), mix->node());
    QVERIFY(!properties->subjectEditor(QStringLiteral("a"))->isEnabled());
    QVERIFY(properties->subjectEditor(QStringLiteral("factor"))->isEnabled());

    // An image node: the UV scale is a vector (one spin box per component), the file a setting.
    auto* image = new AddNodeCommand(model, "texture.image", glm::vec2(-520.0f, -200.0f));
    stack->push(image);
    scene->clearSelection();
    scene->nodeItem(image->node())->setSelected(true);
    QCOMPARE(properties->graphNode(), image->node());
    auto* scaleX = properties->findChild<QDoubleSpinBox*>(QStringLiteral("nodeInput:scale/x"));
    QVERIFY(scaleX);
    QVERIFY(properties->findChild<QDoubleSpinBox*>(QStringLiteral("nodeInput:scale/y")));
    const int beforeScale = stack->count();
    scaleX->setValue(3.0);
    QCOMPARE(stack->count(), beforeScale + 1);
    QCOMPARE(model->graph().node(image->node())->inputValues[1], glm::vec4(3.0f, 1.0f, 0.0f, 0.0f));
    auto* file = properties->findChild<QLineEdit*>(QStringLiteral("nodeSetting:file"));
    QVERIFY(file);
    file->setText(QStringLiteral("/nonexistent/weave.png"));
    emit file->editingFinished();
    QCOMPARE(stack->count(), beforeScale + 2);
    QCOMPARE(model->graph().node(image->node())->settings[0],
             std::string("/nonexistent/weave.png"));
    stack->undo();
    QVERIFY(model->graph().node(image->node())->settings[0].empty());
    QVERIFY(file->text().isEmpty());
    stack->undo();
    QCOMPARE(scaleX->value(), 1.0);

    // The material output shows the material's parameters; a deleted node gives way too.
    scene->clearSelection();
    scene->nodeItem(out)->setSelected(true);
    QCOMPARE(properties->subject(), PropertyPanel::Subject::Material);
    scene->clearSelection();
    scene->nodeItem(image->node())->setSelected(true);
    QCOMPARE(properties->subject(), PropertyPanel::Subject::GraphNode);
    m_view->setFocus();
    QTest::keyClick(m_view, Qt::Key_Delete);
    QVERIFY(!model->graph().node(image->node()));
    QCOMPARE(properties->subject(), PropertyPanel::Subject::Material);
}

// Node thumbnails are rendered by the GPU through the graph compiler: a new noise node gets a
// thumbnail that varies over the square (not a flat placeholder), and a value edit upstream
// (a constant into Invert) changes the downstream node's thumbnail to the known answer 1 - c,
// sRGB-encoded, in one debounced batch.
void TestUiGraph::nodeThumbnailsAreLive() {
    GraphModel* model = m_panel->model();
    GraphScene* scene = m_panel->scene();
    QUndoStack* stack = model->undoStack();
    const int batches = m_panel->previewBatchCount();
    const int start = stack->index();
    auto* noise = new AddNodeCommand(model, "noise.perlin", glm::vec2(-700.0f, -300.0f));
    stack->push(noise);
    NodeItem* noiseItem = scene->nodeItem(noise->node());
    QVERIFY(noiseItem && noiseItem->hasPreview());
    QTRY_VERIFY_WITH_TIMEOUT(!noiseItem->preview().isNull(), kFrameTimeoutMs);
    QCOMPARE(m_panel->previewBatchCount(), batches + 1);
    const QImage n = noiseItem->preview();
    QCOMPARE(n.size(), QSize(64, 64));
    int lo = 255, hi = 0;
    for (int y = 0; y < n.height(); ++y)
        for (int x = 0; x < n.width(); ++x) {
            const QColor c = n.pixelColor(x, y);
            QCOMPARE(c.red(), c.green()); // a float shows as grey
            lo = std::min(lo, c.red());
            hi = std::max(hi, c.red());
        }
    qInfo("noise thumbnail range %d..%d", lo, hi);
    QVERIFY2(hi - lo > 60, qPrintable(QStringLiteral("%1..%2").arg(lo).arg(hi)));

    // constant.color -> math.invert: Invert's thumbnail is 1 - c.
    auto* constant = new AddNodeCommand(model, "constant.color", glm::vec2(-700.0f, -100.0f));
    stack->push(constant);
    auto* invert = new AddNodeCommand(model, "math.invert", glm::vec2(-500.0f, -100.0f));
    stack->push(invert);
    QVERIFY(pushConnect(model, {constant->node(), 0, invert->node(), 0}));
    NodeItem* invertItem = scene->nodeItem(invert->node());
    QVERIFY(invertItem && invertItem->hasPreview());
    QVERIFY(!scene->nodeItem(constant->node())->hasPreview());
    const auto encode = [](float v) {
        const float e = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
        return e * 255.0f;
    };
    const auto showsInverseOf = [&](float c) {
        const QImage img = invertItem->preview();
        if (img.isNull())
            return false;
        const QColor p = img.pixelColor(32, 32);
        return std::abs(p.red() - encode(1.0f - c)) <= 1.0f &&
               std::abs(p.blue() - encode(1.0f - c)) <= 1.0f;
    };
    const float before = model->graph().node(constant->node())->inputValues[0].x; // default 0.8
    QTRY_VERIFY_WITH_TIMEOUT(showsInverseOf(before), kFrameTimeoutMs);
    const int settled = m_panel->previewBatchCount();
    const QImage old = invertItem->preview();
    // Three quick edits (a slider drag) settle into one batch.
    for (float v : {0.5f, 0.4f, 0.3f}) {
        const glm::vec4 current = model->graph().node(constant->node())->inputValues[0];
        stack->push(new SetNodeInputCommand(model, constant->node(), 0, current,
                                            glm::vec4(v, v, v, 0.0f), 0));
    }
    QTRY_VERIFY_WITH_TIMEOUT(showsInverseOf(0.3f), kFrameTimeoutMs);
    QVERIFY(invertItem->preview() != old);
    QCOMPARE(m_panel->previewBatchCount(), settled + 1);
    // The noise node's thumbnail came in the same batch and has not changed.
    QCOMPARE(noiseItem->preview(), n);
    stack->setIndex(start);
    QVERIFY(!model->graph().node(noise->node()));
}

// A right click on empty canvas opens the palette (through the window, so Qt itself turns the
// press into a context menu event); a filter and Enter add that node where the click was, as one
// undo command.
void TestUiGraph::rightClickPaletteAddsAtClick() {
    GraphModel* model = m_panel->model();
    QUndoStack* stack = m_doc->undoStack();
    NodePalette* palette = m_view->palette();
    QVERIFY(!palette->isVisible());
    m_view->setTransform(QTransform());
    m_view->centerOn(0.0, 0.0);
    // An empty spot: no item within 20 px of it.
    QPoint click(-1, -1);
    const QRect area = m_view->viewport()->rect().adjusted(30, 30, -30, -30);
    for (int y = area.top(); y < area.bottom() && click.x() < 0; y += 25)
        for (int x = area.left(); x < area.right() && click.x() < 0; x += 25)
            if (m_view->items(QRect(x - 20, y - 20, 40, 40)).isEmpty())
                click = QPoint(x, y);
    QVERIFY2(click.x() >= 0, "no empty canvas in the view");
    const QPointF scenePoint = m_view->mapToScene(click);

    QWidget* top = m_view->window();
    QVERIFY(top->windowHandle());
    // The previous test undid its edits: a push now drops their redo entries, so count on the
    // index.
    const int before = stack->index();
    const int countBefore = stack->count();
    const graph::NodeId next = model->graph().nextId();
    QTest::mouseClick(top->windowHandle(), Qt::RightButton, {},
                      m_view->viewport()->mapTo(top, click));
    QTRY_VERIFY(palette->isVisible());
    QCOMPARE(stack->count(), countBefore); // opening the palette edits nothing
    QVERIFY(palette->filter()->text().isEmpty());
    QTest::keyClicks(palette->filter(), QStringLiteral("perlin"));
    QTest::keyClick(palette->filter(), Qt::Key_Return);
    QVERIFY(!palette->isVisible());

    const graph::Node* node = model->graph().node(next);
    QVERIFY(node);
    QCOMPARE(std::string(node->type->id), std::string("noise.perlin"));
    QVERIFY2(std::abs(node->position.x - float(scenePoint.x())) < 0.5f &&
                 std::abs(node->position.y - float(scenePoint.y())) < 0.5f,
             qPrintable(QStringLiteral("added at %1, %2, clicked %3, %4")
                            .arg(node->position.x)
                            .arg(node->position.y)
                            .arg(scenePoint.x())
                            .arg(scenePoint.y())));
    QVERIFY(m_panel->scene()->nodeItem(next));
    QCOMPARE(stack->index(), before + 1);
    QCOMPARE(stack->count(), before + 1); // one command, on top
    QCOMPARE(stack->text(stack->index() - 1), QStringLiteral("Add Perlin noise node"));
    stack->undo();
    QVERIFY(!model->graph().node(next));
    QVERIFY(!m_panel->scene()->nodeItem(next));
}

// Ctrl+C, Ctrl+V on two linked nodes: two new ids, 30 units down and right, the same type and
// values, the link between them copied; one command, which undo takes back whole.
void TestUiGraph::copyPasteKeepsValuesAndLinks() {
    GraphModel* model = m_panel->model();
    GraphScene* scene = m_panel->scene();
    QUndoStack* stack = m_doc->undoStack();
    const int start = stack->index();
    auto* constant = new AddNodeCommand(model, "constant.color", glm::vec2(-900.0f, 300.0f));
    stack->push(constant);
    auto* invert = new AddNodeCommand(model, "math.invert", glm::vec2(-700.0f, 300.0f));
    stack->push(invert);
    const graph::NodeId c = constant->node(), inv = invert->node();
    const glm::vec4 value(0.25f, 0.5f, 0.75f, 0.0f);
    stack->push(
        new SetNodeInputCommand(model, c, 0, model->graph().node(c)->inputValues[0], value, 0));
    QVERIFY(pushConnect(model, {c, 0, inv, 0}));
    const graph::Graph before = model->graph();

    scene->clearSelection();
    scene->nodeItem(c)->setSelected(true);
    scene->nodeItem(inv)->setSelected(true);
    m_view->setFocus();
    QTest::keyClick(m_view, Qt::Key_C, Qt::ControlModifier);
    QVERIFY(model->graph() == before); // copying edits nothing
    QVERIFY(!QApplication::clipboard()->text().isEmpty());
    const int count = stack->count();
    QTest::keyClick(m_view, Qt::Key_V, Qt::ControlModifier);
    QCOMPARE(stack->count(), count + 1);
    QCOMPARE(stack->text(stack->index() - 1), QStringLiteral("Paste nodes"));
    QCOMPARE(model->graph().nodes().size(), before.nodes().size() + 2);
    QCOMPARE(model->graph().connections().size(), before.connections().size() + 1);

    // The selection is the pasted copies; match them to the originals by type.
    const std::vector<graph::NodeId> pasted = scene->selectedNodes();
    QCOMPARE(pasted.size(), size_t(2));
    graph::NodeId c2 = graph::kInvalidNodeId, inv2 = graph::kInvalidNodeId;
    for (graph::NodeId id : pasted) {
        QVERIFY(!before.node(id)); // a new id
        const std::string_view type = model->graph().node(id)->type->id;
        (type == "constant.color" ? c2 : inv2) = id;
    }
    QVERIFY(c2 != graph::kInvalidNodeId && inv2 != graph::kInvalidNodeId);
    for (auto [original, copy] : {std::pair{c, c2}, std::pair{inv, inv2}}) {
        const graph::Node* o = model->graph().node(original);
        const graph::Node* p = model->graph().node(copy);
        QCOMPARE(p->type, o->type);
        QCOMPARE(p->position, o->position + glm::vec2(30.0f));
        QVERIFY(p->inputValues == o->inputValues);
        QVERIFY(p->settings == o->settings);
        QCOMPARE(scene->nodeItem(copy)->pos(),
                 QPointF(o->position.x + 30.0f, o->position.y + 30.0f));
    }
    QCOMPARE(model->graph().node(c2)->inputValues[0], value);
    const graph::Connection link{c2, 0, inv2, 0};
    QVERIFY(model->graph().connections().count(link));
    QVERIFY(scene->connectionItem(link));
    QCOMPARE(m_doc->material().graph->nodes().size(), model->graph().nodes().size());

    stack->undo();
    QVERIFY(model->graph() == before);
    QVERIFY(!scene->nodeItem(c2) && !scene->nodeItem(inv2));
    stack->setIndex(start);
    QVERIFY(!model->graph().node(c) && !model->graph().node(inv));
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
