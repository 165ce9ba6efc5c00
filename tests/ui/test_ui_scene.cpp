// Drives the real MainWindow under xvfb-run (issue 5): the Scene dock's lights (a rig, add, edit
// by typing, Delete) and the toolbar's light rig are undoable document edits that change the
// viewport's pixels; a material preset dropped on the window is applied as one undoable step
// (the mesh, HDRI and lights stay), an image dropped on it fills the base colour slot; the
// History panel jumps; Ctrl+S saves; closing or R with unsaved changes asks first and Cancel
// keeps everything; the status bar shows the frame time; the Library lists fabrics first.
#include "core/document_io.h"
#include "core/light_rigs.h"
#include "core/post_effects.h"
#include "core/resources.h"
#include "ui/document_controller.h"
#include "ui/library/library_panel.h"
#include "ui/main_window.h"
#include "ui/post_chain/post_chain_panel.h"
#include "ui/scene/scene_panel.h"
#include "ui/viewport_widget.h"
#include "ui_test_util.h"

#include <QAbstractButton>
#include <QApplication>
#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QFile>
#include <QFileDialog>
#include <QLabel>
#include <QLineEdit>
#include <QListView>
#include <QListWidget>
#include <QMenu>
#include <QMessageBox>
#include <QMimeData>
#include <QRegularExpression>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>
#include <QToolButton>
#include <QUndoStack>
#include <QUndoView>
#include <QUrl>
#include <QWindow>

using namespace velvet;
using namespace velvet::ui;

using velvet::test::answerNextMessageBox;
using velvet::test::centreLuma;
using velvet::test::dropFile;

class TestUiScene : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void init();

    void sceneDockRigChangesPixelAndUndoes();
    void addAndTypeIntoLightIsOneCommandEach();
    void deleteKeyRemovesSelectedLight();
    void toolbarLightRigMatchesSceneDock();
    void droppedPresetIsAppliedUndoably();
    void droppedImageFillsBaseColour();
    void historyPanelJumps();
    void ctrlSSavesAndClosePromptsWhenDirty();
    void reloadKeyAsksAndRestoresFile();
    void statusBarShowsFrameTime();
    void libraryListsFabricsFirst();
    void libraryDoubleClickAppliesAndCtrlZUndoes();
    void postChainDragInWindowReordersAndRedraws();
    void ctrlOReopensSavedDocumentEqual();
    void lightFieldsTakeDecimalsAndEditOnlyThemselves();
    void conesStayOrderedAndDirectionNeverZero();
    void discreteLightEditsAreSeparateCommands();
    void repeatedSceneProblemsAreReportedOnce();

private:
    QImage viewportImage() { return m_window->viewport()->grabFramebuffer(); }
    template <class T>
    T* find(const QString& name) {
        return test::findNamed<T>(m_window.get(), name);
    }
    void chooseRig(QComboBox* combo, std::string_view id) {
        const int index = combo->findData(QString::fromUtf8(id.data(), qsizetype(id.size())));
        QVERIFY(index >= 0);
        combo->setCurrentIndex(index);
        emit combo->activated(index); // what a click on the item does
    }

    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
    ScenePanel* m_scene = nullptr;
    QTemporaryDir m_dir;
};

void TestUiScene::initTestCase() {
    QVERIFY(m_dir.isValid());
    m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
    m_doc = m_window->controller();
    m_scene = m_window->scenePanel();
    QVERIFY(m_scene);
    const QString up = test::showWithFirstFrame(m_window.get(), {900, 700});
    QVERIFY2(up.isEmpty(), qPrintable(up));
}

void TestUiScene::cleanupTestCase() {
    m_doc->newDocument();
    QVERIFY(m_window->close());
    m_window.reset();
}

void TestUiScene::init() {
    m_doc->newDocument();
}

