// Issue 17, item 7: the linear-workflow colour picker, driven through the real MainWindow under
// xvfb-run. A click on the Base colour swatch opens it (not modal); a drag on its wheel changes
// the document and the viewport while the mouse moves, and the whole drag is one undo step;
// display-referred and scene-linear values sit side by side (sRGB's known pairs: #808080 is
// 0.2159 linear, 0.5 linear is 0.7354 displayed); hex is display space; undo while it is open
// moves it too; the eyedropper stores the linear value of the viewport pixel clicked (and does
// not orbit); the emissive colour's picker has an intensity beyond 1 (the emission strength);
// the colour spaces are named.
#include "ui/document_controller.h"
#include "ui/main_window.h"
#include "ui/properties/color_param_editor.h"
#include "ui/properties/linear_color_picker.h"
#include "ui/properties/property_panel.h"
#include "ui/viewport_toolbar.h"
#include "ui/viewport_widget.h"
#include "ui_test_window.h"

#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QStandardPaths>
#include <QSurfaceFormat>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>
#include <cmath>

using namespace velvet;
using namespace velvet::ui;

namespace {

bool near(glm::vec3 a, glm::vec3 b, float eps) {
    return std::abs(a.x - b.x) <= eps && std::abs(a.y - b.y) <= eps && std::abs(a.z - b.z) <= eps;
}

QString str(glm::vec3 v) {
    return QStringLiteral("(%1, %2, %3)").arg(v.x).arg(v.y).arg(v.z);
}

} // namespace

class TestUiColorPicker : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void pickerIsLiveLinearAndOneStepPerGesture();
    void eyedropperAndEmissionIntensity();

private:
    LinearColorPicker* open(ParamId id);
    QWindow* glWindow() const { return m_window->viewport()->glWindow(); }

    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
};

void TestUiColorPicker::initTestCase() {
    m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
    m_doc = m_window->controller();
    const QString up = test::showWithFirstFrame(m_window.get(), QSize(1280, 800));
    QVERIFY2(up.isEmpty(), qPrintable(up));
    m_window->viewport()->setReducedResolution(false);
}

void TestUiColorPicker::cleanupTestCase() {
    m_doc->newDocument();
    QVERIFY(m_window->close());
    m_window.reset();
}

LinearColorPicker* TestUiColorPicker::open(ParamId id) {
    auto* editor = qobject_cast<ColorParamEditor*>(m_window->propertyPanel()->editor(id));
    if (!editor)
        return nullptr;
    m_window->findChild<QDockWidget*>(QStringLiteral("propertiesDock"))->raise();
    m_window->propertyPanel()->showMaterial();
    QTest::mouseClick(editor->swatch(), Qt::LeftButton);
    if (!QTest::qWaitFor([editor] { return editor->picker() && editor->picker()->isVisible(); }))
        return nullptr;
    return editor->picker();
}

