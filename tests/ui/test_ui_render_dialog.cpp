// File > Render… through the real MainWindow under xvfb-run (issue 14): F12 opens the dialog, the
// artist types a size unlike the window's, and the still is written at that size with the pixels
// `velvet render`'s code (render::runRenderJob) gives for the same scene and view; a turntable
// reports its frames in a progress dialog whose Cancel stops it, keeping the frames written; a
// bad pattern is refused in the dialog, which stays open.
#include "core/default_stage.h"
#include "core/image.h"
#include "render/render_job.h"
#include "ui/document_controller.h"
#include "ui/log_panel.h"
#include "ui/main_window.h"
#include "ui/render_dialog.h"
#include "ui/viewport_widget.h"
#include "ui_test_modal.h"
#include "ui_test_window.h"

#include <QComboBox>
#include <QDir>
#include <QDockWidget>
#include <QLineEdit>
#include <QMessageBox>
#include <QProgressDialog>
#include <QPushButton>
#include <QSettings>
#include <QSpinBox>
#include <QStandardPaths>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
#include <glm/common.hpp>
#include <thread>

using namespace velvet;
using namespace velvet::ui;

namespace {

/// Replaces the text of @p widget (a spin box or a line edit) as typed: select all, then type.
void retype(QWidget* widget, const QString& text) {
    widget->setFocus();
    QTest::keyClick(widget, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(widget, text);
}

} // namespace

class TestUiRenderDialog : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        QVERIFY(m_dir.isValid());
        QSettings().remove(QStringLiteral("render")); // the last render's fields, from a run before
        m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
        m_doc = m_window->controller();
        const QString error = test::showWithFirstFrame(m_window.get(), QSize(1000, 700));
        QVERIFY2(error.isEmpty(), qPrintable(error));
    }
    void cleanupTestCase() {
        // A clean document: the HDRI case leaves edits, and closing a dirty window asks to save
        // (a modal dialog nobody answers under xvfb: the test hung until ctest's timeout).
        m_doc->newDocument();
        QVERIFY(m_window->close());
        m_window.reset();
    }

    void stillAtItsOwnSizeMatchesTheCli() {
        const QString out = m_dir.filePath(QStringLiteral("still.png"));
        bool answered = false;
        test::onNextModal<RenderDialog>([&](RenderDialog* dialog) {
            retype(dialog->findChild<QSpinBox*>(QStringLiteral("renderWidth")), "320");
            retype(dialog->findChild<QSpinBox*>(QStringLiteral("renderHeight")), "180");
            retype(dialog->findChild<QSpinBox*>(QStringLiteral("renderFrames")), "1");
            retype(dialog->findChild<QLineEdit*>(QStringLiteral("renderOutput")), out);
            // What leaves the editor is anti-aliased by default: 2x2 samples a pixel.
            auto* supersample = dialog->findChild<QComboBox*>(QStringLiteral("renderSupersample"));
            QVERIFY(supersample);
            QCOMPARE(supersample->currentData().toInt(), 2);
            answered = true;
            QTest::mouseClick(dialog->findChild<QPushButton*>(QStringLiteral("renderStart")),
                              Qt::LeftButton);
        });
        pressF12();
        QVERIFY(answered);
        QVERIFY(QTest::qWaitFor([&] { return QFile::exists(out); }, 120000));
        Image image;
        std::string error;
        QVERIFY2(readImage(out.toStdString(), image, &error), error.c_str());
        QCOMPARE(image.width, 320);
        QCOMPARE(image.height, 180);
        QVERIFY(m_window->viewport()->width() != 320);
        QVERIFY2(m_window->logPanel()->text().contains(QStringLiteral("Rendered")),
                 qPrintable(m_window->logPanel()->text()));

        // The same job through render::runRenderJob, as `velvet render --supersample 2` runs
        // it, on a thread of its own (its own headless context).
        render::RenderJob job;
        job.settings = m_window->viewport()->frameSettings();
        job.settings.camera = m_window->viewport()->viewCamera();
        job.settings.width = 320;
        job.settings.height = 180;
        job.supersample = 2;
        job.output = m_dir.filePath(QStringLiteral("reference.png")).toStdString();
        render::RenderJobStatus status = render::RenderJobStatus::Failed;
        std::thread cli([&] { status = render::runRenderJob(m_doc->scene(), job, {}, &error); });
        cli.join();
        QVERIFY2(status == render::RenderJobStatus::Done, error.c_str());
        Image reference;
        QVERIFY2(readImage(job.output, reference, &error), error.c_str());
        float worst = 0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                const glm::vec4 d = glm::abs(image.rgba(x, y) - reference.rgba(x, y));
                worst = std::max({worst, d.r, d.g, d.b});
            }
        QVERIFY2(worst <= 1.0f / 255.0f, qPrintable(QString::number(worst)));
    }

    void badPatternIsRefusedInTheDialog() {
        bool refused = false, stayedOpen = false;
        test::onNextModal<RenderDialog>([&](RenderDialog* dialog) {
            retype(dialog->findChild<QSpinBox*>(QStringLiteral("renderFrames")), "3");
            retype(dialog->findChild<QLineEdit*>(QStringLiteral("renderOutput")),
                   m_dir.filePath(QStringLiteral("turn_%s.png")));
            test::onNextModal<QMessageBox>([&, dialog](QMessageBox* box) {
                refused = box->text().contains(QStringLiteral("%0Nd"));
                box->accept();
                QTimer::singleShot(50, dialog, [&, dialog] {
                    stayedOpen = dialog->isVisible();
                    dialog->reject();
                });
            });
            QTest::mouseClick(dialog->findChild<QPushButton*>(QStringLiteral("renderStart")),
                              Qt::LeftButton);
        });
        pressF12();
        QVERIFY(QTest::qWaitFor([&] { return stayedOpen; }, 10000));
        QVERIFY(refused);
        QVERIFY(QDir(m_dir.path()).entryList({"turn_*"}, QDir::Files).isEmpty());
    }

    void turntableProgressCanBeCancelled() {
        const QString pattern = m_dir.filePath(QStringLiteral("spin_%03d.png"));
        int seenValue = -1;
        test::onNextModal<RenderDialog>([&](RenderDialog* dialog) {
            retype(dialog->findChild<QSpinBox*>(QStringLiteral("renderWidth")), "48");
            retype(dialog->findChild<QSpinBox*>(QStringLiteral("renderHeight")), "48");
            retype(dialog->findChild<QSpinBox*>(QStringLiteral("renderFrames")), "500");
            auto* mode = dialog->findChild<QComboBox*>(QStringLiteral("renderMode"));
            mode->setCurrentIndex(1); // the HDRI and the lights turn
            retype(dialog->findChild<QLineEdit*>(QStringLiteral("renderOutput")), pattern);
            // Cancel once two frames are reported.
            test::onNextModal<QProgressDialog>([&](QProgressDialog* progress) {
                QVERIFY(QTest::qWaitFor([&] { return progress->value() >= 2; }, 120000));
                seenValue = progress->value();
                QVERIFY(progress->labelText().contains(QStringLiteral("of 500")));
                QTest::mouseClick(progress->findChild<QPushButton*>(), Qt::LeftButton);
            });
            QTest::mouseClick(dialog->findChild<QPushButton*>(QStringLiteral("renderStart")),
                              Qt::LeftButton);
        });
        pressF12(); // returns once the job has stopped
        QVERIFY(seenValue >= 2);
        const int written = QDir(m_dir.path()).entryList({"spin_*.png"}, QDir::Files).size();
        qInfo("cancelled after %d of 500 frames", written);
        QVERIFY(written >= 2 && written < 500);
        QVERIFY(QFile::exists(m_dir.filePath(QStringLiteral("spin_000.png"))));
        QVERIFY2(m_window->logPanel()->text().contains(QStringLiteral("cancelled")),
                 qPrintable(m_window->logPanel()->text()));
    }

    // A new document is the look-dev stage; choosing another HDRI in the Scene panel gives it
    // its own default rotation (core/default_stage.h), one undo step with the HDRI.
    void choosingAnHdriAppliesItsDefaultRotation() {
        m_doc->newDocument();
        QCOMPARE(m_doc->scene().environment.background, BackgroundMode::Blurred);
        auto* combo = m_window->findChild<QComboBox*>(QStringLiteral("sceneHdri"));
        QVERIFY(combo);
        m_window->findChild<QDockWidget*>(QStringLiteral("sceneDock"))->raise();
        const int city = combo->findText(QStringLiteral("city"));
        QVERIFY(city >= 0);
        const auto expected =
            hdriDefaultRotationDeg(combo->itemData(city).toString().toStdString());
        QVERIFY(expected);
        QVERIFY(*expected != m_doc->scene().environment.rotationDeg);
        const int steps = m_doc->undoStack()->count();
        combo->setCurrentIndex(city);
        emit combo->activated(city); // what a click on the item does (as test_ui_scene)
        QVERIFY(m_doc->scene().environment.hdri.find("city") != std::string::npos);
        QCOMPARE(m_doc->scene().environment.rotationDeg, *expected);
        QCOMPARE(m_doc->undoStack()->count(), steps + 1);
    }

private:
    /// F12 as the artist presses it, on the active window.
    void pressF12() {
        QVERIFY(test::activate(m_window.get()));
        QTest::keyClick(m_window.get(), Qt::Key_F12);
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
    QApplication::setApplicationName(QStringLiteral("VelvetRenderDialogTest"));
    QApplication::setOrganizationName(QStringLiteral("VelvetTest"));
    TestUiRenderDialog test;
    return QTest::qExec(&test, argc, argv);
}
#include "test_ui_render_dialog.moc"