void TestUiScene::sceneDockRigChangesPixelAndUndoes() {
    QCOMPARE(matchingLightRig(m_doc->scene().lights).value_or(""), std::string_view("key"));
    auto* rig = find<QComboBox>(QStringLiteral("sceneLightRig"));
    QCOMPARE(rig->currentData().toString(), QStringLiteral("key"));
    const double keyLit = centreLuma(viewportImage());

    chooseRig(rig, "environment");
    QVERIFY(m_doc->scene().lights.empty());
    QCOMPARE(m_doc->undoStack()->count(), 1);
    QCOMPARE(m_doc->undoStack()->undoText(), QStringLiteral("Light rig: Environment only"));
    QCOMPARE(find<QListWidget>(QStringLiteral("lightList"))->count(), 0);
    const double envOnly = centreLuma(viewportImage());
    QVERIFY2(envOnly < keyLit - 3.0,
             qPrintable(QStringLiteral("%1 -> %2").arg(keyLit).arg(envOnly)));

    chooseRig(rig, "sun"); // twice the key's illuminance, from higher up
    QCOMPARE(m_doc->scene().lights.size(), size_t(1));
    QCOMPARE(m_doc->scene().lights[0].name, std::string("Sun"));

    m_doc->undoStack()->undo();
    m_doc->undoStack()->undo();
    QCOMPARE(matchingLightRig(m_doc->scene().lights).value_or(""), std::string_view("key"));
    QCOMPARE(rig->currentData().toString(), QStringLiteral("key"));
    QVERIFY(std::abs(centreLuma(viewportImage()) - keyLit) < 1.0);
}

void TestUiScene::addAndTypeIntoLightIsOneCommandEach() {
    chooseRig(find<QComboBox>(QStringLiteral("sceneLightRig")), "environment");
    const double dark = centreLuma(viewportImage());

    // Add > Point from the dock's menu.
    auto* add = find<QToolButton>(QStringLiteral("addLightButton"));
    QMenu* menu = add->menu();
    QAction* point = nullptr;
    for (QAction* a : menu->actions())
        if (a->text() == QStringLiteral("Point"))
            point = a;
    QVERIFY(point);
    point->trigger();
    QCOMPARE(m_doc->scene().lights.size(), size_t(1));
    QCOMPARE(m_doc->scene().lights[0].type, LightType::Point);
    QCOMPARE(m_scene->selectedLight(), 0);
    QCOMPARE(m_doc->undoStack()->count(), 2);

    // Put it in front of the sphere and type a new intensity: one command for the typing.
    m_doc->editLights(
        [&] {
            auto lights = m_doc->scene().lights;
            lights[0].position = {0.0f, 0.0f, 2.0f};
            return lights;
        }(),
        QStringLiteral("Move light"));
    auto* intensity = find<QDoubleSpinBox>(QStringLiteral("lightIntensity"));
    QVERIFY(intensity->isVisibleTo(m_window.get()) || intensity->isEnabled());
    QCOMPARE(intensity->suffix(), QStringLiteral(" cd"));
    const int before = m_doc->undoStack()->count();
    intensity->setFocus();
    intensity->selectAll();
    QTest::keyClicks(intensity, QStringLiteral("40"));
    QTest::keyClick(intensity, Qt::Key_Return);
    QCOMPARE(m_doc->scene().lights[0].intensity, 40.0f);
    QCOMPARE(m_doc->undoStack()->count(), before + 1); // "4" then "40" merged
    const double lit = centreLuma(viewportImage());
    QVERIFY2(lit > dark + 10.0, qPrintable(QStringLiteral("%1 -> %2").arg(dark).arg(lit)));

    m_doc->undoStack()->undo();
    QCOMPARE(m_doc->scene().lights[0].intensity, 10.0f);
    QCOMPARE(intensity->value(), 10.0);
    m_doc->undoStack()->undo(); // move
    m_doc->undoStack()->undo(); // add
    QVERIFY(m_doc->scene().lights.empty());
    QVERIFY(std::abs(centreLuma(viewportImage()) - dark) < 1.0);
}

void TestUiScene::deleteKeyRemovesSelectedLight() {
    chooseRig(find<QComboBox>(QStringLiteral("sceneLightRig")), "three-point");
    auto* list = find<QListWidget>(QStringLiteral("lightList"));
    QCOMPARE(list->count(), 3);
    m_window->findChild<QDockWidget*>(QStringLiteral("sceneDock"))->raise();
    list->setCurrentRow(1);
    list->setFocus();
    QTest::keyClick(list, Qt::Key_Delete);
    QCOMPARE(m_doc->scene().lights.size(), size_t(2));
    QCOMPARE(m_doc->scene().lights[0].name, std::string("Key"));
    QCOMPARE(m_doc->scene().lights[1].name, std::string("Rim"));
    QCOMPARE(m_doc->undoStack()->undoText(), QStringLiteral("Remove light Fill"));
    QCOMPARE(find<QComboBox>(QStringLiteral("sceneLightRig"))->currentData().toString(),
             QString()); // "Custom"
    m_doc->undoStack()->undo();
    QCOMPARE(matchingLightRig(m_doc->scene().lights).value_or(""), std::string_view("three-point"));
}