void TestUiColorPicker::pickerIsLiveLinearAndOneStepPerGesture() {
    m_doc->newDocument();
    const PickerColorSpace space = m_window->viewportToolbar()->pickerColorSpace();
    LinearColorPicker* picker = open(ParamId::BaseColor);
    QVERIFY(picker);
    QVERIFY(!picker->isModal());

    // Both sides, and what they are.
    const glm::vec3 start = m_doc->param(ParamId::BaseColor);
    QVERIFY(near(picker->linear(), start, 1e-6f));
    for (int c = 0; c < 3; ++c) {
        QCOMPARE(float(picker->linearBox(c)->value()), std::round(start[c] * 1e4f) / 1e4f);
        QVERIFY(std::abs(picker->displayBox(c)->value() - space.toDisplay(start)[c]) < 1e-4);
    }
    QCOMPARE(picker->hexField()->text(), picker->hex());
    QVERIFY2(picker->spaceLabel()->text().contains(space.name()),
             qPrintable(picker->spaceLabel()->text()));
    QVERIFY(picker->spaceLabel()->text().contains(QStringLiteral("scene-linear")));
    if (space.colorManagement && space.colorManagement->isLoaded())
        QVERIFY(picker->spaceLabel()->text().contains(
            QString::fromStdString(space.colorManagement->roleColorSpace("scene_linear"))));

    // A drag on the wheel: live (the document and the viewport change while the mouse moves),
    // and one undo step for the whole drag.
    QUndoStack* stack = m_doc->undoStack();
    const int steps = stack->count();
    const QImage before = m_window->viewport()->grabFramebuffer();
    QWidget* wheel = picker->wheel();
    const QPoint c = wheel->rect().center();
    QTest::mousePress(wheel, Qt::LeftButton, Qt::NoModifier, c + QPoint(30, 0));
    QTest::mouseMove(wheel, c + QPoint(40, -10));
    QVERIFY2(!near(m_doc->param(ParamId::BaseColor), start, 1e-4f), "no live edit while dragging");
    QVERIFY(m_window->viewport()->grabFramebuffer() != before);
    for (int i = 1; i <= 4; ++i)
        QTest::mouseMove(wheel, c + QPoint(40 - 12 * i, -10 - 12 * i));
    QTest::mouseRelease(wheel, Qt::LeftButton, Qt::NoModifier, c + QPoint(-8, -58));
    QCOMPARE(stack->count(), steps + 1);
    QVERIFY(near(m_doc->param(ParamId::BaseColor), picker->linear(), 1e-6f));
    if (const QString shot = qEnvironmentVariable("VELVET_PICKER_SHOT"); !shot.isEmpty())
        picker->grab().save(shot); // for judging the layout by eye
    // A second gesture is a second step; undo takes the picker back with the document.
    const glm::vec3 afterFirst = m_doc->param(ParamId::BaseColor);
    QTest::mousePress(wheel, Qt::LeftButton, Qt::NoModifier, c + QPoint(-40, 20));
    QTest::mouseMove(wheel, c + QPoint(-45, 25));
    QTest::mouseRelease(wheel, Qt::LeftButton, Qt::NoModifier, c + QPoint(-45, 25));
    QCOMPARE(stack->count(), steps + 2);
    stack->undo();
    QVERIFY(near(picker->linear(), afterFirst, 1e-6f));

    // Hex is display-referred: #808080 is sRGB 128/255, 0.2159 scene-linear.
    if (space.isSrgb()) {
        picker->hexField()->selectAll();
        QTest::keyClicks(picker->hexField(), QStringLiteral("#808080"));
        QTest::keyClick(picker->hexField(), Qt::Key_Return);
        const float expected = std::pow((128.0f / 255.0f + 0.055f) / 1.055f, 2.4f);
        QVERIFY2(near(m_doc->param(ParamId::BaseColor), glm::vec3(expected), 1e-4f),
                 qPrintable(str(m_doc->param(ParamId::BaseColor))));
        // A linear value typed: stored as typed, shown displayed beside it (0.5 -> 0.7354).
        QDoubleSpinBox* red = picker->linearBox(0);
        red->selectAll();
        QTest::keyClicks(red, QStringLiteral("0.5"));
        QTest::keyClick(red, Qt::Key_Return);
        QCOMPARE(m_doc->param(ParamId::BaseColor).x, 0.5f);
        QVERIFY2(std::abs(picker->displayBox(0)->value() - 0.7354) < 2e-4,
                 qPrintable(QString::number(picker->displayBox(0)->value())));
    }
    picker->close();
}

void TestUiColorPicker::eyedropperAndEmissionIntensity() {
    m_doc->newDocument();
    const PickerColorSpace space = m_window->viewportToolbar()->pickerColorSpace();
    LinearColorPicker* picker = open(ParamId::BaseColor);
    QVERIFY(picker);
    QVERIFY(picker->eyedropper()->isVisible());
    // The pixel at the viewport's centre (the sphere), as displayed now.
    const QImage frame = m_window->viewport()->grabFramebuffer();
    const QPoint centre(glWindow()->width() / 2, glWindow()->height() / 2);
    const qreal dpr = frame.devicePixelRatio();
    const QColor pixel = frame.pixelColor(int(centre.x() * dpr), int(centre.y() * dpr));
    const glm::vec3 expected =
        space.toLinear(glm::vec3(pixel.redF(), pixel.greenF(), pixel.blueF()));
    const Camera view = m_window->viewport()->viewCamera();
    QTest::mouseClick(picker->eyedropper(), Qt::LeftButton);
    QVERIFY(picker->eyedropper()->isChecked());
    QTest::mousePress(glWindow(), Qt::LeftButton, Qt::NoModifier, centre);
    QTest::mouseMove(glWindow(), centre + QPoint(30, 0));
    QTest::mouseRelease(glWindow(), Qt::LeftButton, Qt::NoModifier, centre + QPoint(30, 0));
    QVERIFY(!picker->eyedropper()->isChecked());
    QVERIFY2(near(m_doc->param(ParamId::BaseColor), expected, 2e-3f),
             qPrintable(str(m_doc->param(ParamId::BaseColor)) + " vs " + str(expected)));
    QCOMPARE(m_window->viewport()->viewCamera().yawDeg, view.yawDeg); // picked, not orbited
    picker->close();

    // Emission: an intensity beyond 1, the emission strength.
    LinearColorPicker* emissive = open(ParamId::EmissiveColor);
    QVERIFY(emissive);
    QDoubleSpinBox* intensity = emissive->intensityBox();
    QVERIFY(intensity->isVisible());
    QVERIFY(intensity->maximum() > 1.0);
    intensity->selectAll();
    QTest::keyClicks(intensity, QStringLiteral("25"));
    QTest::keyClick(intensity, Qt::Key_Return);
    QCOMPARE(m_doc->param(ParamId::EmissiveStrength).x, 25.0f);
    m_doc->undoStack()->undo();
    QCOMPARE(float(intensity->value()), m_doc->param(ParamId::EmissiveStrength).x);
    emissive->close();
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetColorPickerTest"));
    TestUiColorPicker test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_ui_color_picker.moc"
