// File > Import… (Ctrl+I), drops of .mtlx / .gltf on the main window (issue 12, "Import") and a
// texture slot's UV transform in Properties (issue 17 item 6), through the real MainWindow
// under xvfb-run: a file with two materials lists them and the chosen one is applied as one
// undo step, a malformed file is refused with its place in the Log and the document untouched,
// a dropped MaterialX file is applied, and typing a UV offset is one undo step.
#include "core/image.h"
#include "core/material.h"
#include "core/material_export.h"
#include "ui/document_controller.h"
#include "ui/log_panel.h"
#include "ui/main_window.h"
#include "ui/viewport_widget.h"
#include "ui_test_modal.h"
#include "ui_test_window.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFile>
#include <QInputDialog>
#include <QLineEdit>
#include <QMessageBox>
#include <QMimeData>
#include <QStandardPaths>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
#include <QUrl>

using namespace velvet;
using namespace velvet::ui;

namespace {

QString write(const QString& path, const QByteArray& text) {
    QFile f(path);
    if (!f.open(QIODevice::WriteOnly))
        qFatal("cannot write %s", qPrintable(path));
    f.write(text);
    return path;
}

/// A file drop on @p target as QGuiApplication delivers it: enter, move, drop.
bool dropFile(QWidget* target, const QString& file) {
    QMimeData mime;
    mime.setUrls({QUrl::fromLocalFile(file)});
    const QPoint pos = target->rect().center();
    QDragEnterEvent enter(pos, Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    enter.setAccepted(false);
    QCoreApplication::sendEvent(target, &enter);
    if (!enter.isAccepted())
        return false;
    QDropEvent drop(QPointF(pos), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    drop.setAccepted(false);
    QCoreApplication::sendEvent(target, &drop);
    return drop.isAccepted();
}

} // namespace

class TestUiImport : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        QVERIFY(m_dir.isValid());
        m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
        m_doc = m_window->controller();
        const QString error = test::showWithFirstFrame(m_window.get(), QSize(1280, 800));
        QVERIFY2(error.isEmpty(), qPrintable(error));
    }
    void cleanupTestCase() {
        m_doc->newDocument();
        m_window->close();
        m_window.reset();
    }