void TestUiScene::toolbarLightRigMatchesSceneDock() {
    auto* toolbarRig = find<QComboBox>(QStringLiteral("lightRigCombo"));
    auto* dockRig = find<QComboBox>(QStringLiteral("sceneLightRig"));
    QCOMPARE(toolbarRig->count(), int(lightRigs().size()));
    chooseRig(toolbarRig, "coloured-points");
    QCOMPARE(m_doc->scene().lights.size(), size_t(64));
    QCOMPARE(dockRig->currentData().toString(), QStringLiteral("coloured-points"));
    QCOMPARE(find<QListWidget>(QStringLiteral("lightList"))->count(), 64);
    m_doc->undoStack()->undo();
    QCOMPARE(toolbarRig->currentData().toString(), QStringLiteral("key"));
}

void TestUiScene::droppedPresetIsAppliedUndoably() {
    chooseRig(find<QComboBox>(QStringLiteral("sceneLightRig")), "softboxes");
    const Scene before = m_doc->scene();
    const double velvet = centreLuma(viewportImage());
    const QString gold = QString::fromStdString(resources::path("presets/gold.json").string());
    QVERIFY(dropFile(m_window.get(), m_window->rect().center(), gold));
    QCOMPARE(m_doc->scene().material.name, std::string("Polished gold"));
    // The scene being judged stays: mesh, HDRI, lights, post chain.
    QVERIFY(m_doc->scene().lights == before.lights);
    QVERIFY(m_doc->scene().environment == before.environment);
    QVERIFY(m_doc->scene().mesh == before.mesh);
    QCOMPARE(m_doc->undoStack()->count(), 2);
    QVERIFY(std::abs(centreLuma(viewportImage()) - velvet) > 3.0);
    m_doc->undoStack()->undo();
    QVERIFY(m_doc->scene() == before);
}

void TestUiScene::droppedImageFillsBaseColour() {
    // A flat green image: the base colour texture replaces the velvet's red.
    const QString png = m_dir.filePath(QStringLiteral("green.png"));
    QImage image(16, 16, QImage::Format_RGB32);
    image.fill(QColor(20, 200, 40));
    QVERIFY(image.save(png));
    const QImage beforeImage = viewportImage();
    const QColor before = beforeImage.pixelColor(beforeImage.width() / 2, beforeImage.height() / 2);
    QVERIFY(dropFile(m_window.get(), m_window->rect().center(), png));
    QCOMPARE(QString::fromStdString(m_doc->material().texture(TextureSlot::BaseColor).file),
             QFileInfo(png).absoluteFilePath());
    // The texture loads off the drawing thread (issue 16): frames show the parameter value until
    // it arrives, then the map.
    QColor c;
    const auto green = [&] {
        const QImage after = viewportImage();
        c = after.pixelColor(after.width() / 2, after.height() / 2);
        return c.green() > c.red();
    };
    QTRY_VERIFY2_WITH_TIMEOUT(
        green(), qPrintable(QStringLiteral("%1 -> %2").arg(before.name(), c.name())), 20000);
    QVERIFY(before.red() > before.green());
    m_doc->undoStack()->undo();
    QVERIFY(m_doc->material().texture(TextureSlot::BaseColor).empty());
    // Something that is none of these is refused, and nothing changes.
    const QString text = m_dir.filePath(QStringLiteral("notes.txt"));
    QFile f(text);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("hello");
    f.close();
    QVERIFY(!dropFile(m_window.get(), m_window->rect().center(), text));
}

