// Drives the real MainWindow under xvfb-run (issue 14, docs/shadows.md): a light's "Casts
// shadows" box, the Scene toolbar's ground toggle, the Scene panel's ground and occlusion, and
// the mesh chooser's stage defaults are undoable document edits that change the viewport. An
// orbit at full size draws the stage's masks and occlusion coarser until the mouse is released.
#include "core/scene.h"
#include "ui/document_controller.h"
#include "ui/main_window.h"
#include "ui/scene/scene_panel.h"
#include "ui/viewport_widget.h"
#include "ui_test_util.h"
#include "ui_test_window.h"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDockWidget>
#include <QStandardPaths>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>
#include <algorithm>

using namespace velvet;
using namespace velvet::ui;

class TestUiStage : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
        m_doc = m_window->controller();
        const QString up = test::showWithFirstFrame(m_window.get(), {900, 700});
        QVERIFY2(up.isEmpty(), qPrintable(up));
        m_window->findChild<QDockWidget*>(QStringLiteral("sceneDock"))->raise();
    }
    void cleanupTestCase() {
        m_doc->newDocument();
        QVERIFY(m_window->close());
        m_window.reset();
    }
    void init() { m_doc->newDocument(); }

    // The default rig's key light casts shadows; the box turns it off in one undo step.
    void castShadowsBoxIsOneUndoStep() {
        QVERIFY(m_doc->scene().lights.at(0).castShadows);
        m_window->scenePanel()->selectLight(0);
        auto* box = m_window->findChild<QCheckBox*>(QStringLiteral("lightCastShadows"));
        QVERIFY(box && box->isVisible() && box->isChecked());
        QTest::mouseClick(box, Qt::LeftButton, {}, QPoint(8, box->height() / 2));
        QVERIFY(!m_doc->scene().lights[0].castShadows);
        QCOMPARE(m_doc->undoStack()->count(), 1);
        QCOMPARE(m_doc->undoStack()->undoText(), QStringLiteral("Light casts no shadows"));
        m_doc->undoStack()->undo();
        QVERIFY(m_doc->scene().lights[0].castShadows);
        QVERIFY(box->isChecked());
    }

    // Choosing the shader ball brings its stage (a shadow catcher, occlusion) in the same step;
    // the toolbar's toggle and the panel show it, and the toggle turns the ground off, which
    // changes the viewport under the ball.
    void shaderBallStandsOnACatcher() {
        auto* mesh = m_window->findChild<QComboBox*>(QStringLiteral("sceneMesh"));
        const int index = mesh->findData(int(PreviewMeshKind::ShaderBall));
        QVERIFY(index >= 0);
        mesh->setCurrentIndex(index);
        emit mesh->activated(index);
        QCOMPARE(m_doc->scene().mesh.kind, PreviewMeshKind::ShaderBall);
        QCOMPARE(m_doc->scene().environment.ground, GroundMode::ShadowCatcher);
        QVERIFY(m_doc->scene().environment.ambientOcclusion);
        QCOMPARE(m_doc->undoStack()->count(), 1);
        auto* toggle = m_window->findChild<QToolButton*>(QStringLiteral("groundToggle"));
        QVERIFY(toggle && toggle->isChecked());
        auto* ground = m_window->findChild<QComboBox*>(QStringLiteral("sceneGround"));
        QCOMPARE(ground->currentData().toInt(), int(GroundMode::ShadowCatcher));
        QVERIFY(
            m_window->findChild<QCheckBox*>(QStringLiteral("sceneAmbientOcclusion"))->isChecked());

        // A mid-grey backdrop, so the catcher's darkening shows (the studio HDRI is dark there).
        Environment grey = m_doc->scene().environment;
        grey.background = BackgroundMode::SolidColor;
        grey.backgroundColor = glm::vec3(0.5f);
        m_doc->editEnvironment(grey, QStringLiteral("Grey backdrop"));
        const QImage withGround = m_window->viewport()->grabFramebuffer();
        QTest::mouseClick(toggle, Qt::LeftButton);
        QCOMPARE(m_doc->scene().environment.ground, GroundMode::Off);
        QCOMPARE(ground->currentData().toInt(), int(GroundMode::Off));
        const QImage without = m_window->viewport()->grabFramebuffer();
        // The ball's shadow and contact occlusion only darken: the lower half is darker with it.
        const auto lowerLuma = [](const QImage& image) {
            double sum = 0.0;
            int n = 0;
            for (int y = image.height() / 2; y < image.height(); ++y)
                for (int x = 0; x < image.width(); ++x, ++n) {
                    const QColor c = image.pixelColor(x, y);
                    sum += 0.2126 * c.red() + 0.7152 * c.green() + 0.0722 * c.blue();
                }
            return sum / std::max(n, 1);
        };
        qInfo("lower half luma with the ground %.1f, without %.1f", lowerLuma(withGround),
              lowerLuma(without));
        QVERIFY(lowerLuma(withGround) < lowerLuma(without) - 1.0);

        m_doc->undoStack()->undo(); // the ground again
        QCOMPARE(m_doc->scene().environment.ground, GroundMode::ShadowCatcher);
        m_doc->undoStack()->undo(); // the backdrop
        m_doc->undoStack()->undo(); // the sphere, and its stage: none
        QCOMPARE(m_doc->scene().mesh.kind, PreviewMeshKind::Sphere);
        QCOMPARE(m_doc->scene().environment.ground, GroundMode::Off);
        QVERIFY(!m_doc->scene().environment.ambientOcclusion);
        QVERIFY(!toggle->isChecked());
    }

    // A ground set by hand stays when the mesh changes.
    void handSetGroundSurvivesAMeshSwitch() {
        auto* ground = m_window->findChild<QComboBox*>(QStringLiteral("sceneGround"));
        const int plain = ground->findData(int(GroundMode::Plain));
        ground->setCurrentIndex(plain);
        emit ground->activated(plain);
        QCOMPARE(m_doc->scene().environment.ground, GroundMode::Plain);
        auto* mesh = m_window->findChild<QComboBox*>(QStringLiteral("sceneMesh"));
        const int drape = mesh->findData(int(PreviewMeshKind::ClothDrape));
        mesh->setCurrentIndex(drape);
        emit mesh->activated(drape);
        QCOMPARE(m_doc->scene().mesh.kind, PreviewMeshKind::ClothDrape);
        QCOMPARE(m_doc->scene().environment.ground, GroundMode::Plain);
        QVERIFY(!m_doc->scene().environment.ambientOcclusion);
    }

    // With the toolbar's "Half while moving" off, a left drag's frames are drawn at full size,
    // navigating (the stage's shadow masks and occlusion at a quarter: FrameSettings::navigating);
    // the release draws the view at rest again, at half. With it on (the default) the drag's
    // frames are reduced, coarse already, and not navigating.
    void orbitDrawsTheStageCoarserUntilReleased() {
        ViewportWidget* viewport = m_window->viewport();
        QWindow* gl = viewport->glWindow();
        auto* reducedAction =
            m_window->findChild<QAction*>(QStringLiteral("reducedWhileMovingAction"));
        QVERIFY(reducedAction && reducedAction->isChecked() &&
                viewport->reducedResolutionEnabled());
        reducedAction->trigger();
        QVERIFY(!viewport->reducedResolutionEnabled());
        const QPoint c = viewport->rect().center();
        QTest::mousePress(gl, Qt::LeftButton, Qt::NoModifier, c);
        QTest::mouseMove(gl, c + QPoint(12, 3));
        QTRY_VERIFY_WITH_TIMEOUT(viewport->lastFrameNavigating(), 5000);
        QCOMPARE(viewport->lastRenderScale(), 1.0f);
        const int frames = viewport->frameCount();
        QTest::mouseRelease(gl, Qt::LeftButton, Qt::NoModifier, c + QPoint(12, 3));
        QTRY_VERIFY_WITH_TIMEOUT(viewport->frameCount() > frames, 5000);
        QTRY_VERIFY_WITH_TIMEOUT(!viewport->lastFrameNavigating(), 5000);

        // Reduced (the default): every frame of the drag records its scale and whether it was
        // drawn navigating.
        reducedAction->trigger();
        QVERIFY(viewport->reducedResolutionEnabled());
        QList<QPair<float, bool>> drawn;
        const QMetaObject::Connection noted =
            connect(viewport, &ViewportWidget::frameCompleted, this, [&] {
                drawn.append({viewport->lastRenderScale(), viewport->lastFrameNavigating()});
            });
        QTest::mousePress(gl, Qt::LeftButton, Qt::NoModifier, c);
        for (int i = 1; i <= 4; ++i) {
            QTest::mouseMove(gl, c + QPoint(-6 * i, 2 * i));
            QTest::qWait(10);
        }
        const auto reduced = [&] {
            return std::any_of(drawn.begin(), drawn.end(),
                               [](const QPair<float, bool>& f) { return f.first < 1.0f; });
        };
        QTRY_VERIFY_WITH_TIMEOUT(reduced(), 5000);
        QTest::mouseRelease(gl, Qt::LeftButton, Qt::NoModifier, c + QPoint(-24, 8));
        QTRY_COMPARE_WITH_TIMEOUT(viewport->lastRenderScale(), 1.0f, 5000);
        disconnect(noted);
        for (const QPair<float, bool>& f : drawn)
            QVERIFY2(!(f.first < 1.0f && f.second), "a reduced frame was drawn navigating");
    }

    // A drag whose moves come slower than the refine delay (frames slower than 150 ms, as a
    // heavy stage on a loaded machine draws them) is still a drag: each move's frame is reduced,
    // and a pause under the held button draws the view at full size again.
    void aSlowDragStillDrawsReduced() {
        ViewportWidget* viewport = m_window->viewport();
        QWindow* gl = viewport->glWindow();
        QVERIFY(viewport->reducedResolutionEnabled());
        QTest::qWait(2 * ViewportWidget::kRefineDelayMs); // nothing streams into the drag
        QTRY_COMPARE_WITH_TIMEOUT(viewport->lastRenderScale(), 1.0f, 5000);
        const QPoint c = viewport->rect().center();
        QTest::mousePress(gl, Qt::LeftButton, Qt::NoModifier, c);
        for (int i = 1; i <= 2; ++i) {
            const int frames = viewport->frameCount();
            QTest::mouseMove(gl, c + QPoint(10 * i, 0));
            // The move's own frame: reduced (before, the first move after a pause was drawn at
            // full size, and with frames this far apart every one was).
            QTRY_VERIFY_WITH_TIMEOUT(viewport->frameCount() > frames, 5000);
            QVERIFY2(viewport->lastRenderScale() < 1.0f,
                     qPrintable(QStringLiteral("move %1").arg(i)));
            // Held still past the delay: the full-size view, the button still down.
            QTRY_COMPARE_WITH_TIMEOUT(viewport->lastRenderScale(), 1.0f, 5000);
        }
        QTest::mouseRelease(gl, Qt::LeftButton, Qt::NoModifier, c + QPoint(20, 0));
        QTRY_VERIFY_WITH_TIMEOUT(!viewport->lastFrameNavigating(), 5000);
    }

private:
    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
};

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetStageTest"));
    QApplication::setOrganizationName(QStringLiteral("VelvetTest"));
    TestUiStage test;
    return QTest::qExec(&test, argc, argv);
}
#include "test_ui_stage.moc"
