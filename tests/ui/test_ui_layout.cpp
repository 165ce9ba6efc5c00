// Issue 17, items 1 and 2, driven through the real MainWindow under xvfb-run (a 1920x1200 screen):
// - a graph node (Tab -> Image texture) or a post effect (Bloom) shows its inputs at the top of
//   Properties, fully: no blank screen above them, the Image node's File "…" button inside the
//   panel;
// - at 1280x800 and 1920x1080 no text is clipped in Properties (the material page and a node
//   page), the Scene panel or the toolbars: labels, buttons, value boxes and combo boxes are wide
//   enough for their text, and nothing reaches past the right edge of its scrolling panel; the
//   graph's node labels fit their nodes (every node type);
// - the View menu names every dock and toolbar once; the graph dock starts at a usable size and
//   the separator between the Log and the graph moves; the node menu opens inside the window.
#include "core/graph/graph.h"
#include "core/graph/node_catalogue.h"
#include "ui/document_controller.h"
#include "ui/graph/graph_panel.h"
#include "ui/graph/graph_view.h"
#include "ui/graph/node_item.h"
#include "ui/graph/node_palette.h"
#include "ui/main_window.h"
#include "ui/models/graph_model.h"
#include "ui/post_chain/post_chain_panel.h"
#include "ui/properties/property_panel.h"
#include "ui/viewport_widget.h"
#include "ui_test_window.h"

#include <QAbstractButton>
#include <QAbstractSpinBox>
#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDockWidget>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMenu>
#include <QMenuBar>
#include <QPushButton>
#include <QRegularExpression>
#include <QScrollArea>
#include <QScrollBar>
#include <QStandardPaths>
#include <QStyleOptionComboBox>
#include <QSurfaceFormat>
#include <QTest>
#include <QToolBar>
#include <QToolButton>
#include <QWindow>
#include <algorithm>

using namespace velvet;
using namespace velvet::ui;

namespace {

QString withoutMnemonic(QString text) {
    text.remove(QRegularExpression(QStringLiteral("&(?!&)")));
    return text;
}

/// What a widget under @p root shows clipped, one line each ("param:x/spin: '1.000 nit' needs
/// 70 px, has 52"). Hidden widgets are skipped; scroll areas are checked whole (scrolled
/// content counts, cut-off content does not hide behind the scroll bar).
QStringList clippedText(QWidget* root) {
    QStringList out;
    const auto name = [](const QWidget* w) {
        return w->objectName().isEmpty() ? QString::fromLatin1(w->metaObject()->className())
                                         : w->objectName();
    };
    const auto report = [&](const QWidget* w, const QString& text, int need, int have) {
        if (need > have + 1)
            out << QStringLiteral("%1: '%2' needs %3 px, has %4")
                       .arg(name(w), text)
                       .arg(need)
                       .arg(have);
    };
    for (QWidget* w : root->findChildren<QWidget*>()) {
        if (!w->isVisibleTo(root->window()) || w->width() <= 0)
            continue;
        const QFontMetrics fm = w->fontMetrics();
        if (auto* label = qobject_cast<QLabel*>(w)) {
            if (label->wordWrap() || label->text().isEmpty() || Qt::mightBeRichText(label->text()))
                continue;
            report(w, label->text(), fm.horizontalAdvance(label->text()),
                   label->contentsRect().width());
        } else if (auto* spin = qobject_cast<QAbstractSpinBox*>(w)) {
            const QLineEdit* edit = spin->findChild<QLineEdit*>();
            if (edit)
                report(w, edit->text(), fm.horizontalAdvance(edit->text()) + 4, edit->width());
        } else if (auto* combo = qobject_cast<QComboBox*>(w)) {
            if (combo->isEditable() || combo->currentText().isEmpty())
                continue;
            QStyleOptionComboBox option;
            option.initFrom(combo);
            const QRect field = combo->style()->subControlRect(QStyle::CC_ComboBox, &option,
                                                               QStyle::SC_ComboBoxEditField, combo);
            const int icon =
                combo->itemIcon(combo->currentIndex()).isNull() ? 0 : combo->iconSize().width() + 4;
            report(w, combo->currentText(), fm.horizontalAdvance(combo->currentText()) + icon,
                   field.width());
        } else if (auto* button = qobject_cast<QAbstractButton*>(w)) {
            const QString text = withoutMnemonic(button->text());
            if (text.isEmpty())
                continue;
            if (auto* tool = qobject_cast<QToolButton*>(w);
                tool && tool->toolButtonStyle() == Qt::ToolButtonIconOnly && !tool->icon().isNull())
                continue;
            const int icon = button->icon().isNull() ? 0 : button->iconSize().width() + 4;
            int extra = 6;
            if (qobject_cast<QCheckBox*>(w))
                extra = 22; // the indicator
            if (auto* tool = qobject_cast<QToolButton*>(w);
                tool && tool->popupMode() == QToolButton::MenuButtonPopup)
                extra += 14; // the arrow
            report(w, text, fm.horizontalAdvance(text) + icon + extra, button->width());
        }
    }
    // Nothing may reach past the right edge of a scrolling panel without a horizontal bar.
    for (QScrollArea* area : root->findChildren<QScrollArea*>()) {
        if (!area->isVisibleTo(root->window()) || !area->widget() ||
            area->horizontalScrollBarPolicy() != Qt::ScrollBarAlwaysOff)
            continue;
        QWidget* viewport = area->viewport();
        for (QWidget* w : area->widget()->findChildren<QWidget*>()) {
            if (!w->isVisibleTo(area->widget()) || !w->findChildren<QWidget*>().isEmpty())
                continue;
            const int right = w->mapTo(viewport, QPoint(w->width(), 0)).x();
            if (right > viewport->width() + 1)
                out << QStringLiteral("%1: right edge at %2, past the panel's %3")
                           .arg(name(w))
                           .arg(right)
                           .arg(viewport->width());
        }
    }
    return out;
}

} // namespace

