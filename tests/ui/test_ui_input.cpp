// Issue 17, items 3, 4 and 15 (HDRIs), driven through the real MainWindow under xvfb-run:
// - the mouse wheel over an unfocused slider, spin box or combo box in Properties scrolls the
//   panel and changes no value (no undo step); a focused one still takes the wheel;
// - after typing 0.35 and Enter in a number field, Ctrl+Z / Ctrl+Shift+Z / Ctrl+Y undo and redo
//   the document with the focus still in the field; uncommitted typing keeps its own text undo;
// - the HDRI chooser lists the five shipped environments with thumbnails, and picking one is one
//   undo step that changes the viewport.
#include "core/material.h"
#include "ui/document_controller.h"
#include "ui/main_window.h"
#include "ui/viewport_widget.h"
#include "ui_test_window.h"

#include <QAbstractItemView>
#include <QApplication>
#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QLineEdit>
#include <QScrollArea>
#include <QScrollBar>
#include <QSignalSpy>
#include <QSlider>
#include <QStandardPaths>
#include <QTest>
#include <QUndoStack>
#include <QUndoView>
#include <QWheelEvent>
#include <QtTest/qtestspontaneevent.h>
#include <cmath>

using namespace velvet;
using namespace velvet::ui;

namespace {

using test::kFrameTimeoutMs;

/// Mean absolute difference of two images' channels, 0..255 (every second pixel).
double meanDifference(const QImage& a, const QImage& b) {
    if (a.size() != b.size())
        return 255.0;
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < a.height(); y += 2)
        for (int x = 0; x < a.width(); x += 2, n += 3) {
            const QRgb p = a.pixel(x, y), q = b.pixel(x, y);
            sum += std::abs(qRed(p) - qRed(q)) + std::abs(qGreen(p) - qGreen(q)) +
                   std::abs(qBlue(p) - qBlue(q));
        }
    return sum / std::max(1, n);
}

} // namespace

class TestUiInput : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void init();

    void wheelOverUnfocusedControlsScrollsThePanel();
    void wheelOverFocusedSliderStillEdits();
    void undoKeysReachTheDocumentFromANumberField();
    void uncommittedTypingKeepsItsOwnUndo();
    void hdriChooserListsShippedEnvironmentsWithThumbnails();

private:
    template <class T>
    T* find(const QString& name) const {
        return m_window->findChild<T*>(name);
    }
    /// One wheel notch (@p angle eighths of a degree) at the centre of @p over, delivered as the
    /// platform would: spontaneous, to the deepest widget under the pointer.
    void wheelAt(QWidget* over, int angle);
    /// Scrolls Properties so that @p w is visible, and returns the panel's scroll area.
    QScrollArea* showInProperties(QWidget* w);

    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
};

void TestUiInput::initTestCase() {
    m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
    m_doc = m_window->controller();
    const QString error = test::showWithFirstFrame(m_window.get(), QSize(1280, 800));
    QVERIFY2(error.isEmpty(), qPrintable(error));
}

void TestUiInput::cleanupTestCase() {
    m_doc->newDocument();
    QVERIFY(m_window->close());
    m_window.reset();
}

void TestUiInput::init() {
    m_doc->newDocument();
    QCOMPARE(m_doc->undoStack()->count(), 0);
    // The focus somewhere that is neither a value control nor a text field.
    auto* history = find<QUndoView>(QStringLiteral("historyView"));
    history->setFocus();
    QTRY_VERIFY(history->hasFocus());
}

