// Drives the real MainWindow under xvfb-run: an edit made through a property widget changes the
// document and the viewport's pixels; undo and redo through the Edit shortcuts restore both; a
// slider drag is one undo command; the title carries the modified marker. Also checks that the
// property panel is generated from the parameter metadata, and that an image dropped onto a
// texture slot row fills the slot, shows its thumbnail and changes the viewport, undoably.
#include "core/color_management.h"
#include "core/image.h"
#include "core/material.h"
#include "render/renderer.h"
#include "ui/commands/set_param_command.h"
#include "ui/document_controller.h"
#include "ui/log_panel.h"
#include "ui/main_window.h"
#include "ui/properties/property_panel.h"
#include "ui/properties/texture_slot_editor.h"
#include "ui/viewport_widget.h"
#include "ui_test_util.h"

#include <QApplication>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QDropEvent>
#include <QElapsedTimer>
#include <QFile>
#include <QMimeData>
#include <QSignalSpy>
#include <QSlider>
#include <QStandardPaths>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QTemporaryDir>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>
#include <QUrl>
#include <cmath>

using namespace velvet;
using namespace velvet::ui;
using velvet::test::centrePixel;
using velvet::test::describe;
using velvet::test::handleCentre;
using velvet::test::kFrameTimeoutMs;
using velvet::test::maxDifference;

namespace {

const QString kRoughness = QStringLiteral("param:lobes.base.roughness");

/// The spin box shows 3 decimals of the stored float.
bool shows(const QDoubleSpinBox* spin, float value) {
    return std::abs(spin->value() - value) < 5e-4;
}

} // namespace

class TestUiEditor : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void init();

    void panelIsGeneratedFromMetadata();
    void editRedrawUndoRedo();
    void sliderDragIsOneCommand();
    void comboEditAndReset();
    void titleShowsModifiedMarker();
    void colourSwatchShowsDisplayValues();
    void failedOpenLeavesDocumentUntouched();
    void saveMarksCleanAndNamesTitle();
    void textureDropShowsThumbnailAndUndoes();
    void textureDropRefusesNonImage();
    void editsSayWhichPartsChanged();

private:
    /// The viewport's current image (grabFramebuffer renders a fresh frame).
    QImage viewportImage() { return m_window->viewport()->grabFramebuffer(); }
    /// Waits for the frame that follows an edit.
    void waitForFrame(QSignalSpy& spy);
    /// The centre pixel once the viewport has settled: the look-dev stage converges over a few
    /// frames (the environment is prefiltered in slices, an edit first draws at reduced
    /// resolution), and a grab reads the last frame, so each round asks for a new one and the
    /// pixel counts once two frames in a row agree.
    QVector<double> settledCentrePixel();
    template <class T>
    T* find(const QString& name) {
        return test::findNamed<T>(m_window.get(), name);
    }

    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
};

void TestUiEditor::initTestCase() {
    m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
    m_doc = m_window->controller();
    const QString up = test::showWithFirstFrame(m_window.get(), {800, 600});
    QVERIFY2(up.isEmpty(), qPrintable(up));
}

void TestUiEditor::cleanupTestCase() {
    m_doc->newDocument(); // clean: closing asks nothing
    QVERIFY(m_window->close());
    m_window.reset();
}

void TestUiEditor::init() {
    m_doc->newDocument();
    QVERIFY(!m_doc->isDirty());
    QCOMPARE(m_doc->undoStack()->count(), 0);
}

void TestUiEditor::waitForFrame(QSignalSpy& spy) {
    if (spy.isEmpty())
        QVERIFY(spy.wait(kFrameTimeoutMs));
}

