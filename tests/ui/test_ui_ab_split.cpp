// Issue 17, items 8, 9 and 15 (the Library drop), driven through the real MainWindow under
// xvfb-run:
// - "B from preset…" opens the Library's folder, and B draws with B's own material graph: with a
//   graph on A and a plain preset as B (and the other way round), B's half of the split is the
//   image B gives alone, not B's values under A's graph;
// - B draws its own texture files: a plain B over a textured A shows no texture, a textured B
//   over a plain A shows its texture (before, B drew with A's texture slots);
// - the split draws a divider and A / B labels, the toolbar says what B is, a drag on the
//   divider moves the seam (and does not orbit), X swaps the sides;
// - a preset dragged from the Library onto the viewport is applied as one undo step; dropped on
//   B's half of the split it becomes B and the document is untouched.
#include "core/document_io.h"
#include "ui/ab_split_control.h"
#include "ui/document_controller.h"
#include "ui/library/library_panel.h"
#include "ui/main_window.h"
#include "ui/viewport_widget.h"
#include "ui_test_modal.h"
#include "ui_test_util.h"
#include "ui_test_window.h"

#include <QAbstractItemModel>
#include <QAction>
#include <QDir>
#include <QDropEvent>
#include <QFileDialog>
#include <QGuiApplication>
#include <QListView>
#include <QMenu>
#include <QMimeData>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>
#include <algorithm>
#include <cmath>

using namespace velvet;
using namespace velvet::ui;

namespace {

using test::kFrameTimeoutMs;

/// Largest channel difference of two frames over columns [x0, x1), 0..255.
int maxDiff(const QImage& a, const QImage& b, int x0, int x1) {
    int d = 0;
    for (int y = 0; y < std::min(a.height(), b.height()); ++y)
        for (int x = std::max(0, x0); x < std::min({x1, a.width(), b.width()}); ++x) {
            const QRgb p = a.pixel(x, y), q = b.pixel(x, y);
            d = std::max({d, std::abs(qRed(p) - qRed(q)), std::abs(qGreen(p) - qGreen(q)),
                          std::abs(qBlue(p) - qBlue(q))});
        }
    return d;
}

QString preset(const char* name) {
    return AbSplitControl::presetFolder() + QLatin1Char('/') + QLatin1String(name);
}

/// A drag of @p mime entering, moving over and dropped on @p target at @p pos, as
/// QGuiApplication delivers one. Whether the drop was accepted.
bool dropOn(QObject* target, QPoint pos, const QMimeData* mime) {
    QDragEnterEvent enter(pos, Qt::CopyAction, mime, Qt::LeftButton, Qt::NoModifier);
    enter.setAccepted(false);
    QCoreApplication::sendEvent(target, &enter);
    if (!enter.isAccepted())
        return false;
    QDragMoveEvent move(pos, Qt::CopyAction, mime, Qt::LeftButton, Qt::NoModifier);
    move.setDropAction(enter.dropAction());
    move.setAccepted(true);
    QCoreApplication::sendEvent(target, &move);
    QDropEvent drop(QPointF(pos), Qt::CopyAction, mime, Qt::LeftButton, Qt::NoModifier);
    drop.setAccepted(false);
    QCoreApplication::sendEvent(target, &drop);
    return drop.isAccepted();
}

} // namespace

class TestUiAbSplit : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void init();

    void bFromPresetOpensTheLibraryAndDrawsBsOwnGraph();
    void bDrawsItsOwnTextures();
    void dividerLabelsDragAndSwap();
    void libraryDropOnViewportAppliesOrSetsB();

private:
    /// A fresh frame once no graph program is being built (the frame the artist ends up seeing).
    QImage settledFrame();
    /// A click in the viewport's corner: the GL window gets the keyboard (shortcuts, Ctrl+Z).
    bool focusViewport() {
        QTest::mouseClick(glWindow(), Qt::LeftButton, Qt::NoModifier, QPoint(5, 5));
        return QTest::qWaitFor([this] { return QGuiApplication::focusWindow() == glWindow(); },
                               5000);
    }
    QWindow* glWindow() const { return m_window->viewport()->glWindow(); }

    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
};

void TestUiAbSplit::initTestCase() {
    QDir(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation)).removeRecursively();
    m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
    m_doc = m_window->controller();
    const QString up = test::showWithFirstFrame(m_window.get(), {1000, 700});
    QVERIFY2(up.isEmpty(), qPrintable(up));
    ViewportWidget* viewport = m_window->viewport();
    QTRY_VERIFY_WITH_TIMEOUT(viewport->environmentProgress() < 0.0 ||
                                 viewport->environmentProgress() >= 1.0,
                             kFrameTimeoutMs);
    viewport->setReducedResolution(false);
}

