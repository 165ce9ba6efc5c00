// The Post chain panel (issue 5) under xvfb-run: reordering effects by a drop on the list's
// viewport and by the keyboard alternative (Ctrl+Up / Ctrl+Down), undo of both; toggling an
// effect with its check box (Space) is undoable; a stage conflict is explained on its row; a
// parameter drag is one command; chain presets load (errors name file and JSON path). In the real
// main window, selecting an effect shows its parameters in the Properties dock; a slider drag
// there is one command that changes the chain and the viewport, and undo restores both; the
// window has the Post chain and Library docks. The Library panel's cases are test_ui_library's.
//
// Real drags: QDrag::exec runs a nested loop fed by the window system, which QTest's synthetic
// mouse events do not reach under xvfb, so the drop half of a drag is driven by sending
// QDragEnter/QDragMove/QDropEvent to the viewport (PostChainListView handles drops of its own
// rows whatever the drag's source), and the keyboard alternative is tested with key clicks.
#include "core/document_io.h"
#include "core/post_effects.h"
#include "core/resources.h"
#include "ui/document_controller.h"
#include "ui/library/library_panel.h"
#include "ui/main_window.h"
#include "ui/models/post_chain_model.h"
#include "ui/post_chain/post_chain_panel.h"
#include "ui/properties/param_editor.h"
#include "ui/properties/property_panel.h"
#include "ui/viewport_widget.h"
#include "ui_test_util.h"

#include <QApplication>
#include <QDir>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFile>
#include <QGroupBox>
#include <QLabel>
#include <QLineEdit>
#include <QListView>
#include <QMenu>
#include <QMimeData>
#include <QPushButton>
#include <QSignalSpy>
#include <QSlider>
#include <QSortFilterProxyModel>
#include <QStandardItemModel>
#include <QStandardPaths>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>

using namespace velvet;
using namespace velvet::ui;
using velvet::test::centrePixel;
using velvet::test::handleCentre;
using velvet::test::kFrameTimeoutMs;
using velvet::test::maxDifference;