QVector<double> TestUiEditor::settledCentrePixel() {
    // The environment's prefiltering first: it converges by small steps (a slice a frame), too
    // small for two frames to tell apart, but ~1 % of the pixel over the whole bake.
    const render::Renderer* renderer = m_window->viewport()->renderer();
    QElapsedTimer baking;
    baking.start();
    while (renderer && renderer->environmentProgress() < 1.0f && baking.elapsed() < 60000) {
        QSignalSpy drawn(m_window->viewport(), &ViewportWidget::frameCompleted);
        m_window->viewport()->requestFrame();
        if (!drawn.wait(kFrameTimeoutMs))
            break;
    }
    QVector<double> pixel = centrePixel(viewportImage());
    for (int i = 0; i < 40; ++i) {
        QSignalSpy drawn(m_window->viewport(), &ViewportWidget::frameCompleted);
        m_window->viewport()->requestFrame();
        if (!drawn.wait(kFrameTimeoutMs))
            break;
        const QVector<double> next = centrePixel(viewportImage());
        const bool settled = maxDifference(next, pixel) <= 0.25;
        pixel = next;
        if (settled && i >= 2)
            break;
    }
    return pixel;
}

void TestUiEditor::panelIsGeneratedFromMetadata() {
    for (const ParamMeta& meta : paramMetas()) {
        const QString name = QStringLiteral("param:") + QString::fromUtf8(meta.id);
        QWidget* row = find<QWidget>(name);
        QVERIFY2(row, qPrintable(name));
        QCOMPARE(row->toolTip(), QString::fromUtf8(meta.tooltip));
        QVERIFY(find<QToolButton>(name + "/reset"));
        switch (meta.type) {
        case ParamType::Float: {
            auto* slider = find<QSlider>(name + "/slider");
            auto* spin = find<QDoubleSpinBox>(name + "/spin");
            QVERIFY(slider && spin);
            QCOMPARE(spin->minimum(), double(meta.min));
            QCOMPARE(spin->maximum(), double(meta.max));
            QCOMPARE(slider->maximum() - slider->minimum(), 1000);
            break;
        }
        case ParamType::Color:
            QVERIFY(find<QToolButton>(name + "/swatch"));
            break;
        case ParamType::Choice: {
            auto* combo = find<QComboBox>(name + "/combo");
            QVERIFY(combo);
            QCOMPARE(combo->count(), int(meta.choices.size()));
            break;
        }
        }
    }
}

