// File > Export… through the real MainWindow under xvfb-run: Ctrl+E opens Qt's save dialog, the
// chosen filter picks the way out (glTF binary by default, MaterialX per shader node, preset),
// the extension is added when the name has none, warnings and the result reach the Log, and a
// target that cannot be written is refused with a message naming it, leaving the document as it
// was (still dirty, its history intact); a node graph is baked to textures as the CLI bakes it.
#include "core/document_io.h"
#include "core/image.h"
#include "core/material.h"
#include "ui/document_controller.h"
#include "ui/export_action.h"
#include "ui/log_panel.h"
#include "ui/main_window.h"
#include "ui/texture_set_dialog.h"
#include "ui/viewport_widget.h"
#include "ui_test_modal.h"
#include "ui_test_window.h"

#include <QComboBox>
#include <QDir>
#include <QFile>
#include <QInputDialog>
#include <QMessageBox>
#include <QSettings>
#include <QSpinBox>
#include <QStandardPaths>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>

using namespace velvet;
using namespace velvet::ui;

class TestUiExport : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        QVERIFY(m_dir.isValid());
        QSettings().remove(QStringLiteral("export/lastDir"));
        QSettings().remove(QStringLiteral("export/lastFilter"));
        QSettings().remove(QStringLiteral("export/textureSet"));
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

    void ctrlEExportsGlbByDefault() {
        m_doc->editParam(ParamId::Roughness, glm::vec3(0.6f));
        const QString path = m_dir.filePath(QStringLiteral("look"));
        test::answerFileDialog(path);
        pressCtrlE();
        QVERIFY(QTest::qWaitFor([&] { return QFile::exists(path + ".glb"); }, 30000));
        QFile glb(path + ".glb");
        QVERIFY(glb.open(QIODevice::ReadOnly));
        QCOMPARE(glb.read(4), QByteArray("glTF")); // the GLB header's magic (glTF 2.0, 4.4)
        QVERIFY(m_window->logPanel()->text().contains(QStringLiteral("Exported")));
        QVERIFY(m_doc->isDirty()); // an export is not a save
        QCOMPARE(m_doc->undoStack()->count(), 1);
    }

    void filterChoosesMaterialXShader() {
        const QStringList filters = exportFilters();
        const QString openPbr = filters.filter(QStringLiteral("open_pbr_surface")).value(0);
        QVERIFY(!openPbr.isEmpty());
        const QString path = m_dir.filePath(QStringLiteral("look_openpbr"));
        test::answerFileDialog(path, openPbr);
        pressCtrlE();
        QVERIFY2(QTest::qWaitFor([&] { return QFile::exists(path + ".mtlx"); }, 30000),
                 qPrintable(QDir(m_dir.path()).entryList(QDir::Files).join(' ') + " | " +
                            m_window->logPanel()->text()));
        QFile mtlx(path + ".mtlx");
        QVERIFY(mtlx.open(QIODevice::ReadOnly));
        const QByteArray xml = mtlx.readAll();
        QVERIFY(xml.contains("<open_pbr_surface"));
        QVERIFY(!xml.contains("<standard_surface"));
    }

    // A texture set for Unreal from the dialog: the settings dialog offers the CLI's defaults
    // (1024 px, PNG, 8 bits, the engine's normals); the maps are baked (on a worker thread, with
    // a busy dialog) into T_NAME_D / _N / _ORM beside the manifest the dialog named; the dialog
    // offers the same way out first next time.
    void filterChoosesTextureSet() {
        const QString unreal = exportFilters().filter(QStringLiteral("Unreal")).value(0);
        QVERIFY(!unreal.isEmpty());
        QCOMPARE(exportFilters().filter(QStringLiteral("Texture set")).size(), 4);
        m_doc->editParam(ParamId::Metallic, glm::vec3(1.0f));
        const QString path = m_dir.filePath(QStringLiteral("engine"));
        test::answerFileDialog(path, unreal);
        TextureSetOptions shown;
        test::onNextModal<TextureSetDialog>([&shown](TextureSetDialog* d) {
            shown = d->options();
            d->accept();
        });
        pressCtrlE();
        const QString manifest = path + QStringLiteral("_texture_set.json");
        QVERIFY2(QTest::qWaitFor([&] { return QFile::exists(manifest); }, 60000),
                 qPrintable(QDir(m_dir.path()).entryList(QDir::Files).join(' ') + " | " +
                            m_window->logPanel()->text()));
        for (const char* file : {"T_engine_D.png", "T_engine_N.png", "T_engine_ORM.png"})
            QVERIFY2(QFile::exists(m_dir.filePath(QString::fromLatin1(file))), file);
        QFile f(manifest);
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QByteArray json = f.readAll();
        QVERIFY(json.contains("\"target\": \"unreal\""));
        QVERIFY(json.contains("\"normalConvention\": \"directx\""));
        // The flat maps hold the document's values: metallic 1 in the ORM's blue channel.
        Image orm;
        std::string error;
        QVERIFY2(readImage(m_dir.filePath(QStringLiteral("T_engine_ORM.png")).toStdString(), orm,
                           &error),
                 error.c_str());
        QCOMPARE(orm.at(orm.width / 2, orm.height / 2)[2], 1.0f);
        QCOMPARE(orm.width, 1024); // the CLI's defaults, as the dialog showed them
        QCOMPARE(shown.size, 1024);
        QCOMPARE(shown.fileType, TextureFileType::Png);
        QCOMPARE(shown.bits, 8);
        QVERIFY(!shown.normal);
        QCOMPARE(shown.target, TextureSetTarget::Unreal);
        QVERIFY(m_window->logPanel()->text().contains(QStringLiteral("T_engine")) ||
                m_window->logPanel()->text().contains(QStringLiteral("engine_texture_set")));
        QCOMPARE(QSettings().value(QStringLiteral("export/lastFilter")).toString(), unreal);
        QSettings().remove(QStringLiteral("export/lastFilter"));
    }

    // The settings chosen in the dialog reach the files: 64 px, 16-bit PNG, OpenGL normals for
    // Unreal (replacing its DirectX default). The dialog offers them again next time, and
    // cancelling it exports nothing.
    void textureSetSettingsReachTheFiles() {
        const QString unrealFilter = exportFilters().filter(QStringLiteral("Unreal")).value(0);
        const QString path = m_dir.filePath(QStringLiteral("small"));
        test::answerFileDialog(path, unrealFilter);
        test::onNextModal<TextureSetDialog>([](TextureSetDialog* d) {
            d->sizeBox()->setValue(64);
            d->typeBox()->setCurrentIndex(d->typeBox()->findText(QStringLiteral("PNG")));
            QCOMPARE(d->bitsBox()->count(), 2); // PNG holds 8 or 16
            d->bitsBox()->setCurrentIndex(d->bitsBox()->findData(16));
            d->normalBox()->setCurrentIndex(d->normalBox()->findData(QStringLiteral("opengl")));
            d->accept();
        });
        pressCtrlE();
        const QString manifest = path + QStringLiteral("_texture_set.json");
        QVERIFY2(QTest::qWaitFor([&] { return QFile::exists(manifest); }, 60000),
                 qPrintable(m_window->logPanel()->text()));
        for (const char* file : {"T_small_D.png", "T_small_N.png", "T_small_ORM.png"}) {
            ImageInfo info;
            std::string error;
            QVERIFY2(readImageInfo(m_dir.filePath(QString::fromLatin1(file)).toStdString(), info,
                                   &error),
                     error.c_str());
            QCOMPARE(info.width, 64);
            QCOMPARE(info.height, 64);
            QCOMPARE(info.bitsPerSample, 16);
        }
        QFile f(manifest);
        QVERIFY(f.open(QIODevice::ReadOnly));
        QVERIFY(f.readAll().contains("\"normalConvention\": \"opengl\""));

        // Remembered: the next texture set starts from them (TGA offers 8 bits only).
        TextureSetDialog again(TextureSetTarget::Godot);
        QCOMPARE(again.options().size, 64);
        QCOMPARE(again.options().bits, 16);
        QCOMPARE(again.options().normal, std::optional(NormalConvention::OpenGl));
        again.typeBox()->setCurrentIndex(again.typeBox()->findText(QStringLiteral("TGA")));
        QCOMPARE(again.bitsBox()->count(), 1);
        QCOMPARE(again.options().bits, 8);
        QVERIFY(checkTextureSetOptions(again.options()).empty());

        // Cancelled: nothing is written.
        const QString cancelled = m_dir.filePath(QStringLiteral("cancelled"));
        test::answerFileDialog(cancelled, unrealFilter);
        bool asked = false;
        test::onNextModal<TextureSetDialog>([&asked](TextureSetDialog* d) {
            asked = true;
            d->reject();
        });
        pressCtrlE();
        QVERIFY(QTest::qWaitFor([&] { return asked; }, 30000));
        QTest::qWait(200);
        QVERIFY(!QFile::exists(cancelled + QStringLiteral("_texture_set.json")));
        QSettings().remove(QStringLiteral("export/lastFilter"));
    }

    void unwritableTargetIsRefusedWithItsName() {
        // A regular file where the export's folder should be.
        const QString blocker = m_dir.filePath(QStringLiteral("blocker"));
        QFile f(blocker);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("x");
        f.close();
        const int history = m_doc->undoStack()->count();
        QString error;
        QVERIFY(!exportDocument(*m_doc, blocker + "/inside.glb", exportFilters().front(),
                                m_window->logPanel(), &error));
        QVERIFY2(error.contains(QStringLiteral("blocker")), qPrintable(error));
        QVERIFY(!QFile::exists(blocker + "/inside.glb"));
        QCOMPARE(m_doc->undoStack()->count(), history);
        QVERIFY(m_doc->isDirty());

        // The same through the dialog: a message box says it, the Log keeps it.
        bool boxShown = false;
        test::onNextModal<QMessageBox>([&boxShown](QMessageBox* box) {
            boxShown = box->text().contains(QStringLiteral("blocker"));
            box->accept();
        });
        test::answerFileDialog(blocker + "/inside.glb");
        pressCtrlE();
        QVERIFY(QTest::qWaitFor([&] { return boxShown; }, 30000));
        QVERIFY(m_window->logPanel()->text().contains(QStringLiteral("Export failed")));
    }

    /// File > Export… bakes what the graph drives, as `velvet export` does (the same
    /// render::exportMaterialBaked, on a worker thread): denim's base colour, ORM and normal.
    void graphIsBakedLikeTheCli() {
        Problems problems;
        const auto denim =
            loadMaterialFile(VELVET_SOURCE_DIR "/resources/presets/denim.json", problems);
        QVERIFY(denim && denim->graph);
        m_doc->setMaterial(*denim, "denim");
        const QString path = m_dir.filePath(QStringLiteral("graph/denim.gltf"));
        QString error;
        QVERIFY2(exportDocument(*m_doc, path, QString(), m_window->logPanel(), &error),
                 qPrintable(error));
        for (const char* map : {"baseColor", "orm", "normal"}) {
            ImageInfo info;
            std::string why;
            const QString image =
                m_dir.filePath(QStringLiteral("graph/denim_baked_%1.png").arg(map));
            QVERIFY2(readImageInfo(image.toStdString(), info, &why), why.c_str());
            QCOMPARE(info.width, 1024); // the CLI's default --bake-size
        }
        QFile gltf(path);
        QVERIFY(gltf.open(QIODevice::ReadOnly));
        QVERIFY(gltf.readAll().contains("denim_baked_baseColor.png"));
        QVERIFY(!m_window->logPanel()->text().contains(QStringLiteral("graph:")));
    }

    // Through Ctrl+E the bake size is asked for (a graph, glTF) and reaches the files.
    void bakeSizeIsAskedForAGraph() {
        Problems problems;
        const auto denim =
            loadMaterialFile(VELVET_SOURCE_DIR "/resources/presets/denim.json", problems);
        QVERIFY(denim && denim->graph);
        m_doc->setMaterial(*denim, "denim");
        const QString glbFilter = exportFilters().filter(QStringLiteral(".glb")).value(0);
        QVERIFY(!glbFilter.isEmpty());
        const QString path = m_dir.filePath(QStringLiteral("asked/denim.glb"));
        QVERIFY(QDir().mkpath(m_dir.filePath(QStringLiteral("asked"))));
        test::answerFileDialog(path, glbFilter);
        bool asked = false;
        test::onNextModal<QInputDialog>([&asked](QInputDialog* d) {
            asked = true;
            d->setIntValue(48);
            d->accept();
        });
        pressCtrlE();
        QVERIFY2(QTest::qWaitFor([&] { return QFile::exists(path); }, 60000),
                 qPrintable(m_window->logPanel()->text()));
        QVERIFY(asked);
        QFile glb(path);
        QVERIFY(glb.open(QIODevice::ReadOnly));
        const QByteArray bytes = glb.readAll();
        // The embedded PNGs' IHDR: width and height 48 (big-endian after "IHDR").
        const QByteArray ihdr48 = QByteArray("IHDR") + QByteArray::fromHex("0000003000000030");
        QVERIFY2(bytes.contains(ihdr48), "the baked maps must be 48 x 48");
        QCOMPARE(QSettings().value(QStringLiteral("export/lastBakeSize")).toInt(), 48);
    }

private:
    /// Ctrl+E as the artist presses it, on the active window (a closed dialog leaves Xvfb, which
    /// has no window manager, without an active window).
    void pressCtrlE() {
        QVERIFY(test::activate(m_window.get()));
        QTest::keyClick(m_window.get(), Qt::Key_E, Qt::ControlModifier);
    }

    QTemporaryDir m_dir;
    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
};

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetExportTest"));
    QApplication::setOrganizationName(QStringLiteral("VelvetTest"));
    TestUiExport test;
    return QTest::qExec(&test, argc, argv);
}
#include "test_ui_export.moc"