class TestUiLayout : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();

    void nodeAndEffectInputsShowAtTheTop();
    void nothingClipped_data();
    void nothingClipped();
    void nodeLabelsFitTheirNodes();
    void viewMenuNamesEachOnce();
    void graphDockIsUsableAndItsSeparatorMoves();
    void nodeMenuOpensInsideTheWindow();

private:
    template <class T>
    T* find(const QString& name) const {
        return m_window->findChild<T*>(name);
    }
    QDockWidget* dock(const char* name) const { return find<QDockWidget>(QLatin1String(name)); }
    QScrollArea* propertiesArea() const {
        return qobject_cast<QScrollArea*>(dock("propertiesDock")->widget());
    }
    /// Adds a node through the graph view's palette (Tab, a filter, Enter); its id.
    graph::NodeId addNode(const QString& filter);
    void resizeWindow(QSize size);

    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
    GraphPanel* m_graph = nullptr;
};

void TestUiLayout::initTestCase() {
    m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
    m_doc = m_window->controller();
    const QString up = test::showWithFirstFrame(m_window.get(), QSize(1280, 800));
    QVERIFY2(up.isEmpty(), qPrintable(up));
    m_graph = m_window->findChild<GraphPanel*>();
    QVERIFY(m_graph);
}

void TestUiLayout::cleanupTestCase() {
    m_doc->newDocument();
    QVERIFY(m_window->close());
    m_window.reset();
}

void TestUiLayout::resizeWindow(QSize size) {
    m_window->resize(size);
    QTRY_COMPARE(m_window->size(), size);
    QCoreApplication::processEvents();
}

graph::NodeId TestUiLayout::addNode(const QString& filter) {
    GraphView* view = m_graph->view();
    const graph::NodeId next = m_graph->model()->graph().nextId();
    view->setFocus();
    QTest::keyClick(view, Qt::Key_Tab);
    NodePalette* palette = view->palette();
    if (!palette->isVisible())
        return graph::kInvalidNodeId;
    QTest::keyClicks(palette->filter(), filter);
    QTest::keyClick(palette->filter(), Qt::Key_Return);
    return m_graph->model()->graph().node(next) ? next : graph::kInvalidNodeId;
}