    void fileImportListsMaterialsAndUndoes() {
        const QString file = write(m_dir.filePath("two.gltf"), R"({"asset": {"version": "2.0"},
          "materials": [{"name": "first", "pbrMetallicRoughness": {"metallicFactor": 0.1}},
                        {"name": "second", "pbrMetallicRoughness": {"metallicFactor": 0.9,
                         "roughnessFactor": 0.3}}]})");
        const Material before = m_doc->material();
        const int history = m_doc->undoStack()->count();
        QStringList offered;
        test::onNextModal<QInputDialog>([&offered](QInputDialog* dialog) {
            offered = dialog->comboBoxItems();
            dialog->setTextValue(offered.value(1));
            dialog->accept();
        });
        test::answerFileDialog(file);
        QVERIFY(test::activate(m_window.get()));
        QTest::keyClick(m_window.get(), Qt::Key_I, Qt::ControlModifier);
        QVERIFY(QTest::qWaitFor([&] { return m_doc->material().name == "second"; }, 30000));
        QCOMPARE(offered, (QStringList{"0: first", "1: second"}));
        QCOMPARE(m_doc->material().scalar(ParamId::Metallic), 0.9f);
        QCOMPARE(m_doc->undoStack()->count(), history + 1); // one step
        m_doc->undoStack()->undo();
        QVERIFY(m_doc->material() == before);
        m_doc->undoStack()->redo();
        QCOMPARE(m_doc->material().scalar(ParamId::Roughness), 0.3f);
    }

    void malformedFileIsRefusedWithItsPlace() {
        const QString file = write(
            m_dir.filePath("bad.gltf"),
            R"({"asset": {"version": "2.0"}, "materials": [{"normalTexture": {"index": 4}}]})");
        const Material before = m_doc->material();
        const int history = m_doc->undoStack()->count();
        bool boxShown = false;
        test::onNextModal<QMessageBox>([&boxShown](QMessageBox* box) {
            boxShown = box->text().contains(QStringLiteral("materials[0].normalTexture.index"));
            box->accept();
        });
        test::answerFileDialog(file);
        QVERIFY(test::activate(m_window.get()));
        QTest::keyClick(m_window.get(), Qt::Key_I, Qt::ControlModifier);
        QVERIFY(QTest::qWaitFor([&] { return boxShown; }, 30000));
        QVERIFY(m_window->logPanel()->text().contains(QStringLiteral("bad.gltf")));
        QCOMPARE(m_doc->undoStack()->count(), history);
        QVERIFY(m_doc->material() == before);
    }

    void droppedMaterialXIsApplied() {
        const QString file = write(m_dir.filePath("drop.mtlx"), R"(<?xml version="1.0"?>
<materialx version="1.39">
  <standard_surface name="SR" type="surfaceshader">
    <input name="base_color" type="color3" value="0.2, 0.4, 0.6" />
    <input name="coat" type="float" value="0.75" />
    <input name="thin_film_thickness" type="float" value="500" />
  </standard_surface>
  <surfacematerial name="Dropped" type="material">
    <input name="surfaceshader" type="surfaceshader" nodename="SR" />
  </surfacematerial>
</materialx>
)");
        const int history = m_doc->undoStack()->count();
        QVERIFY(dropFile(m_window.get(), file));
        QCOMPARE(QString::fromStdString(m_doc->material().name), QStringLiteral("Dropped"));
        QVERIFY(m_doc->material().color(ParamId::BaseColor) == glm::vec3(0.2f, 0.4f, 0.6f));
        QCOMPARE(m_doc->material().scalar(ParamId::ClearcoatWeight), 0.75f);
        QCOMPARE(m_doc->undoStack()->count(), history + 1);
        // What was not mapped is in the Log, by name.
        QVERIFY(m_window->logPanel()->text().contains(QStringLiteral("thin_film_thickness")));
    }

    void droppedGlbBringsMaterialAndMeshInOneStep() {
        Scene scene;
        scene.material.name = "Exported";
        scene.material.setScalar(ParamId::Metallic, 0.75f);
        scene.mesh.kind = PreviewMeshKind::Cube;
        const ExportOutcome exported =
            exportMaterial(scene, m_dir.filePath("glb").toStdString(), "cube", ExportOptions{});
        QVERIFY2(exported.ok(), exported.error.c_str());
        const QString glb = QString::fromStdString(exported.written.back().string());
        const Scene before = m_doc->scene();
        const int history = m_doc->undoStack()->count();
        QVERIFY(dropFile(m_window.get(), glb));
        QCOMPARE(m_doc->material().scalar(ParamId::Metallic), 0.75f);
        QCOMPARE(m_doc->scene().mesh.kind, PreviewMeshKind::Custom);
        QCOMPARE(QString::fromStdString(m_doc->scene().mesh.file), glb);
        QCOMPARE(m_doc->undoStack()->count(), history + 1);
        m_doc->undoStack()->undo(); // material and mesh together
        QVERIFY(m_doc->material() == before.material);
        QVERIFY(m_doc->scene().mesh == before.mesh);
    }

    void typedUvOffsetIsOneUndoStep() {
        Image img(4, 4, 3);
        std::string error;
        const QString png = m_dir.filePath("c.png");
        QVERIFY(writeImage(png.toStdString(), img, PixelFormat::UInt8, &error));
        TextureRef ref;
        ref.file = png.toStdString();
        m_doc->editTexture(TextureSlot::BaseColor, ref, QStringLiteral("Set"));
        auto* box =
            m_window->findChild<QDoubleSpinBox*>(QStringLiteral("textureSlot:baseColor/uvOffsetU"));
        QVERIFY(box);
        QVERIFY(QTest::qWaitFor([&] { return box->isEnabled(); }, 5000));
        const int history = m_doc->undoStack()->count();
        QVERIFY(test::activate(m_window.get()));
        box->setFocus();
        box->selectAll();
        QTest::keyClicks(box, QStringLiteral("0.25"));
        QCOMPARE(m_doc->undoStack()->count(), history); // no command per keystroke
        QTest::keyClick(box, Qt::Key_Return);
        QCOMPARE(m_doc->material().texture(TextureSlot::BaseColor).uv.offset.x, 0.25f);
        QCOMPARE(m_doc->undoStack()->count(), history + 1);
        m_doc->undoStack()->undo();
        QCOMPARE(m_doc->material().texture(TextureSlot::BaseColor).uv.offset.x, 0.0f);
        QCOMPARE(box->value(), 0.0); // the editor shows the undone value
    }

private:
    QTemporaryDir m_dir;
    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
};

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(
        true); // QSettings and imported images go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetImportTest"));
    QApplication::setOrganizationName(QStringLiteral("VelvetTest"));
    TestUiImport test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_ui_import.moc"