void TestUiScene::historyPanelJumps() {
    auto* rig = find<QComboBox>(QStringLiteral("sceneLightRig"));
    chooseRig(rig, "sun");
    chooseRig(rig, "three-point");
    chooseRig(rig, "softboxes");
    QCOMPARE(m_doc->undoStack()->count(), 3);
    auto* history = m_window->findChild<QUndoView*>(QStringLiteral("historyView"));
    QVERIFY(history);
    m_window->findChild<QDockWidget*>(QStringLiteral("historyDock"))->raise();
    // Row 0 is "<opened>", row k the state after command k.
    const QModelIndex second = history->model()->index(1, 0);
    QCOMPARE(second.data().toString(), QStringLiteral("Light rig: Sun"));
    const QRect rect = history->visualRect(second);
    QTest::mouseClick(history->viewport(), Qt::LeftButton, Qt::NoModifier, rect.center());
    QCOMPARE(m_doc->undoStack()->index(), 1);
    QCOMPARE(m_doc->scene().lights[0].name, std::string("Sun"));
    QTest::mouseClick(history->viewport(), Qt::LeftButton, Qt::NoModifier,
                      history->visualRect(history->model()->index(3, 0)).center());
    QCOMPARE(m_doc->undoStack()->index(), 3);
}

void TestUiScene::ctrlSSavesAndClosePromptsWhenDirty() {
    const QString path = m_dir.filePath(QStringLiteral("ctrl_s.json"));
    QString error;
    QVERIFY2(m_doc->saveAs(path, &error), qPrintable(error));
    chooseRig(find<QComboBox>(QStringLiteral("sceneLightRig")), "stage-spot");
    QVERIFY(m_doc->isDirty());
    QVERIFY(m_window->windowTitle().contains(QStringLiteral("ctrl_s.json")));

    m_window->activateWindow();
    QTRY_VERIFY(m_window->isActiveWindow());
    QTest::keyClick(m_window.get(), Qt::Key_S, Qt::ControlModifier);
    QVERIFY(!m_doc->isDirty());
    QFile saved(path);
    QVERIFY(saved.open(QIODevice::ReadOnly));
    QVERIFY(saved.readAll().contains("\"spot\""));

    // Dirty again; closing asks, Cancel keeps the window and the edit.
    chooseRig(find<QComboBox>(QStringLiteral("sceneLightRig")), "sun");
    answerNextMessageBox(QMessageBox::Cancel);
    QVERIFY(!m_window->close());
    QVERIFY(m_window->isVisible());
    QVERIFY(m_doc->isDirty());
    QCOMPARE(m_doc->scene().lights[0].name, std::string("Sun"));
}

void TestUiScene::reloadKeyAsksAndRestoresFile() {
    const QString path = m_dir.filePath(QStringLiteral("reload.json"));
    QString error;
    QVERIFY2(m_doc->saveAs(path, &error), qPrintable(error));
    chooseRig(find<QComboBox>(QStringLiteral("sceneLightRig")), "sun");
    // R with unsaved changes asks; Cancel keeps them.
    m_window->activateWindow();
    QTRY_VERIFY(m_window->isActiveWindow());
    answerNextMessageBox(QMessageBox::Cancel);
    QTest::keyClick(m_window.get(), Qt::Key_R);
    QCOMPARE(m_doc->scene().lights[0].name, std::string("Sun"));
    // Discard reads the file again.
    answerNextMessageBox(QMessageBox::Discard);
    QTest::keyClick(m_window.get(), Qt::Key_R);
    QCOMPARE(matchingLightRig(m_doc->scene().lights).value_or(""), std::string_view("key"));
    QVERIFY(!m_doc->isDirty());
}

void TestUiScene::statusBarShowsFrameTime() {
    auto* label = find<QLabel>(QStringLiteral("frameTime"));
    QVERIFY(label);
    m_window->viewport()->requestFrame();
    QTRY_VERIFY(
        QRegularExpression(QStringLiteral("^Frame \\d+\\.\\d ms")).match(label->text()).hasMatch());
}

void TestUiScene::libraryListsFabricsFirst() {
    QListView* view = m_window->libraryPanel()->view();
    QAbstractItemModel* model = view->model();
    QVERIFY(model->rowCount() >= 12);
    // Every fabric comes before every non-fabric.
    bool seenOther = false;
    for (int row = 0; row < model->rowCount(); ++row) {
        const QStringList tags = model->index(row, 0).data(LibraryPanel::TagsRole).toStringList();
        const bool fabric = tags.contains(QStringLiteral("fabric"));
        QVERIFY2(!(fabric && seenOther),
                 qPrintable(model->index(row, 0).data().toString() + " after a non-fabric"));
        seenOther |= !fabric;
    }
    QVERIFY(model->index(0, 0)
                .data(LibraryPanel::TagsRole)
                .toStringList()
                .contains(QStringLiteral("fabric")));
}