void TestUiInput::wheelAt(QWidget* over, int angle) {
    const QPoint global = over->mapToGlobal(over->rect().center());
    QWidget* target = m_window->childAt(m_window->mapFromGlobal(global));
    QVERIFY(target);
    QVERIFY2(target == over || over->isAncestorOf(target), qPrintable(target->objectName()));
    QWheelEvent wheel(QPointF(target->mapFromGlobal(global)), QPointF(global), QPoint(),
                      QPoint(0, angle), Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
    QSpontaneKeyEvent::setSpontaneous(&wheel);
    qApp->notify(target, &wheel);
}

QScrollArea* TestUiInput::showInProperties(QWidget* w) {
    QScrollArea* area = nullptr;
    for (QWidget* p = w->parentWidget(); p && !area; p = p->parentWidget())
        area = qobject_cast<QScrollArea*>(p);
    if (!area)
        return nullptr;
    area->ensureWidgetVisible(w, 10, 80);
    QCoreApplication::processEvents();
    return area;
}

void TestUiInput::wheelOverUnfocusedControlsScrollsThePanel() {
    const QString ior = QStringLiteral("param:lobes.base.ior");
    const Material before = m_doc->material();
    const QList<QWidget*> controls = {
        find<QSlider>(ior + "/slider"), find<QDoubleSpinBox>(ior + "/spin"),
        find<QComboBox>(QStringLiteral("param:brdf.distribution/combo"))};
    for (QWidget* control : controls) {
        QVERIFY(control);
        QScrollArea* area = showInProperties(control);
        QVERIFY(area);
        QScrollBar* bar = area->verticalScrollBar();
        QVERIFY2(bar->maximum() > 0, "Properties should be taller than its dock");
        // Scroll towards the side that has room.
        const bool down = bar->value() < bar->maximum();
        const int barBefore = bar->value();
        wheelAt(control, down ? -120 : 120);
        QCOMPARE(m_doc->undoStack()->count(), 0);
        QVERIFY2(m_doc->material() == before, qPrintable(control->objectName()));
        QVERIFY2(!control->hasFocus(), qPrintable(control->objectName()));
        QVERIFY2(down ? bar->value() > barBefore : bar->value() < barBefore,
                 qPrintable(QStringLiteral("%1: scroll bar %2 -> %3")
                                .arg(control->objectName())
                                .arg(barBefore)
                                .arg(bar->value())));
    }
}

void TestUiInput::wheelOverFocusedSliderStillEdits() {
    auto* slider = find<QSlider>(QStringLiteral("param:lobes.base.ior/slider"));
    QVERIFY(slider);
    showInProperties(slider);
    const float before = m_doc->material().scalar(ParamId::Ior);
    slider->setFocus(Qt::TabFocusReason); // as Tab would
    QTRY_VERIFY(slider->hasFocus());
    wheelAt(slider, -120);
    QVERIFY2(m_doc->material().scalar(ParamId::Ior) != before,
             qPrintable(QStringLiteral("IOR stayed %1").arg(before)));
    QCOMPARE(m_doc->undoStack()->count(), 1);
}

void TestUiInput::undoKeysReachTheDocumentFromANumberField() {
    const QString roughness = QStringLiteral("param:lobes.base.roughness");
    auto* spin = find<QDoubleSpinBox>(roughness + "/spin");
    QVERIFY(spin);
    showInProperties(spin);
    const float before = m_doc->material().scalar(ParamId::Roughness);
    QVERIFY(before != 0.35f);
    QTest::mouseClick(spin, Qt::LeftButton, Qt::NoModifier, QPoint(8, spin->height() / 2));
    QTRY_VERIFY(spin->hasFocus());
    spin->selectAll();
    QTest::keyClicks(spin, QStringLiteral("0.35"));
    QTest::keyClick(spin, Qt::Key_Return);
    QCOMPARE(m_doc->material().scalar(ParamId::Roughness), 0.35f);
    QCOMPARE(m_doc->undoStack()->count(), 1);
    QVERIFY(spin->hasFocus());

    // The keys go to the focus widget, the number field, as a user's would.
    QTest::keyClick(spin, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(m_doc->material().scalar(ParamId::Roughness), before);
    QCOMPARE(m_doc->undoStack()->index(), 0);
    QVERIFY(std::abs(spin->value() - before) < 5e-4);
    QTest::keyClick(spin, Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
    QCOMPARE(m_doc->material().scalar(ParamId::Roughness), 0.35f);
    QTest::keyClick(spin, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(m_doc->material().scalar(ParamId::Roughness), before);
    QTest::keyClick(spin, Qt::Key_Y, Qt::ControlModifier);
    QCOMPARE(m_doc->material().scalar(ParamId::Roughness), 0.35f);
    QCOMPARE(m_doc->undoStack()->count(), 1); // undo and redo made no commands
}

void TestUiInput::uncommittedTypingKeepsItsOwnUndo() {
    const QString roughness = QStringLiteral("param:lobes.base.roughness");
    auto* spin = find<QDoubleSpinBox>(roughness + "/spin");
    QVERIFY(spin);
    showInProperties(spin);
    // One committed edit, then typing that is not committed yet.
    QTest::mouseClick(spin, Qt::LeftButton, Qt::NoModifier, QPoint(8, spin->height() / 2));
    QTRY_VERIFY(spin->hasFocus());
    spin->selectAll();
    QTest::keyClicks(spin, QStringLiteral("0.35"));
    QTest::keyClick(spin, Qt::Key_Return);
    QCOMPARE(m_doc->undoStack()->count(), 1);
    QTest::keyClick(spin, Qt::Key_End);
    QTest::keyClick(spin, Qt::Key_Backspace);
    QCOMPARE(spin->text(), QStringLiteral("0.35"));
    // Ctrl+Z takes back the typing in the field; the document is untouched.
    QTest::keyClick(spin, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(spin->text(), QStringLiteral("0.350"));
    QCOMPARE(m_doc->undoStack()->index(), 1);
    QCOMPARE(m_doc->material().scalar(ParamId::Roughness), 0.35f);
    // Nothing typed is left: the next Ctrl+Z is the document's.
    QTest::keyClick(spin, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(m_doc->undoStack()->index(), 0);

    // A plain text field (the Library's search): typing is its own until committed (Enter).
    m_doc->undoStack()->redo();
    auto* search = find<QLineEdit>(QStringLiteral("librarySearch"));
    QVERIFY(search);
    m_window->findChild<QDockWidget*>(QStringLiteral("libraryDock"))->raise();
    QTRY_VERIFY(search->isVisible());
    search->setFocus();
    QTRY_VERIFY(search->hasFocus());
    QTest::keyClicks(search, QStringLiteral("x"));
    QTest::keyClick(search, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(search->text(), QString());
    QCOMPARE(m_doc->undoStack()->index(), 1);
    QTest::keyClicks(search, QStringLiteral("go"));
    QTest::keyClick(search, Qt::Key_Return);
    QTest::qWait(1); // the event loop turns between two keystrokes of a user
    QTest::keyClick(search, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(m_doc->undoStack()->index(), 0);
    QCOMPARE(search->text(), QStringLiteral("go"));
    search->clear();
    m_window->findChild<QDockWidget*>(QStringLiteral("propertiesDock"))->raise();
}

void TestUiInput::hdriChooserListsShippedEnvironmentsWithThumbnails() {
    auto* combo = find<QComboBox>(QStringLiteral("hdriCombo"));
    QVERIFY(combo);
    const QStringList shipped = {QStringLiteral("city"), QStringLiteral("forest"),
                                 QStringLiteral("interior"), QStringLiteral("studio"),
                                 QStringLiteral("sunset")};
    for (const QString& name : shipped) {
        const int i = combo->findText(name);
        QVERIFY2(i >= 0, qPrintable(name));
        const QIcon icon = combo->itemIcon(i);
        QVERIFY2(!icon.isNull(), qPrintable(name));
        // A thumbnail of the image, not a flat swatch: its pixels differ.
        const QImage thumb = icon.pixmap(combo->iconSize()).toImage();
        QVERIFY(!thumb.isNull());
        int distinct = 0;
        const QRgb first = thumb.pixel(0, 0);
        for (int y = 0; y < thumb.height(); ++y)
            for (int x = 0; x < thumb.width(); ++x)
                distinct += thumb.pixel(x, y) != first;
        QVERIFY2(distinct > thumb.width(), qPrintable(name));
    }
    const QString current =
        QFileInfo(QString::fromStdString(m_doc->scene().environment.hdri)).completeBaseName();
    const QString pick =
        current == QLatin1String("sunset") ? QStringLiteral("forest") : QStringLiteral("sunset");
    ViewportWidget* viewport = m_window->viewport();
    const auto settled = [viewport] {
        const double p = viewport->environmentProgress();
        return p < 0.0 || p >= 1.0;
    };
    QTRY_VERIFY_WITH_TIMEOUT(settled(), kFrameTimeoutMs);
    const QImage imageBefore = viewport->grabFramebuffer();

    // Chosen with the mouse in the combo's popup list.
    combo->showPopup();
    QAbstractItemView* list = combo->view();
    QTRY_VERIFY(list->isVisible());
    const QModelIndex index = combo->model()->index(combo->findText(pick), 0);
    list->scrollTo(index);
    const QPoint at = list->visualRect(index).center();
    QTest::mouseMove(list->viewport(), at);
    QTest::mouseClick(list->viewport(), Qt::LeftButton, Qt::NoModifier, at);
    QTRY_VERIFY(!list->isVisible());

    QCOMPARE(QFileInfo(QString::fromStdString(m_doc->scene().environment.hdri)).fileName(),
             pick + QStringLiteral(".exr"));
    QCOMPARE(m_doc->undoStack()->count(), 1);
    QCOMPARE(combo->currentText(), pick);
    QTRY_VERIFY_WITH_TIMEOUT((viewport->requestFrame(), settled()), kFrameTimeoutMs);
    const double changed = meanDifference(imageBefore, viewport->grabFramebuffer());
    QVERIFY2(changed > 1.0, qPrintable(QStringLiteral("mean difference %1").arg(changed)));
    m_doc->undoStack()->undo();
    QCOMPARE(QFileInfo(QString::fromStdString(m_doc->scene().environment.hdri)).completeBaseName(),
             current);
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetInputTest"));
    TestUiInput test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_ui_input.moc"