void TestUiLayout::nodeAndEffectInputsShowAtTheTop() {
    m_doc->newDocument();
    PropertyPanel* properties = m_window->propertyPanel();
    QScrollArea* area = propertiesArea();
    QVERIFY(area);
    // The artist had scrolled the material page down before picking a node.
    area->verticalScrollBar()->setValue(area->verticalScrollBar()->maximum() / 2);

    const graph::NodeId image = addNode(QStringLiteral("Image texture"));
    QVERIFY(image != graph::kInvalidNodeId);
    QCOMPARE(properties->subject(), PropertyPanel::Subject::GraphNode);
    QTRY_VERIFY(area->isVisible());
    QCoreApplication::processEvents();
    QWidget* viewport = area->viewport();
    const auto top = [viewport](QWidget* w) { return w->mapTo(viewport, QPoint(0, 0)).y(); };
    const auto right = [viewport](QWidget* w) {
        return w->mapTo(viewport, QPoint(w->width(), 0)).x();
    };
    auto* file = properties->findChild<QLineEdit*>(QStringLiteral("nodeSetting:file"));
    auto* browse = properties->findChild<QToolButton*>(QStringLiteral("nodeSetting:file/browse"));
    QVERIFY(file && browse);
    // The inputs start near the top: the title and the node's description above them only.
    QWidget* box = properties->findChild<QWidget*>(QStringLiteral("subjectParameters"));
    QVERIFY(box);
    QVERIFY2(
        top(box) >= 0 && top(box) < viewport->height() / 3,
        qPrintable(
            QStringLiteral("inputs start at %1 of %2 px").arg(top(box)).arg(viewport->height())));
    QVERIFY2(top(browse) + browse->height() <= viewport->height(), "File row below the panel");
    QVERIFY2(right(browse) <= viewport->width(),
             qPrintable(QStringLiteral("the File button ends at %1, the panel at %2")
                            .arg(right(browse))
                            .arg(viewport->width())));
    QVERIFY(browse->width() >= browse->sizeHint().width());
    QVERIFY(file->width() >= 80);
    QCOMPARE(area->verticalScrollBar()->value(), 0);

    // A post effect: its parameters at the top too.
    auto* add = m_window->postChainPanel()->addMenu()->findChild<QAction*>(
        QStringLiteral("addEffect:bloom"));
    QVERIFY(add);
    add->trigger();
    QTRY_COMPARE(properties->subject(), PropertyPanel::Subject::Effect);
    QCoreApplication::processEvents();
    box = nullptr;
    for (QWidget* w : properties->findChildren<QWidget*>(QStringLiteral("subjectParameters")))
        if (w->isVisible())
            box = w; // the node's page goes later (deleteLater)
    QVERIFY(box);
    QVERIFY2(top(box) >= 0 && top(box) < viewport->height() / 3,
             qPrintable(QStringLiteral("Bloom's parameters start at %1 of %2 px")
                            .arg(top(box))
                            .arg(viewport->height())));
    properties->showMaterial();
}

void TestUiLayout::nothingClipped_data() {
    QTest::addColumn<QSize>("size");
    QTest::newRow("1280x800") << QSize(1280, 800);
    QTest::newRow("1920x1080") << QSize(1920, 1080);
}