namespace {

/// A left-button drag of @p slider's handle by @p dx pixels, in small steps (one gesture).
void dragHandle(QSlider* slider, int dx) {
    QPoint pos = handleCentre(slider);
    QTest::mousePress(slider, Qt::LeftButton, Qt::NoModifier, pos);
    for (int i = 0; i < 8; ++i) {
        pos.rx() += dx / 8;
        QTest::mouseMove(slider, pos);
    }
    QTest::mouseRelease(slider, Qt::LeftButton, Qt::NoModifier, pos);
}

PostChain chainOf(std::initializer_list<const char*> types) {
    PostChain chain;
    for (const char* type : types)
        chain.effects.push_back(makeEffect(type));
    return chain;
}

std::vector<std::string> typesOf(const PostChain& chain) {
    std::vector<std::string> types;
    for (const EffectInstance& e : chain.effects)
        types.push_back(e.type);
    return types;
}

void setChain(DocumentController& controller, const PostChain& chain) {
    Scene scene = controller.scene();
    scene.post = chain;
    controller.setDocument(std::move(scene), QString());
}

/// Sends drag enter, drag move and drop of row @p from onto viewport point @p pos.
bool dropRow(PostChainListView* list, int from, QPoint pos) {
    QMimeData* mime = list->model()->mimeData({list->model()->index(from, 0)});
    QDragEnterEvent enter(pos, Qt::MoveAction, mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(list->viewport(), &enter);
    QDragMoveEvent move(pos, Qt::MoveAction, mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(list->viewport(), &move);
    QDropEvent drop(QPointF(pos), Qt::MoveAction, mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(list->viewport(), &drop);
    const bool accepted = drop.isAccepted();
    delete mime;
    return accepted;
}

} // namespace

class TestUiPanels : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void dropReordersAndUndoRestores();
    void keyboardReorders();
    void toggleIsUndoable();
    void stageConflictExplainedOnRow();
    void addRemoveDuplicate();
    void parameterDragIsOneCommand();
    void effectParametersInPropertiesReachViewport();
    void chainPresetLoadsAndReportsErrors();
    void mainWindowHasDocks();

private:
    QTemporaryDir m_tmp;
};

void TestUiPanels::initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
    QVERIFY(m_tmp.isValid());
}

void TestUiPanels::dropReordersAndUndoRestores() {
    DocumentController controller;
    setChain(controller, chainOf({"gaussian_blur", "pixelate", "vignette"}));
    PostChainPanel panel(&controller);
    panel.resize(360, 480);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PostChainListView* list = panel.list();
    QCOMPARE(list->model()->rowCount(), 3);

    // Row 0 dropped on the lower half of row 1: lands after it.
    const QRect row1 = list->visualRect(list->model()->index(1, 0));
    QVERIFY(row1.isValid());
    const QPoint lowerHalf(row1.center().x(), row1.bottom() - 1);
    QCOMPARE(list->insertPositionAt(lowerHalf), 2);
    QVERIFY(dropRow(list, 0, lowerHalf));
    QCOMPARE(typesOf(controller.scene().post),
             (std::vector<std::string>{"pixelate", "gaussian_blur", "vignette"}));
    QCOMPARE(controller.undoStack()->count(), 1);
    QCOMPARE(panel.currentRow(), 1); // the moved effect stays selected

    // Row 2 dropped on the upper half of row 0: first.
    const QRect row0 = list->visualRect(list->model()->index(0, 0));
    QVERIFY(dropRow(list, 2, QPoint(row0.center().x(), row0.top() + 1)));
    QCOMPARE(typesOf(controller.scene().post),
             (std::vector<std::string>{"vignette", "pixelate", "gaussian_blur"}));

    controller.undoStack()->undo();
    controller.undoStack()->undo();
    QCOMPARE(typesOf(controller.scene().post),
             (std::vector<std::string>{"gaussian_blur", "pixelate", "vignette"}));
    QCOMPARE(list->model()->index(0, 0).data().toString(), QStringLiteral("Gaussian blur"));

    // A drop onto itself changes nothing and pushes nothing.
    const int before = controller.undoStack()->index();
    QVERIFY(dropRow(list, 1, list->visualRect(list->model()->index(1, 0)).center()));
    QCOMPARE(controller.undoStack()->index(), before);
}

void TestUiPanels::keyboardReorders() {
    DocumentController controller;
    setChain(controller, chainOf({"gaussian_blur", "pixelate", "vignette"}));
    PostChainPanel panel(&controller);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    panel.setCurrentRow(0);
    panel.list()->setFocus();
    QTest::keyClick(panel.list(), Qt::Key_Down, Qt::ControlModifier);
    QCOMPARE(typesOf(controller.scene().post),
             (std::vector<std::string>{"pixelate", "gaussian_blur", "vignette"}));
    QCOMPARE(panel.currentRow(), 1);
    QTest::keyClick(panel.list(), Qt::Key_Down, Qt::ControlModifier);
    QCOMPARE(typesOf(controller.scene().post),
             (std::vector<std::string>{"pixelate", "vignette", "gaussian_blur"}));
    QTest::keyClick(panel.list(), Qt::Key_Up, Qt::ControlModifier);
    QCOMPARE(typesOf(controller.scene().post),
             (std::vector<std::string>{"pixelate", "gaussian_blur", "vignette"}));
    QCOMPARE(controller.undoStack()->count(), 3);
    controller.undoStack()->undo();
    controller.undoStack()->undo();
    controller.undoStack()->undo();
    QCOMPARE(typesOf(controller.scene().post),
             (std::vector<std::string>{"gaussian_blur", "pixelate", "vignette"}));
}

void TestUiPanels::toggleIsUndoable() {
    DocumentController controller;
    setChain(controller, chainOf({"bloom", "tonemap", "vignette"}));
    PostChainPanel panel(&controller);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    panel.setCurrentRow(2);
    panel.list()->setFocus();
    QCOMPARE(panel.model()->index(2).data(Qt::CheckStateRole).toInt(), int(Qt::Checked));
    QTest::keyClick(panel.list(), Qt::Key_Space); // the check box of the current row
    QVERIFY(!controller.scene().post.effects[2].enabled);
    QCOMPARE(panel.model()->index(2).data(Qt::CheckStateRole).toInt(), int(Qt::Unchecked));
    QCOMPARE(controller.undoStack()->count(), 1);
    QVERIFY(controller.undoStack()->text(0).startsWith(QStringLiteral("Disable")));
    controller.undoStack()->undo();
    QVERIFY(controller.scene().post.effects[2].enabled);
    QCOMPARE(panel.model()->index(2).data(Qt::CheckStateRole).toInt(), int(Qt::Checked));
    controller.undoStack()->redo();
    QVERIFY(!controller.scene().post.effects[2].enabled);
}

void TestUiPanels::stageConflictExplainedOnRow() {
    DocumentController controller;
    setChain(controller, chainOf({"tonemap", "color_grading", "vignette"}));
    PostChainPanel panel(&controller);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PostChainModel* model = panel.model();
    const QModelIndex bad = model->index(1);
    const QString expected =
        QString::fromStdString(checkStageOrder(controller.scene().post).at(0).message);
    QCOMPARE(checkStageOrder(controller.scene().post).at(0).index, size_t(1));
    QCOMPARE(bad.data(PostChainModel::IssueRole).toString(), expected);
    QCOMPARE(bad.data(Qt::ToolTipRole).toString(), expected);
    QVERIFY(!bad.data(Qt::DecorationRole).value<QIcon>().isNull());
    QVERIFY(expected.contains(QStringLiteral("before")));
    QVERIFY(model->index(0).data(PostChainModel::IssueRole).toString().isEmpty());
    QVERIFY(model->index(0).data(Qt::DecorationRole).isNull());
    QVERIFY(panel.issueLabel()->isVisible());
    QVERIFY(panel.issueLabel()->text().contains(expected));

    // Fixing the order (a move, undoable) clears the explanation.
    panel.setCurrentRow(1);
    panel.moveCurrent(-1);
    QVERIFY(model->index(0).data(PostChainModel::IssueRole).toString().isEmpty());
    QVERIFY(model->index(1).data(PostChainModel::IssueRole).toString().isEmpty());
    QVERIFY(!panel.issueLabel()->isVisible());
    controller.undoStack()->undo();
    QCOMPARE(model->index(1).data(PostChainModel::IssueRole).toString(), expected);
}

void TestUiPanels::addRemoveDuplicate() {
    DocumentController controller;
    setChain(controller, chainOf({"bloom", "tonemap", "fxaa"}));
    PostChainPanel panel(&controller);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));

    // The Add menu is grouped by stage and adds where the stage belongs.
    QAction* grading =
        panel.addMenu()->findChild<QAction*>(QStringLiteral("addEffect:color_grading"));
    QVERIFY(grading);
    grading->trigger();
    QCOMPARE(typesOf(controller.scene().post),
             (std::vector<std::string>{"bloom", "color_grading", "tonemap", "fxaa"}));
    QVERIFY(checkStageOrder(controller.scene().post).empty());
    QCOMPARE(panel.currentRow(), 1);

    panel.duplicateCurrent();
    QCOMPARE(controller.scene().post.effects.size(), size_t(5));
    QCOMPARE(controller.scene().post.effects[2].type, std::string("color_grading"));
    QCOMPARE(panel.currentRow(), 2); // the copy is selected
    panel.removeCurrent();
    QCOMPARE(panel.currentRow(), 2); // the next effect
    panel.setCurrentRow(1);
    QTest::keyClick(panel.list(), Qt::Key_Delete);
    QCOMPARE(typesOf(controller.scene().post),
             (std::vector<std::string>{"bloom", "tonemap", "fxaa"}));
    QCOMPARE(controller.undoStack()->count(), 4);
    for (int i = 0; i < 4; ++i)
        controller.undoStack()->undo();
    QCOMPARE(typesOf(controller.scene().post),
             (std::vector<std::string>{"bloom", "tonemap", "fxaa"}));
    controller.undoStack()->redo();
    controller.undoStack()->redo();
    QCOMPARE(controller.scene().post.effects.size(), size_t(5));
}