void TestUiAbSplit::cleanupTestCase() {
    m_window->setAbSplit(false);
    m_doc->newDocument();
    QVERIFY(m_window->close());
    m_window.reset();
}

void TestUiAbSplit::init() {
    m_window->setAbSplit(false);
    m_doc->newDocument();
}

QImage TestUiAbSplit::settledFrame() {
    ViewportWidget* viewport = m_window->viewport();
    QImage image = viewport->grabFramebuffer();
    QElapsedTimer clock;
    clock.start();
    const auto busy = [viewport] {
        const render::Renderer* r = viewport->renderer();
        return r && (r->graphPending() || r->textureProgress().loading > 0);
    };
    while (busy() && clock.elapsed() < kFrameTimeoutMs) {
        QTest::qWait(20);
        image = viewport->grabFramebuffer();
    }
    return viewport->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
}

void TestUiAbSplit::bFromPresetOpensTheLibraryAndDrawsBsOwnGraph() {
    LibraryPanel* library = m_window->libraryPanel();
    QString error;
    // Gold alone (no graph), then denim alone (a woven graph feeding base colour and more).
    QVERIFY2(library->applyPreset(preset("gold.json"), &error), qPrintable(error));
    QVERIFY(!m_doc->material().graph);
    const QImage gold = settledFrame();
    QVERIFY2(library->applyPreset(preset("denim.json"), &error), qPrintable(error));
    QVERIFY(m_doc->material().graph);
    const QImage denim = settledFrame();
    const int w = denim.width(), half = w / 2;
    QVERIFY2(maxDiff(gold, denim, half + 2, w) > 20, "gold and denim must look different");

    // A = denim, B = gold through the A/B menu; the dialog opens in the Library's folder.
    auto* presetAction = m_window->findChild<QAction*>(QStringLiteral("abPresetAction"));
    QVERIFY(presetAction);
    QString openedIn;
    test::onNextModal<QFileDialog>([&openedIn](QFileDialog* dialog) {
        openedIn = QDir::cleanPath(dialog->directory().absolutePath());
        dialog->selectFile(preset("gold.json"));
        QMetaObject::invokeMethod(dialog, "accept", Qt::QueuedConnection);
    });
    presetAction->trigger();
    QCOMPARE(openedIn, QDir(AbSplitControl::presetFolder()).canonicalPath());
    QVERIFY(m_window->abSplitAction()->isChecked());
    QVERIFY(m_window->abSplitAction()->text().contains(QStringLiteral("gold")));
    const QImage split = settledFrame();
    QVERIFY2(maxDiff(denim, split, 0, half - 2) <= 2, "the left half must stay A (denim)");
    const int bError = maxDiff(gold, split, half + 2, w);
    QVERIFY2(bError <= 2, qPrintable(QStringLiteral("B's half must be gold alone, not gold under "
                                                    "denim's graph (off by %1)")
                                         .arg(bError)));

    // The other way round: A = gold (undo the preset), B = denim with its graph.
    QVERIFY(focusViewport());
    QTest::keyClick(glWindow(), Qt::Key_Z, Qt::ControlModifier);
    QTRY_VERIFY(!m_doc->material().graph);
    QVERIFY(m_window->setAbSplitPreset(preset("denim.json")));
    const QImage reversed = settledFrame();
    QVERIFY2(maxDiff(gold, reversed, 0, half - 2) <= 2, "the left half must stay A (gold)");
    const int reversedError = maxDiff(denim, reversed, half + 2, w);
    QVERIFY2(
        reversedError <= 2,
        qPrintable(
            QStringLiteral("B's half must draw denim's graph (off by %1)").arg(reversedError)));
}