void TestUiScene::libraryDoubleClickAppliesAndCtrlZUndoes() {
    m_window->findChild<QDockWidget*>(QStringLiteral("libraryDock"))->raise();
    QListView* view = m_window->libraryPanel()->view();
    QAbstractItemModel* model = view->model();
    QModelIndex gold;
    for (int row = 0; row < model->rowCount(); ++row)
        if (model->index(row, 0).data().toString() == QStringLiteral("Polished gold"))
            gold = model->index(row, 0);
    QVERIFY(gold.isValid());
    view->scrollTo(gold);
    const Material velvet = m_doc->material();
    // "before" is the settled image the undo returns to.
    QVERIFY(test::drawUntilEnvironmentBaked(m_window->viewport()));
    const double before = centreLuma(viewportImage());
    const QPoint at = view->visualRect(gold).center();
    QTest::mouseClick(view->viewport(), Qt::LeftButton, Qt::NoModifier, at);
    QTest::mouseDClick(view->viewport(), Qt::LeftButton, Qt::NoModifier, at);
    QCOMPARE(m_doc->material().name, std::string("Polished gold"));
    QCOMPARE(m_doc->undoStack()->count(), 1);
    const double gilded = centreLuma(viewportImage());
    QVERIFY2(std::abs(gilded - before) > 3.0,
             qPrintable(QStringLiteral("%1 -> %2").arg(before).arg(gilded)));

    m_window->activateWindow();
    QTRY_VERIFY(m_window->isActiveWindow());
    QTest::keyClick(m_window.get(), Qt::Key_Z, Qt::ControlModifier);
    QVERIFY(m_doc->material() == velvet);
    // The frame right after an edit may be the reduced interactive one; the settled frame is A's.
    QTRY_VERIFY_WITH_TIMEOUT(std::abs(centreLuma(viewportImage()) - before) < 1.0, 10000);
}