void TestUiPanels::parameterDragIsOneCommand() {
    DocumentController controller;
    setChain(controller, chainOf({"vignette"}));
    PostChainPanel panel(&controller);
    PropertyPanel properties(&controller);
    connect(&panel, &PostChainPanel::effectSelected, &properties, &PropertyPanel::showEffect);
    properties.show();
    QVERIFY(QTest::qWaitForWindowExposed(&properties));
    panel.setCurrentRow(0);
    QCOMPARE(properties.subject(), PropertyPanel::Subject::Effect);
    QCOMPARE(properties.effectIndex(), 0);
    ParamEditor* editor = properties.subjectEditor(QStringLiteral("intensity"));
    QVERIFY2(editor, "the vignette's intensity editor, generated from its ParamMeta");
    auto* slider = editor->findChild<QSlider*>(QStringLiteral("effectParam:intensity/slider"));
    QVERIFY(slider);
    QCOMPARE(editor->toolTip(),
             QString::fromUtf8(findEffectParam(*findPostEffect("vignette"), "intensity")->tooltip));
    const float before = effectFloat(controller.scene().post.effects[0], "intensity");
    slider->setSliderDown(true); // sliderPressed: a new gesture
    for (int v : {100, 300, 500, 700})
        slider->setValue(v);
    slider->setSliderDown(false);
    QCOMPARE(controller.undoStack()->count(), 1);
    const float after = effectFloat(controller.scene().post.effects[0], "intensity");
    QCOMPARE(after, 0.7f);
    controller.undoStack()->undo();
    QCOMPARE(effectFloat(controller.scene().post.effects[0], "intensity"), before);
    QCOMPARE(slider->value(), int(std::lround(before * 1000))); // the editor follows the document

    // Reset: one command back to the metadata default.
    controller.undoStack()->redo();
    auto* reset = editor->findChild<QToolButton*>(QStringLiteral("effectParam:intensity/reset"));
    QVERIFY(reset);
    reset->click();
    QCOMPARE(controller.undoStack()->count(), 2);
    QCOMPARE(effectFloat(controller.scene().post.effects[0], "intensity"), 0.35f);
    QVERIFY(controller.undoStack()->undoText().startsWith(QStringLiteral("Reset")));

    // The effect removed: Properties falls back to the material.
    panel.removeCurrent();
    QCOMPARE(properties.subject(), PropertyPanel::Subject::Material);
}