void TestUiAbSplit::bDrawsItsOwnTextures() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    // A flat blue base-colour map: unmistakable against gold.
    const QString png = dir.filePath(QStringLiteral("blue.png"));
    QImage blue(16, 16, QImage::Format_RGB32);
    blue.fill(QColor(30, 60, 220));
    QVERIFY(blue.save(png));

    LibraryPanel* library = m_window->libraryPanel();
    QString error;
    QVERIFY2(library->applyPreset(preset("gold.json"), &error), qPrintable(error));
    const QImage gold = settledFrame();
    // The image dropped on the window fills A's base colour (one undo step).
    QVERIFY(test::dropFile(m_window.get(), m_window->rect().center(), png));
    QCOMPARE(QString::fromStdString(m_doc->material().texture(TextureSlot::BaseColor).file),
             QFileInfo(png).absoluteFilePath());
    QTRY_VERIFY_WITH_TIMEOUT(maxDiff(gold, settledFrame(), 0, gold.width()) > 40, kFrameTimeoutMs);
    const QImage blueGold = settledFrame();
    const int w = gold.width(), half = w / 2;
    QVERIFY2(maxDiff(gold, blueGold, half + 2, w) > 40, "the map must show on A");
    // The textured material as a preset of its own, for the reverse case.
    const QString texturedPreset = dir.filePath(QStringLiteral("blue_gold.json"));
    std::string saveError;
    QVERIFY2(saveMaterialFile(m_doc->material(), texturedPreset.toStdString(), &saveError),
             saveError.c_str());

    // A textured, B = plain gold: B's half is gold alone, not gold's values over A's map.
    QVERIFY(m_window->setAbSplitPreset(preset("gold.json")));
    const QImage split = settledFrame();
    QVERIFY2(maxDiff(blueGold, split, 0, half - 2) <= 2, "the left half must stay A (textured)");
    const int plainError = maxDiff(gold, split, half + 2, w);
    QVERIFY2(plainError <= 2,
             qPrintable(QStringLiteral("B has no texture: its half must be plain gold (off by %1)")
                            .arg(plainError)));

    // A plain (the drop undone), B = the textured preset: B's half shows B's map.
    m_window->setAbSplit(false);
    QVERIFY(focusViewport());
    QTest::keyClick(glWindow(), Qt::Key_Z, Qt::ControlModifier);
    QTRY_VERIFY(m_doc->material().texture(TextureSlot::BaseColor).empty());
    QVERIFY(m_window->setAbSplitPreset(texturedPreset));
    const QImage reversed = settledFrame();
    QVERIFY2(maxDiff(gold, reversed, 0, half - 2) <= 2, "the left half must stay A (plain gold)");
    const int texturedError = maxDiff(blueGold, reversed, half + 2, w);
    QVERIFY2(texturedError <= 2,
             qPrintable(
                 QStringLiteral("B's half must show B's own map (off by %1)").arg(texturedError)));
}

void TestUiAbSplit::dividerLabelsDragAndSwap() {
    ViewportWidget* viewport = m_window->viewport();
    m_doc->editParam(ParamId::Roughness, glm::vec3(0.9f));
    const QImage a = settledFrame();
    const int undoCount = m_doc->undoStack()->count();

    // "A/B" alone: B is a snapshot, and the toolbar and the label say so; the divider shows.
    QTest::mouseClick(m_window->findChild<QToolButton*>(QStringLiteral("abSplitButton")),
                      Qt::LeftButton, Qt::NoModifier, QPoint(8, 8));
    QVERIFY(m_window->abSplitAction()->isChecked());
    QVERIFY(m_window->abSplitAction()->text().contains(QStringLiteral("snapshot")));
    QVERIFY(viewport->splitLabel().contains(QStringLiteral("snapshot")));
    const QImage plain = settledFrame();
    QVERIFY2(maxDiff(a, plain, 0, plain.width()) <= 1, "A == B: the frame itself is unchanged");
    const QImage decorated = viewport->grabDecorated().convertToFormat(QImage::Format_RGB32);
    const int seam = viewport->splitSeamX();
    QVERIFY(std::abs(seam - plain.width() / 2) <= 1);
    for (int y : {plain.height() / 4, plain.height() / 2, 3 * plain.height() / 4}) {
        QVERIFY2(qGray(decorated.pixel(seam, y)) >= 200,
                 qPrintable(QStringLiteral("no divider at (%1, %2)").arg(seam).arg(y)));
    }
    QVERIFY2(maxDiff(plain, decorated, 0, seam - 20) > 50, "A's label must be drawn");
    QVERIFY2(maxDiff(plain, decorated, seam + 20, plain.width()) > 50, "B's label must be drawn");

    // Another B, then a drag on the divider: the seam follows the mouse, the view does not orbit.
    Material b = m_doc->material();
    b.setValue(ParamId::Roughness, glm::vec3(0.1f));
    m_window->setAbSplit(true, b);
    const Camera before = viewport->viewCamera();
    const int y = glWindow()->height() / 3;
    QTest::mousePress(glWindow(), Qt::LeftButton, Qt::NoModifier, QPoint(seam + 2, y));
    for (int x = seam; x >= glWindow()->width() / 4; x -= 20)
        QTest::mouseMove(glWindow(), QPoint(x, y));
    QTest::mouseMove(glWindow(), QPoint(glWindow()->width() / 4, y));
    QTest::mouseRelease(glWindow(), Qt::LeftButton, Qt::NoModifier,
                        QPoint(glWindow()->width() / 4, y));
    QVERIFY2(std::abs(viewport->splitPosition() - 0.25f) < 0.02f,
             qPrintable(QString::number(viewport->splitPosition())));
    QCOMPARE(viewport->viewCamera().yawDeg, before.yawDeg);
    QCOMPARE(viewport->viewCamera().pitchDeg, before.pitchDeg);
    const QImage moved = settledFrame();
    const int quarter = viewport->splitSeamX();
    QVERIFY2(maxDiff(a, moved, 0, quarter - 2) <= 1, "left of the moved seam: A");
    QVERIFY2(maxDiff(a, moved, quarter + 2, moved.width()) > 20, "right of it: B");

    // X swaps: B left, A right (the seam back in the middle, over the sphere).
    viewport->setSplitPosition(0.5f);
    const int middle = viewport->splitSeamX();
    QVERIFY(focusViewport());
    QTest::keyClick(glWindow(), Qt::Key_X);
    QVERIFY(viewport->splitSwapped());
    const QImage swapped = settledFrame();
    QVERIFY2(maxDiff(a, swapped, middle + 2, swapped.width()) <= 1, "swapped: A on the right");
    QVERIFY2(maxDiff(a, swapped, 0, middle - 2) > 20, "swapped: B on the left");
    QVERIFY(viewport->isOnSplitB(middle - 5) && !viewport->isOnSplitB(middle + 5));
    QTest::keyClick(glWindow(), Qt::Key_X);
    QVERIFY(!viewport->splitSwapped());

    // What B is, in the toolbar: a BRDF term, a preset.
    m_window->setAbSplitTerm(ParamId::Distribution, int(Distribution::Beckmann));
    QVERIFY2(
        m_window->abSplitAction()->text().contains(QStringLiteral("Beckmann"), Qt::CaseInsensitive),
        qPrintable(m_window->abSplitAction()->text()));
    QVERIFY(m_window->setAbSplitPreset(preset("copper.json")));
    QVERIFY(m_window->abSplitAction()->text().contains(QStringLiteral("copper")));
    QCOMPARE(m_doc->undoStack()->count(), undoCount); // all of it view state
    viewport->setSplitPosition(0.5f);
    m_window->setAbSplit(false);
    QCOMPARE(m_window->abSplitAction()->text(), QStringLiteral("A/B"));
}