void TestUiEditor::editRedrawUndoRedo() {
    auto* slider = find<QSlider>(kRoughness + "/slider");
    auto* spin = find<QDoubleSpinBox>(kRoughness + "/spin");
    QVERIFY(slider && spin);
    const float before = m_doc->material().scalar(ParamId::Roughness);
    QVERIFY(shows(spin, before));
    const QVector<double> pixelBefore = settledCentrePixel();
    const int compilesBefore = m_window->viewport()->renderer()->shaderCompileCount();

    // Move as far as the slider goes, away from the current value, with the keyboard.
    const bool up = before < 0.5f;
    const float expected = up ? 1.0f : 0.0f;
    QSignalSpy frames(m_window->viewport(), &ViewportWidget::frameCompleted);
    slider->setFocus();
    QTest::keyClick(slider, up ? Qt::Key_End : Qt::Key_Home);
    QCOMPARE(m_doc->material().scalar(ParamId::Roughness), expected);
    QVERIFY(shows(spin, expected));
    QCOMPARE(m_doc->undoStack()->count(), 1);
    QCOMPARE(m_doc->undoStack()->undoText(), QStringLiteral("Set Roughness"));

    waitForFrame(frames);
    const QVector<double> pixelEdited = settledCentrePixel();
    QVERIFY2(maxDifference(pixelBefore, pixelEdited) > 2.0,
             qPrintable(QStringLiteral("roughness %1 -> %2: centre pixel %3 -> %4")
                            .arg(before)
                            .arg(expected)
                            .arg(describe(pixelBefore), describe(pixelEdited))));

    // Undo through the Edit menu's shortcut, sent to the main window.
    frames.clear();
    QTest::keyClick(m_window.get(), Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(m_doc->material().scalar(ParamId::Roughness), before);
    QVERIFY(shows(spin, before));
    QCOMPARE(slider->value(), int(std::lround(before * 1000)));
    waitForFrame(frames);
    const QVector<double> pixelUndone = settledCentrePixel();
    QVERIFY2(maxDifference(pixelBefore, pixelUndone) <= 1.0,
             qPrintable(describe(pixelBefore) + " vs " + describe(pixelUndone)));

    // Redo.
    frames.clear();
    QTest::keyClick(m_window.get(), Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
    QCOMPARE(m_doc->material().scalar(ParamId::Roughness), expected);
    QVERIFY(shows(spin, expected));
    waitForFrame(frames);
    QVERIFY(maxDifference(pixelEdited, settledCentrePixel()) <= 1.0);
    QCOMPARE(m_doc->undoStack()->count(), 1); // undo/redo created no new commands
    // A value edit goes to a uniform buffer: no shader was compiled for any of these frames.
    QCOMPARE(m_window->viewport()->renderer()->shaderCompileCount(), compilesBefore);

    // Typing into the spin box and pressing Enter is one more command.
    spin->setFocus();
    spin->selectAll();
    QTest::keyClicks(spin, QStringLiteral("0.25"));
    QTest::keyClick(spin, Qt::Key_Return);
    QCOMPARE(m_doc->material().scalar(ParamId::Roughness), 0.25f);
    QCOMPARE(slider->value(), 250);
    QCOMPARE(m_doc->undoStack()->count(), 2);
}

void TestUiEditor::sliderDragIsOneCommand() {
    auto* slider = find<QSlider>(kRoughness + "/slider");
    QVERIFY(slider);
    const float before = m_doc->material().scalar(ParamId::Roughness);
    const int direction = before < 0.5f ? 1 : -1;

    auto drag = [&] {
        QPoint pos = handleCentre(slider);
        QTest::mousePress(slider, Qt::LeftButton, Qt::NoModifier, pos);
        for (int i = 0; i < 10; ++i) {
            pos.rx() += direction * 4;
            QTest::mouseMove(slider, pos);
        }
        QTest::mouseRelease(slider, Qt::LeftButton, Qt::NoModifier, pos);
    };
    drag();
    const float afterFirst = m_doc->material().scalar(ParamId::Roughness);
    QVERIFY2(afterFirst != before, "the drag did not move the slider");
    QCOMPARE(m_doc->undoStack()->count(), 1);
    QCOMPARE(m_doc->undoStack()->undoText(), QStringLiteral("Set Roughness"));

    drag(); // a second drag is a second command
    QCOMPARE(m_doc->undoStack()->count(), 2);

    m_doc->undoStack()->undo();
    QCOMPARE(m_doc->material().scalar(ParamId::Roughness), afterFirst);
    m_doc->undoStack()->undo();
    QCOMPARE(m_doc->material().scalar(ParamId::Roughness), before);
    QCOMPARE(slider->value(), int(std::lround(before * 1000)));
}

void TestUiEditor::comboEditAndReset() {
    const QString name = QStringLiteral("param:brdf.distribution");
    auto* combo = find<QComboBox>(name + "/combo");
    QVERIFY(combo);
    const int before = m_doc->material().choice(ParamId::Distribution);
    const bool down = before + 1 < combo->count();
    const int other = down ? before + 1 : before - 1;
    combo->setFocus();
    QTest::keyClick(combo, down ? Qt::Key_Down : Qt::Key_Up);
    QCOMPARE(m_doc->material().choice(ParamId::Distribution), other);
    QCOMPARE(m_doc->undoStack()->count(), 1);

    // The reset button goes back to the metadata default, as one more command.
    QTest::mouseClick(find<QToolButton>(name + "/reset"), Qt::LeftButton);
    QCOMPARE(m_doc->material().choice(ParamId::Distribution),
             int(paramMeta(ParamId::Distribution).defaultValue.x));
    QCOMPARE(m_doc->undoStack()->count(), 2);
    QVERIFY(m_doc->undoStack()->undoText().startsWith(QStringLiteral("Reset")));
    m_doc->undoStack()->undo();
    m_doc->undoStack()->undo();
    QCOMPARE(m_doc->material().choice(ParamId::Distribution), before);
    QCOMPARE(combo->currentIndex(), before);
    QCOMPARE(m_doc->undoStack()->count(), 2); // refreshing the combo pushed nothing
}

void TestUiEditor::titleShowsModifiedMarker() {
    QVERIFY(m_window->windowTitle().contains(QStringLiteral("[*]")));
    QVERIFY(!m_window->isWindowModified());
    auto* slider = find<QSlider>(kRoughness + "/slider");
    slider->setFocus();
    QTest::keyClick(slider, Qt::Key_PageUp);
    QTest::keyClick(slider, Qt::Key_PageDown);
    QVERIFY(m_doc->isDirty());
    QVERIFY(m_window->isWindowModified());
    m_doc->undoStack()->undo();
    m_doc->undoStack()->undo();
    QVERIFY(!m_window->isWindowModified()); // back at the clean index
}

void TestUiEditor::colourSwatchShowsDisplayValues() {
    // The document stores scene-linear; the swatch (like the picker) shows display-encoded sRGB.
    const glm::vec3 linear(0.18f, 0.5f, 0.0f);
    m_doc->setParam(ParamId::BaseColor, linear); // as an undo command would
    auto* swatch = find<QToolButton>(QStringLiteral("param:lobes.base.color/swatch"));
    QVERIFY(swatch);
    const QImage icon = swatch->icon().pixmap(swatch->iconSize()).toImage();
    const QColor shown = icon.pixelColor(icon.width() / 2, icon.height() / 2);
    QCOMPARE(shown.red(), int(std::lround(linearToSrgb(linear.x) * 255))); // 118, not 46
    QCOMPARE(shown.green(), int(std::lround(linearToSrgb(linear.y) * 255)));
    QCOMPARE(shown.blue(), 0);
}

void TestUiEditor::failedOpenLeavesDocumentUntouched() {
    m_doc->setParam(ParamId::Roughness, glm::vec3(0.123f));
    const Scene before = m_doc->scene();
    QTemporaryDir dir;
    const QString bad = dir.filePath(QStringLiteral("broken.json"));
    QFile file(bad);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write("{\"format\": \"velvet.scene\", \"version\": 1, \"camera\": ");
    file.close();

    QSignalSpy replaced(m_doc, &DocumentController::documentReplaced);
    QStringList problems;
    QVERIFY(!m_doc->openFile(bad, &problems));
    QVERIFY(!problems.isEmpty());
    QVERIFY2(problems.first().contains(QStringLiteral("broken.json")),
             qPrintable(problems.first()));
    QVERIFY(replaced.isEmpty());
    QVERIFY(m_doc->scene() == before);
}

void TestUiEditor::saveMarksCleanAndNamesTitle() {
    QTemporaryDir dir;
    auto* slider = find<QSlider>(kRoughness + "/slider");
    slider->setFocus();
    QTest::keyClick(slider, Qt::Key_PageUp);
    QVERIFY(m_window->isWindowModified());
    const QString path = dir.filePath(QStringLiteral("look.json"));
    QString error;
    QVERIFY2(m_doc->saveAs(path, &error), qPrintable(error));
    QVERIFY(!m_window->isWindowModified());
    QVERIFY(m_window->windowTitle().startsWith(QStringLiteral("look.json")));

    // Reopening gives the same document, clean, with an empty history.
    const Scene saved = m_doc->scene();
    m_doc->newDocument();
    QStringList problems;
    QVERIFY2(m_doc->openFile(path, &problems), qPrintable(problems.join('\n')));
    QVERIFY(m_doc->scene() == saved);
    QCOMPARE(m_doc->undoStack()->count(), 0);
    QVERIFY(std::abs(find<QDoubleSpinBox>(kRoughness + "/spin")->value() -
                     saved.material.scalar(ParamId::Roughness)) < 5e-4);
}

namespace {

/// Sends a drag enter and a drop of @p file's URL onto @p target, as a drag from a file manager
/// would. Returns whether the drop was accepted; @p entered says whether the drag enter was.
/// The drop goes straight to the widget's event(): QApplication routes a sent Drop to the drag
/// manager's current target, which only a real drag sets.
bool dropFile(QWidget* target, const QString& file, bool* entered) {
    QMimeData mime;
    mime.setUrls({QUrl::fromLocalFile(file)});
    const QPointF pos(target->width() / 2.0, target->height() / 2.0);
    QDragEnterEvent enter(pos.toPoint(), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    static_cast<QObject*>(target)->event(&enter);
    *entered = enter.isAccepted();
    QDropEvent drop(pos, Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    static_cast<QObject*>(target)->event(&drop);
    return drop.isAccepted();
}

} // namespace

void TestUiEditor::textureDropShowsThumbnailAndUndoes() {
    // A 16 x 16 PNG of one known sRGB colour, written through core's image writer.
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString png = dir.filePath(QStringLiteral("red.png"));
    const int r = 200, g = 60, b = 30;
    Image image(16, 16, 4);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            float* p = image.at(x, y);
            p[0] = r / 255.0f, p[1] = g / 255.0f, p[2] = b / 255.0f, p[3] = 1.0f;
        }
    std::string error;
    QVERIFY2(writeImage(png.toStdString(), image, PixelFormat::UInt8, &error), error.c_str());

    auto* row = find<TextureSlotEditor>(QStringLiteral("textureSlot:baseColor"));
    QVERIFY(row);
    QCOMPARE(row, m_window->findChild<PropertyPanel*>()->textureEditor(TextureSlot::BaseColor));
    QVERIFY(find<QToolButton>(QStringLiteral("textureSlot:baseColor/browse")));
    QVERIFY(find<QToolButton>(QStringLiteral("textureSlot:baseColor/clear")));
    auto* combo = find<QComboBox>(QStringLiteral("textureSlot:baseColor/colorSpace"));
    QVERIFY(combo);
    QVERIFY(combo->count() > 2); // the default and the config's colour spaces
    QVERIFY(combo->itemText(0).contains(QStringLiteral("sRGB texture")));
    auto* normalCombo = find<QComboBox>(QStringLiteral("textureSlot:normal/colorSpace"));
    QVERIFY(normalCombo && normalCombo->itemText(0).contains(QStringLiteral("Raw")));
    QVERIFY(m_doc->material().texture(TextureSlot::BaseColor).empty());
    QVERIFY(row->thumbnail().isNull());

    // The undo below must come back to the settled image, so that is the one to remember.
    const QVector<double> pixelBefore = settledCentrePixel();
    const Material materialBefore = m_doc->material();
    QSignalSpy frames(m_window->viewport(), &ViewportWidget::frameCompleted);
    bool entered = false;
    QVERIFY(dropFile(row, png, &entered));
    QVERIFY(entered);
    QCOMPARE(QString::fromStdString(m_doc->material().texture(TextureSlot::BaseColor).file),
             QFileInfo(png).absoluteFilePath());
    QCOMPARE(m_doc->undoStack()->count(), 1);
    QCOMPARE(m_doc->undoStack()->undoText(), QStringLiteral("Set Base colour texture"));
    auto* fileLabel = find<QWidget>(QStringLiteral("textureSlot:baseColor/file"));
    QVERIFY(fileLabel && fileLabel->toolTip().contains(QStringLiteral("red.png")));

    // The thumbnail arrives from the background and shows the file's (display-encoded) colour.
    QTRY_VERIFY_WITH_TIMEOUT(!row->thumbnail().isNull(), 10000);
    const QColor shown =
        row->thumbnail().pixelColor(row->thumbnail().width() / 2, row->thumbnail().height() / 2);
    QVERIFY2(std::abs(shown.red() - r) <= 2 && std::abs(shown.green() - g) <= 2 &&
                 std::abs(shown.blue() - b) <= 2,
             qPrintable(shown.name()));

    waitForFrame(frames);
    QVector<double> pixelTextured;
    QTRY_VERIFY_WITH_TIMEOUT(
        maxDifference(pixelBefore, pixelTextured = centrePixel(viewportImage())) > 2.0, 30000);

    // Undo: the slot, the thumbnail and the viewport are back.
    frames.clear();
    m_doc->undoStack()->undo();
    QVERIFY(m_doc->material().texture(TextureSlot::BaseColor).empty());
    QVERIFY(m_doc->material() == materialBefore); // the factor the drop turned white too
    QVERIFY(row->thumbnail().isNull());
    waitForFrame(frames);
    QVector<double> pixelUndone;
    QTRY_VERIFY2_WITH_TIMEOUT(
        maxDifference(pixelBefore, pixelUndone = centrePixel(viewportImage())) <= 1.0,
        qPrintable(QStringLiteral("centre pixel %1, textured %2, undone %3")
                       .arg(describe(pixelBefore), describe(pixelTextured), describe(pixelUndone))),
        30000);

    // Redo shows the texture again (the thumbnail comes from the cache), then Clear empties it.
    m_doc->undoStack()->redo();
    QVERIFY(!m_doc->material().texture(TextureSlot::BaseColor).empty());
    QTRY_VERIFY_WITH_TIMEOUT(!row->thumbnail().isNull(), 10000);
    find<QToolButton>(QStringLiteral("textureSlot:baseColor/clear"))->click();
    QVERIFY(m_doc->material().texture(TextureSlot::BaseColor).empty());
    QCOMPARE(m_doc->undoStack()->count(), 2);

    // A colour space chosen in the combo is one more command.
    m_doc->undoStack()->undo(); // the file again
    const int raw = combo->findData(QStringLiteral("Raw"));
    QVERIFY(raw > 0);
    combo->activated(raw);
    QCOMPARE(m_doc->material().texture(TextureSlot::BaseColor).colorSpace, std::string("Raw"));
    QCOMPARE(m_doc->undoStack()->undoText(),
             QStringLiteral("Set Base colour texture colour space"));
    m_doc->undoStack()->undo();
    QVERIFY(m_doc->material().texture(TextureSlot::BaseColor).colorSpace.empty());
    QCOMPARE(combo->currentIndex(), 0);

    // An atlas region: the thumbnail shows just that region (right half blue, left half red).
    for (int y = 0; y < 16; ++y)
        for (int x = 8; x < 16; ++x) {
            float* p = image.at(x, y);
            p[0] = 0.0f, p[1] = 0.0f, p[2] = 1.0f;
        }
    const QString atlas = dir.filePath(QStringLiteral("atlas.png"));
    QVERIFY2(writeImage(atlas.toStdString(), image, PixelFormat::UInt8, &error), error.c_str());
    TextureRef region;
    region.file = QFileInfo(atlas).absoluteFilePath().toStdString();
    region.useRegion = true;
    region.region = {8, 0, 8, 16};
    m_doc->editTexture(TextureSlot::BaseColor, region, QStringLiteral("Assign region"));
    QVERIFY(fileLabel->toolTip().contains(QStringLiteral("Region: 8, 0, 8 x 16")));
    QTRY_VERIFY_WITH_TIMEOUT(!row->thumbnail().isNull(), 10000);
    QCOMPARE(row->thumbnail().size(), QSize(8, 16));
    for (const QPoint at : {QPoint(0, 0), QPoint(7, 15)})
        QCOMPARE(row->thumbnail().pixelColor(at), QColor(0, 0, 255));
}

void TestUiEditor::textureDropRefusesNonImage() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    auto* row = find<TextureSlotEditor>(QStringLiteral("textureSlot:baseColor"));
    QVERIFY(row);
    LogPanel* log = m_window->logPanel();
    const Material before = m_doc->material();

    // A text file: refused by the drag enter, and by the drop with a message.
    const QString text = dir.filePath(QStringLiteral("notes.txt"));
    QFile file(text);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write("not an image\n");
    file.close();
    QSignalSpy messages(row, &TextureSlotEditor::message);
    const size_t logBefore = log->entries().size();
    bool entered = true;
    QVERIFY(!dropFile(row, text, &entered));
    QVERIFY(!entered);
    QCOMPARE(messages.size(), 1);
    QVERIFY(messages.at(0).at(0).toString().contains(QStringLiteral("notes.txt")));
    QCOMPARE(log->entries().size(), logBefore + 1);
    QVERIFY(log->entries().back().text.contains(QStringLiteral("not an image")));
    QVERIFY(m_doc->material() == before);
    QCOMPARE(m_doc->undoStack()->count(), 0);
    QVERIFY(row->thumbnail().isNull());

    // A file named like an image that OpenImageIO cannot read: refused too, with OIIO's reason.
    const QString broken = dir.filePath(QStringLiteral("broken.png"));
    QFile bad(broken);
    QVERIFY(bad.open(QIODevice::WriteOnly));
    bad.write("this is not a PNG");
    bad.close();
    QVERIFY(!dropFile(row, broken, &entered));
    QVERIFY(entered); // the extension looks right
    QCOMPARE(messages.size(), 2);
    QVERIFY(messages.at(1).at(0).toString().contains(QStringLiteral("broken.png")));
    QVERIFY(m_doc->material() == before);
    QCOMPARE(m_doc->undoStack()->count(), 0);
}

void TestUiEditor::editsSayWhichPartsChanged() {
    // Each edit, its undo and its redo name the one part they changed (core/scene_parts.h), so
    // the renderer and the panels touch only that part; a new document names every part.
    std::vector<ScenePart> seen;
    const QMetaObject::Connection c = connect(m_doc, &DocumentController::sceneChanged, this,
                                              [&seen](ScenePart parts) { seen.push_back(parts); });
    const auto expectOne = [&](ScenePart part, const char* what) {
        QVERIFY2(seen.size() == 1, what);
        QVERIFY2(seen.front() == part, what);
        seen.clear();
    };
    m_doc->editParam(ParamId::Roughness, glm::vec3(0.83f));
    expectOne(ScenePart::MaterialValues, "roughness edit");
    m_doc->undoStack()->undo();
    expectOne(ScenePart::MaterialValues, "roughness undo");
    m_doc->undoStack()->redo();
    expectOne(ScenePart::MaterialValues, "roughness redo");
    std::vector<Light> lights = m_doc->scene().lights;
    lights.push_back(Light{});
    m_doc->editLights(lights, QStringLiteral("Add light"));
    expectOne(ScenePart::Lights, "light added");
    m_doc->editMesh(MeshRef{PreviewMeshKind::Cube, {}});
    expectOne(ScenePart::Mesh, "mesh");
    Environment env = m_doc->scene().environment;
    env.intensity = 2.5f;
    m_doc->editEnvironment(env, QStringLiteral("Intensity"));
    expectOne(ScenePart::Environment, "environment");
    m_doc->editTexture(TextureSlot::BaseColor, TextureRef{}, QStringLiteral("Clear"));
    QVERIFY(seen.empty()); // the slot was empty already: no edit, no signal
    m_doc->newDocument();
    expectOne(ScenePart::All, "new document");
    disconnect(c);
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetTest"));
    TestUiEditor test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_ui_editor.moc"