void TestUiPanels::effectParametersInPropertiesReachViewport() {
    MainWindow window(/*restoreLayout=*/false);
    DocumentController* doc = window.controller();
    ViewportWidget* viewport = window.viewport();
    QSignalSpy frames(viewport, &ViewportWidget::frameCompleted);
    window.resize(1200, 850);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QTRY_VERIFY_WITH_TIMEOUT(!frames.isEmpty(), kFrameTimeoutMs);
    setChain(*doc, chainOf({"tonemap", "vignette"}));
    frames.clear();
    QTRY_VERIFY_WITH_TIMEOUT(!frames.isEmpty(), kFrameTimeoutMs);
    const PostChain chainBefore = doc->scene().post;
    const QVector<double> pixelBefore = centrePixel(viewport->grabFramebuffer());

    // Click the tone mapping row: its parameters replace the material's in Properties.
    PropertyPanel* properties = window.propertyPanel();
    QCOMPARE(properties->subject(), PropertyPanel::Subject::Material);
    PostChainListView* list = window.postChainPanel()->list();
    QTest::mouseClick(list->viewport(), Qt::LeftButton, Qt::NoModifier,
                      list->visualRect(list->model()->index(0, 0)).center());
    QCOMPARE(properties->subject(), PropertyPanel::Subject::Effect);
    QCOMPARE(properties->effectIndex(), 0);
    ParamEditor* exposure = properties->subjectEditor(QStringLiteral("exposure"));
    QVERIFY(exposure);
    QVERIFY(properties->subjectEditor(QStringLiteral("operator")));   // a Choice: a combo
    QVERIFY(!properties->subjectEditor(QStringLiteral("intensity"))); // the vignette's, not shown
    auto* slider = exposure->findChild<QSlider*>(QStringLiteral("effectParam:exposure/slider"));
    QVERIFY(slider);
    QTRY_VERIFY(slider->isVisible()); // the Properties dock was raised
    QTest::qWait(50);                 // the new page's layout settles before the mouse comes
    QCOMPARE(slider->value(), 500);   // 0 EV in the middle of [-16, 16]

    // A real drag of the handle to the right: one command, brighter exposure.
    frames.clear();
    dragHandle(slider, slider->width() / 6);
    QCOMPARE(doc->undoStack()->count(), 1);
    const float ev = effectFloat(doc->scene().post.effects[0], "exposure");
    QVERIFY2(ev > 1.0f, qPrintable(QString::number(ev)));
    QVERIFY(doc->scene().post != chainBefore);
    QTRY_VERIFY_WITH_TIMEOUT(!frames.isEmpty(), kFrameTimeoutMs);
    QTRY_VERIFY_WITH_TIMEOUT(maxDifference(pixelBefore, centrePixel(viewport->grabFramebuffer())) >
                                 10.0,
                             kFrameTimeoutMs);

    // Undo: the chain and the pixel come back, and so does the slider.
    doc->undoStack()->undo();
    QVERIFY(doc->scene().post == chainBefore);
    QTRY_VERIFY_WITH_TIMEOUT(maxDifference(pixelBefore, centrePixel(viewport->grabFramebuffer())) <
                                 2.0,
                             kFrameTimeoutMs);
    QCOMPARE(slider->value(), 500); // 0 EV in [-16, 16]

    // The header's Material button shows the material's parameters again.
    auto* material =
        properties->findChild<QToolButton*>(QStringLiteral("propertiesMaterialButton"));
    QVERIFY(material && material->isVisible());
    material->click();
    QCOMPARE(properties->subject(), PropertyPanel::Subject::Material);
    QVERIFY(properties->editor(ParamId::Roughness)->isVisible());
    doc->newDocument(); // clean: closing asks nothing
}