void TestUiLayout::nothingClipped() {
    QFETCH(QSize, size);
    m_doc->newDocument();
    resizeWindow(size);
    PropertyPanel* properties = m_window->propertyPanel();
    properties->showMaterial();
    const auto check = [](QWidget* root, const char* what) {
        QCoreApplication::processEvents();
        const QStringList clipped = clippedText(root);
        QVERIFY2(clipped.isEmpty(), qPrintable(QStringLiteral("%1: %2").arg(
                                        QLatin1String(what), clipped.join(QStringLiteral("\n")))));
    };
    // Properties, material page.
    dock("propertiesDock")->raise();
    if (qEnvironmentVariableIsSet("VELVET_LAYOUT_DEBUG")) {
        for (QWidget* w : properties->findChildren<QWidget*>())
            if (w->minimumSizeHint().width() > 300 || qobject_cast<QLabel*>(w))
                qDebug() << w->metaObject()->className() << w->objectName()
                         << w->minimumSizeHint().width() << w->width()
                         << (qobject_cast<QLabel*>(w) ? qobject_cast<QLabel*>(w)->text()
                                                      : QString());
    }
    check(dock("propertiesDock"), "Properties (material)");
    if (QTest::currentTestFailed())
        return;
    // Properties, an image node's page.
    QVERIFY(addNode(QStringLiteral("Image texture")) != graph::kInvalidNodeId);
    check(dock("propertiesDock"), "Properties (Image texture node)");
    if (QTest::currentTestFailed())
        return;
    properties->showMaterial();
    // The Scene panel, with a light selected so its editor shows.
    dock("sceneDock")->raise();
    QTRY_VERIFY(dock("sceneDock")->widget()->isVisible());
    if (auto* lights = find<QListWidget>(QStringLiteral("lightList")); lights && lights->count())
        lights->setCurrentRow(0);
    check(dock("sceneDock"), "Scene");
    if (QTest::currentTestFailed())
        return;
    // The other docks (each raised in its tab group), and the toolbars.
    for (const char* name :
         {"logDock", "postChainDock", "libraryDock", "atlasDock", "historyDock", "graphDock"}) {
        dock(name)->raise();
        QTRY_VERIFY(dock(name)->widget()->isVisible());
        check(dock(name), name);
        if (QTest::currentTestFailed())
            return;
    }
    dock("logDock")->raise();
    dock("propertiesDock")->raise();
    for (QToolBar* bar : m_window->findChildren<QToolBar*>())
        check(bar, "toolbar");
    resizeWindow(QSize(1280, 800));
}

void TestUiLayout::nodeLabelsFitTheirNodes() {
    // Every node type, as the graph view draws it: each port label inside its column, the
    // input and output columns apart ("Specular weig", "Normal streng" before).
    const QFontMetricsF metrics{QFont()};
    for (const graph::NodeType& type : graph::nodeTypes()) {
        graph::Node node;
        node.id = 1;
        node.type = &type;
        node.inputValues.resize(type.inputs.size());
        node.settings.resize(type.settings.size());
        NodeItem item(node);
        const QString typeName = QString::fromUtf8(type.label.data(), qsizetype(type.label.size()));
        for (size_t i = 0; i < item.inputLabels().size(); ++i) {
            const QRectF r = item.inputLabelRect(i);
            QVERIFY2(metrics.horizontalAdvance(item.inputLabels()[i]) <= r.width() + 0.5,
                     qPrintable(typeName + ": " + item.inputLabels()[i]));
            for (size_t o = 0; o < item.outputLabels().size(); ++o)
                if (o == i)
                    QVERIFY2(r.right() <= item.outputLabelRect(o).left(),
                             qPrintable(typeName + ": labels overlap"));
        }
        for (size_t o = 0; o < item.outputLabels().size(); ++o)
            QVERIFY2(metrics.horizontalAdvance(item.outputLabels()[o]) <=
                         item.outputLabelRect(o).width() + 0.5,
                     qPrintable(typeName + ": " + item.outputLabels()[o]));
    }
}

void TestUiLayout::viewMenuNamesEachOnce() {
    QMenu* view = nullptr;
    for (QAction* menu : m_window->menuBar()->actions())
        if (withoutMnemonic(menu->text()) == QStringLiteral("View"))
            view = menu->menu();
    QVERIFY(view);
    QStringList names;
    for (QAction* a : view->actions())
        if (!a->isSeparator())
            names << withoutMnemonic(a->text());
    for (const QString& n : names)
        QVERIFY2(names.count(n) == 1, qPrintable(n + QStringLiteral(" is listed twice: ") +
                                                 names.join(QStringLiteral(", "))));
    QVERIFY(names.contains(QStringLiteral("Scene")));
}