void TestUiScene::postChainDragInWindowReordersAndRedraws() {
    // Blur then pixelate gives flat cells; pixelate then blur soft ones: the order shows.
    Scene scene = m_doc->scene();
    scene.post.effects = {makeEffect("gaussian_blur"), makeEffect("pixelate")};
    m_doc->setDocument(scene, QString());
    m_window->findChild<QDockWidget*>(QStringLiteral("postChainDock"))->raise();
    PostChainListView* list = m_window->postChainPanel()->list();
    QCOMPARE(list->model()->rowCount(), 2);
    QVERIFY(test::drawUntilEnvironmentBaked(m_window->viewport()));
    const QImage before = viewportImage();

    // The drop half of a drag of row 0 onto the lower half of row 1 (QDrag::exec's nested loop
    // is fed by the window system, which synthetic events do not reach; test_ui_panels.cpp).
    const QRect row1 = list->visualRect(list->model()->index(1, 0));
    const QPoint lowerHalf(row1.center().x(), row1.bottom() - 1);
    QMimeData* mime = list->model()->mimeData({list->model()->index(0, 0)});
    QDragEnterEvent enter(lowerHalf, Qt::MoveAction, mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(list->viewport(), &enter);
    QDragMoveEvent move(lowerHalf, Qt::MoveAction, mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(list->viewport(), &move);
    QDropEvent drop(QPointF(lowerHalf), Qt::MoveAction, mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(list->viewport(), &drop);
    delete mime;
    QCOMPARE(m_doc->scene().post.effects[0].type, std::string("pixelate"));
    QCOMPARE(m_doc->scene().post.effects[1].type, std::string("gaussian_blur"));
    QCOMPARE(m_doc->undoStack()->count(), 1);
    const QImage after = viewportImage();
    int differing = 0;
    for (int y = 0; y < after.height(); y += 2)
        for (int x = 0; x < after.width(); x += 2)
            differing += before.pixel(x, y) != after.pixel(x, y);
    QVERIFY2(differing > 100, qPrintable(QString::number(differing)));

    m_doc->undoStack()->undo();
    QCOMPARE(m_doc->scene().post.effects[0].type, std::string("gaussian_blur"));
    const QImage undone = viewportImage();
    int stillDiffering = 0;
    for (int y = 0; y < undone.height(); y += 2)
        for (int x = 0; x < undone.width(); x += 2)
            stillDiffering += before.pixel(x, y) != undone.pixel(x, y);
    QCOMPARE(stillDiffering, 0);
}

void TestUiScene::ctrlOReopensSavedDocumentEqual() {
    chooseRig(find<QComboBox>(QStringLiteral("sceneLightRig")), "softboxes");
    m_doc->editParam(ParamId::Roughness, glm::vec3(0.42f));
    const QString path = m_dir.filePath(QStringLiteral("reopen.json"));
    QString error;
    QVERIFY2(m_doc->saveAs(path, &error), qPrintable(error));
    const Scene saved = m_doc->scene();
    m_doc->newDocument();
    QVERIFY(!(m_doc->scene() == saved));

    // Ctrl+O, answered in Qt's own file dialog (no native dialog under xvfb).
    QTimer::singleShot(0, this, [path] {
        std::function<void()> answer = [&answer, path] {
            for (QWidget* w : QApplication::topLevelWidgets())
                if (auto* dialog = qobject_cast<QFileDialog*>(w); dialog && dialog->isVisible()) {
                    dialog->selectFile(path);
                    QMetaObject::invokeMethod(dialog, "accept", Qt::QueuedConnection);
                    return;
                }
            QTimer::singleShot(20, answer);
        };
        answer();
    });
    m_window->activateWindow();
    QTRY_VERIFY(m_window->isActiveWindow());
    QTest::keyClick(m_window.get(), Qt::Key_O, Qt::ControlModifier);
    QTRY_COMPARE(m_doc->filePath(), QFileInfo(path).absoluteFilePath());
    QVERIFY(m_doc->scene() == saved);
    QVERIFY(!m_doc->isDirty());
}

void TestUiScene::lightFieldsTakeDecimalsAndEditOnlyThemselves() {
    m_window->findChild<QDockWidget*>(QStringLiteral("sceneDock"))->raise();
    chooseRig(find<QComboBox>(QStringLiteral("sceneLightRig")), "stage-spot");
    m_scene->selectLight(0);
    // A direction the boxes could not show exactly (y beyond their +-1 range).
    auto lights = m_doc->scene().lights;
    lights[0].direction = {1.0f, -3.0f, 1.0f};
    m_doc->editLights(lights, QStringLiteral("Aim"));
    auto* intensity = find<QDoubleSpinBox>(QStringLiteral("lightIntensity"));
    intensity->setFocus();
    intensity->selectAll();
    QTest::keyClicks(intensity, QStringLiteral("2.5"));
    QTest::keyClick(intensity, Qt::Key_Return);
    QCOMPARE(m_doc->scene().lights[0].intensity, 2.5f);
    // Editing x of the direction leaves y and z exactly as they were.
    auto* dx = find<QDoubleSpinBox>(QStringLiteral("lightDirection.x"));
    dx->setFocus();
    dx->selectAll();
    QTest::keyClicks(dx, QStringLiteral("0.25"));
    QTest::keyClick(dx, Qt::Key_Return);
    QCOMPARE(m_doc->scene().lights[0].direction, glm::vec3(0.25f, -3.0f, 1.0f));

    // The environment's rotation box keeps an intensity beyond its own box's range.
    Environment env = m_doc->scene().environment;
    env.intensity = 123.456f;
    m_doc->editEnvironment(env, QStringLiteral("Bright"));
    auto* rotation = find<QDoubleSpinBox>(QStringLiteral("sceneEnvironmentRotation"));
    rotation->setFocus();
    rotation->selectAll();
    QTest::keyClicks(rotation, QStringLiteral("45.5"));
    QTest::keyClick(rotation, Qt::Key_Return);
    QCOMPARE(m_doc->scene().environment.rotationDeg, 45.5f);
    QCOMPARE(m_doc->scene().environment.intensity, 123.456f);
}

void TestUiScene::conesStayOrderedAndDirectionNeverZero() {
    m_window->findChild<QDockWidget*>(QStringLiteral("sceneDock"))->raise();
    chooseRig(find<QComboBox>(QStringLiteral("sceneLightRig")), "stage-spot");
    m_scene->selectLight(0);
    const Light spot = m_doc->scene().lights[0];
    QCOMPARE(spot.type, LightType::Spot);
    // The inner cone past the outer one pushes the outer along (the loader refuses inner > outer).
    find<QDoubleSpinBox>(QStringLiteral("lightInnerCone"))->setValue(40.0);
    QCOMPARE(m_doc->scene().lights[0].innerConeDeg, 40.0f);
    QCOMPARE(m_doc->scene().lights[0].outerConeDeg, 40.0f);
    find<QDoubleSpinBox>(QStringLiteral("lightOuterCone"))->setValue(10.0);
    QCOMPARE(m_doc->scene().lights[0].innerConeDeg, 10.0f);
    QCOMPARE(m_doc->scene().lights[0].outerConeDeg, 10.0f);
    // A direction of (0, 0, 0) is refused: the light keeps aiming somewhere.
    auto lights = m_doc->scene().lights;
    lights[0].direction = {0.0f, -1.0f, 0.0f};
    m_doc->editLights(lights, QStringLiteral("Aim down"));
    find<QDoubleSpinBox>(QStringLiteral("lightDirection.y"))->setValue(0.0);
    QCOMPARE(m_doc->scene().lights[0].direction, glm::vec3(0.0f, -1.0f, 0.0f));
    QCOMPARE(find<QDoubleSpinBox>(QStringLiteral("lightDirection.y"))->value(), -1.0);
    // What the panel leaves is a scene the loader takes back.
    Problems problems;
    QVERIFY(parseScene(sceneToJson(m_doc->scene()), "panel.json", {}, problems));
    QVERIFY(!problems.hasErrors());
}

void TestUiScene::discreteLightEditsAreSeparateCommands() {
    m_window->findChild<QDockWidget*>(QStringLiteral("sceneDock"))->raise();
    chooseRig(find<QComboBox>(QStringLiteral("sceneLightRig")), "softboxes");
    m_scene->selectLight(0);
    const int before = m_doc->undoStack()->count();
    auto* shape = find<QComboBox>(QStringLiteral("lightShape"));
    const int sphere = shape->findData(int(AreaShape::Sphere));
    shape->setCurrentIndex(sphere);
    emit shape->activated(sphere);
    auto* type = find<QComboBox>(QStringLiteral("lightType"));
    const int point = type->findData(int(LightType::Point));
    type->setCurrentIndex(point);
    emit type->activated(point);
    QCOMPARE(m_doc->undoStack()->count(), before + 2); // two edits, two undo steps
    m_doc->undoStack()->undo();
    QCOMPARE(m_doc->scene().lights[0].type, LightType::Area);
    QCOMPARE(m_doc->scene().lights[0].shape, AreaShape::Sphere);
    // A rename shows in the list, and selecting another light shows that light's name.
    auto* name = find<QLineEdit>(QStringLiteral("lightName"));
    name->setFocus();
    name->selectAll();
    QTest::keyClicks(name, QStringLiteral("Key box"));
    QTest::keyClick(name, Qt::Key_Return);
    QCOMPARE(m_doc->scene().lights[0].name, std::string("Key box"));
    m_scene->selectLight(1);
    QCOMPARE(name->text(), QString::fromStdString(m_doc->scene().lights[1].name));
}

void TestUiScene::repeatedSceneProblemsAreReportedOnce() {
    // 17 directional lights: the 17th is not drawn (render/renderer.h), which is reported once,
    // not again at every later edit while it stays so.
    QSignalSpy problems(m_window->viewport(), &ViewportWidget::sceneProblems);
    std::vector<Light> lights(17, lightRigLights("sun")->front());
    m_doc->editLights(lights, QStringLiteral("Many suns"));
    viewportImage();
    QCOMPARE(problems.count(), 1);
    for (float r : {0.3f, 0.4f, 0.5f}) {
        m_doc->editParam(ParamId::Roughness, glm::vec3(r));
        viewportImage();
    }
    QCOMPARE(problems.count(), 1);
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetSceneTest"));
    QApplication::setOrganizationName(QStringLiteral("VelvetTest"));
    TestUiScene test;
    return QTest::qExec(&test, argc, argv);
}
#include "test_ui_scene.moc"