void TestUiAbSplit::libraryDropOnViewportAppliesOrSetsB() {
    ViewportWidget* viewport = m_window->viewport();
    LibraryPanel* library = m_window->libraryPanel();
    // What a drag out of the Library carries: the preset file's URL.
    QAbstractItemModel* model = library->view()->model();
    QModelIndex index;
    for (int r = 0; r < model->rowCount() && !index.isValid(); ++r)
        if (model->index(r, 0).data(LibraryPanel::PathRole).toString().endsWith("gold.json"))
            index = model->index(r, 0);
    QVERIFY(index.isValid());
    QVERIFY(model->flags(index) & Qt::ItemIsDragEnabled);
    QVERIFY(library->view()->dragEnabled());
    std::unique_ptr<QMimeData> mime(model->mimeData({index}));
    QVERIFY(mime && mime->hasUrls());
    QCOMPARE(mime->urls().value(0).toLocalFile(), index.data(LibraryPanel::PathRole).toString());
    Problems problems;
    const std::optional<Material> gold =
        loadMaterialFile(mime->urls().value(0).toLocalFile().toStdString(), problems);
    QVERIFY(gold);

    // Dropped on the viewport: applied, one undo step; Ctrl+Z takes it back.
    const Material before = m_doc->material();
    const int step = m_doc->undoStack()->index();
    const QPoint centre(glWindow()->width() / 2, glWindow()->height() / 2);
    QVERIFY(dropOn(glWindow(), centre, mime.get()));
    QCOMPARE(m_doc->material().color(ParamId::BaseColor), gold->color(ParamId::BaseColor));
    QCOMPARE(m_doc->undoStack()->index(), step + 1);
    QVERIFY(focusViewport());
    QTest::keyClick(glWindow(), Qt::Key_Z, Qt::ControlModifier);
    QVERIFY(m_doc->material() == before);

    // With the split on: dropped on B's half it becomes B, the document is untouched...
    m_window->setAbSplit(true);
    const QPoint right(glWindow()->width() * 3 / 4, glWindow()->height() / 2);
    QVERIFY(dropOn(glWindow(), right, mime.get()));
    QVERIFY(viewport->splitMaterial().has_value());
    QCOMPARE(viewport->splitMaterial()->color(ParamId::BaseColor), gold->color(ParamId::BaseColor));
    QVERIFY(m_doc->material() == before);
    QCOMPARE(m_doc->undoStack()->index(), step);
    QVERIFY(m_window->abSplitAction()->text().contains(QStringLiteral("gold")));
    // ...and on A's half it is applied to the document.
    const QPoint left(glWindow()->width() / 4, glWindow()->height() / 2);
    QVERIFY(dropOn(glWindow(), left, mime.get()));
    QCOMPARE(m_doc->material().color(ParamId::BaseColor), gold->color(ParamId::BaseColor));
    QCOMPARE(m_doc->undoStack()->index(), step + 1);
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetAbSplitTest"));
    TestUiAbSplit test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_ui_ab_split.moc"