void TestUiLayout::graphDockIsUsableAndItsSeparatorMoves() {
    resizeWindow(QSize(1280, 800));
    QDockWidget* graphDock = dock("graphDock");
    QDockWidget* log = dock("logDock");
    QVERIFY(graphDock && log);
    if (qEnvironmentVariableIsSet("VELVET_LAYOUT_DEBUG"))
        for (const char* n : {"logDock", "postChainDock", "graphDock"})
            qDebug() << n << dock(n)->minimumSizeHint() << dock(n)->widget()->minimumSizeHint()
                     << dock(n)->size();
    QVERIFY2(
        graphDock->width() >= 450 && graphDock->height() >= 220 &&
            graphDock->width() > log->width(),
        qPrintable(
            QStringLiteral("graph dock %1x%2").arg(graphDock->width()).arg(graphDock->height())));
    QVERIFY(m_window->viewport()->height() >= 300);
    // The separator between the Log (left) and the graph: grab its middle, drag it 100 px right,
    // then 20 px left of where it started (the graph grows).
    const auto dragSeparator = [this, log, graphDock](int dx) {
        const QRect logRect(log->mapTo(m_window.get(), QPoint(0, 0)), log->size());
        const QRect graphRect(graphDock->mapTo(m_window.get(), QPoint(0, 0)), graphDock->size());
        QVERIFY2(logRect.right() < graphRect.left(), "the Log should sit left of the graph");
        const QPoint grip((logRect.right() + graphRect.left()) / 2 + 1, graphRect.center().y());
        const int before = log->width();
        // Through the window system, as a real pointer: the window finds what is under it.
        QWindow* handle = m_window->windowHandle();
        QTest::mouseMove(handle, grip);
        QTest::mousePress(handle, Qt::LeftButton, Qt::NoModifier, grip);
        for (int i = 1; i <= 10; ++i)
            QTest::mouseMove(handle, grip + QPoint(dx * i / 10, 0));
        QTest::mouseRelease(handle, Qt::LeftButton, Qt::NoModifier, grip + QPoint(dx, 0));
        QTRY_VERIFY2(std::abs(log->width() - (before + dx)) <= 6,
                     qPrintable(QStringLiteral("Log %1 px wide, was %2, dragged by %3")
                                    .arg(log->width())
                                    .arg(before)
                                    .arg(dx)));
    };
    dragSeparator(100);
    if (QTest::currentTestFailed())
        return;
    dragSeparator(-120);
}

void TestUiLayout::nodeMenuOpensInsideTheWindow() {
    resizeWindow(QSize(1280, 800));
    GraphView* view = m_graph->view();
    NodePalette* palette = view->palette();
    const QRect window = m_window->geometry();
    // Right click near the graph view's bottom right corner (the bottom of the window).
    const QPoint corner(view->viewport()->width() - 5, view->viewport()->height() - 5);
    QContextMenuEvent click(QContextMenuEvent::Mouse, corner,
                            view->viewport()->mapToGlobal(corner));
    QApplication::sendEvent(view->viewport(), &click);
    QTRY_VERIFY(palette->isVisible());
    const QRect shown = palette->frameGeometry();
    QVERIFY2(window.contains(shown),
             qPrintable(QStringLiteral("palette %1,%2 %3x%4 outside the window %5,%6 %7x%8")
                            .arg(shown.x())
                            .arg(shown.y())
                            .arg(shown.width())
                            .arg(shown.height())
                            .arg(window.x())
                            .arg(window.y())
                            .arg(window.width())
                            .arg(window.height())));
    QTest::keyClick(palette->filter(), Qt::Key_Escape);
    palette->hide();
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetLayoutTest"));
    TestUiLayout test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_ui_layout.moc"