void TestUiPanels::chainPresetLoadsAndReportsErrors() {
    DocumentController controller;
    setChain(controller, chainOf({"gaussian_blur"}));
    PostChainPanel panel(&controller);
    const QString toon = QString::fromStdString(resources::path("post-chains/toon.json").string());
    QStringList problems;
    QVERIFY(panel.loadPreset(toon, &problems));
    QCOMPARE(controller.scene().post.effects.front().type, std::string("toon"));
    controller.undoStack()->undo();
    QCOMPARE(typesOf(controller.scene().post), (std::vector<std::string>{"gaussian_blur"}));

    const QString broken = m_tmp.filePath(QStringLiteral("broken-chain.json"));
    QFile file(broken);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write(R"({"format": "velvet.post-chain", "version": 1, "name": "x",
                   "effects": [{"type": "bloom", "params": {"intensity": ["a"]}}]})");
    file.close();
    QVERIFY(!panel.loadPreset(broken, &problems));
    QVERIFY(!problems.isEmpty());
    QVERIFY2(problems.join(QLatin1Char('\n')).contains(QStringLiteral("broken-chain.json")),
             qPrintable(problems.join(QLatin1Char('\n'))));
    QVERIFY2(problems.join(QLatin1Char('\n')).contains(QStringLiteral("effects")),
             qPrintable(problems.join(QLatin1Char('\n'))));
    QCOMPARE(typesOf(controller.scene().post), (std::vector<std::string>{"gaussian_blur"}));

    // Save and load again: equal.
    const QString saved = m_tmp.filePath(QStringLiteral("saved-chain.json"));
    QString error;
    QVERIFY2(panel.savePreset(saved, QStringLiteral("Mine"), &error), qPrintable(error));
    setChain(controller, chainOf({"fxaa"}));
    QVERIFY(panel.loadPreset(saved, &problems));
    QCOMPARE(typesOf(controller.scene().post), (std::vector<std::string>{"gaussian_blur"}));
}

void TestUiPanels::mainWindowHasDocks() {
    MainWindow window(false);
    auto* postDock = window.findChild<QDockWidget*>(QStringLiteral("postChainDock"));
    auto* libraryDock = window.findChild<QDockWidget*>(QStringLiteral("libraryDock"));
    QVERIFY(postDock);
    QVERIFY(libraryDock);
    QVERIFY(window.postChainPanel());
    QVERIFY(window.libraryPanel());
    // The panel edits the window's document.
    QCOMPARE(window.postChainPanel()->model()->rowCount(),
             int(window.controller()->scene().post.effects.size()));
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetTest"));
    TestUiPanels test;
    return QTest::qExec(&test, argc, argv);
}
#include "test_ui_panels.moc"
