// The Atlas panel, the viewport's A/B split and reduced resolution, autosave and recovery, driven
// through the real MainWindow under xvfb-run (issue 5): two added images get regions that do not
// overlap; a mouse drag moves a region in one undo command and undo restores it; assigning a
// region to base colour puts it in the document's TextureRef; with A/B on, the right half shows
// B (differs when B has another roughness, equal when A == B); slider-like edit streams draw at
// reduced size and refine when idle; the dock layout (Atlas included) restores; save, reopen,
// equal; a region dragged with the mouse survives save and reopen (the atlases are saved beside
// the scene); the autosave is written and recovered; a drag of a region's corner handle resizes
// it in one undo command.
#include "core/document_io.h"
#include "core/image.h"
#include "ui/atlas/atlas_panel.h"
#include "ui/atlas/atlas_view.h"
#include "ui/autosave.h"
#include "ui/document_controller.h"
#include "ui/main_window.h"
#include "ui/models/atlas_model.h"
#include "ui/viewport_widget.h"
#include "ui_test_util.h"

#include <QAction>
#include <QApplication>
#include <QDockWidget>
#include <QFile>
#include <QFileInfo>
#include <QMenu>
#include <QMouseEvent>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
#include <filesystem>

using namespace velvet;
using namespace velvet::ui;
using velvet::test::kFrameTimeoutMs;

namespace {

AtlasEntry solid(const QString& name, int w, int h, glm::vec4 colour) {
    AtlasEntry e;
    e.name = name.toStdString();
    e.source = Image(w, h, 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = e.source.at(x, y);
            p[0] = colour.r, p[1] = colour.g, p[2] = colour.b, p[3] = colour.a;
        }
    return e;
}

bool overlaps(const AtlasRegion& a, const AtlasRegion& b, int pad) {
    return a.x - pad < b.x + b.width + pad && b.x - pad < a.x + a.width + pad &&
           a.y - pad < b.y + b.height + pad && b.y - pad < a.y + a.height + pad;
}

/// Largest per-channel difference (0..255) between two images over columns [x0, x1).
int maxDiff(const QImage& a, const QImage& b, int x0, int x1) {
    int d = 0;
    for (int y = 0; y < std::min(a.height(), b.height()); ++y)
        for (int x = x0; x < x1; ++x) {
            const QRgb p = a.pixel(x, y), q = b.pixel(x, y);
            d = std::max({d, std::abs(qRed(p) - qRed(q)), std::abs(qGreen(p) - qGreen(q)),
                          std::abs(qBlue(p) - qBlue(q))});
        }
    return d;
}

void sendMouse(QWidget* w, QEvent::Type type, QPoint pos, Qt::MouseButton button,
               Qt::MouseButtons buttons) {
    QMouseEvent e(type, QPointF(pos), w->mapToGlobal(QPointF(pos)), button, buttons,
                  Qt::NoModifier);
    QApplication::sendEvent(w, &e);
}

bool copyTree(const QString& from, const QString& to) {
    std::error_code ec;
    std::filesystem::copy(from.toStdString(), to.toStdString(),
                          std::filesystem::copy_options::recursive, ec);
    return !ec;
}

} // namespace

class TestUiAtlasAb : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void cleanupTestCase();
    void init();

    void addTwoImagesRegionsDoNotOverlap();
    void dragMovesRegionInOneUndoCommand();
    void assignRegionToBaseColour();
    void channelIsolationAndExport();
    void abSplitShowsBOnTheRight();
    void abSplitComparesBrdfTerms();
    void editStreamRendersReducedThenRefines();
    void dockLayoutRestores();
    void saveReopenEqual();
    void regionDragSurvivesSaveAndReopen();
    void autosaveWritesAndRecovers();
    void cornerDragResizesRegionInOneUndoCommand();

private:
    QImage frame();

    QTemporaryDir m_dir;
    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
};

void TestUiAtlasAb::initTestCase() {
    QVERIFY(m_dir.isValid());
    const QString copy = m_dir.filePath(QStringLiteral("resources"));
    QVERIFY(copyTree(QStringLiteral(VELVET_SOURCE_DIR "/resources"), copy));
    qputenv("VELVET_RESOURCES", copy.toUtf8());
    QDir(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation)).removeRecursively();

    m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
    m_doc = m_window->controller();
    const QString up = test::showWithFirstFrame(m_window.get(), {1000, 700});
    QVERIFY2(up.isEmpty(), qPrintable(up));
    ViewportWidget* viewport = m_window->viewport();
    // The environment bake runs in slices: wait for the finished lighting.
    QTRY_VERIFY_WITH_TIMEOUT(viewport->environmentProgress() < 0.0 ||
                                 viewport->environmentProgress() >= 1.0,
                             kFrameTimeoutMs);
    // The Atlas dock is tabbed behind Properties: bring it to the front for the mouse tests.
    auto* dock = m_window->findChild<QDockWidget*>(QStringLiteral("atlasDock"));
    QVERIFY(dock);
    dock->show();
    dock->raise();
    QTRY_VERIFY(m_window->atlasPanel()->view()->isVisible());
}

void TestUiAtlasAb::cleanupTestCase() {
    m_doc->newDocument();
    QVERIFY(m_window->close());
    m_window.reset();
}

void TestUiAtlasAb::init() {
    m_doc->newDocument();
    m_window->setAbSplit(false);
}

QImage TestUiAtlasAb::frame() {
    // grabFramebuffer renders a fresh frame at full size.
    return m_window->viewport()->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
}

void TestUiAtlasAb::addTwoImagesRegionsDoNotOverlap() {
    AtlasModel* model = m_window->atlasPanel()->model();
    std::vector<AtlasEntry> images;
    images.push_back(solid(QStringLiteral("red"), 24, 16, {1, 0, 0, 1}));
    images.push_back(solid(QStringLiteral("green"), 16, 20, {0, 1, 0, 1}));
    const int before = m_doc->undoStack()->count();
    QString error;
    QVERIFY2(model->addImages(AtlasKind::Albedo, std::move(images), &error), qPrintable(error));
    QCOMPARE(m_doc->undoStack()->count(), before + 1);
    const AtlasDocument& a = model->atlas(AtlasKind::Albedo);
    QCOMPARE(int(a.entries.size()), 2);
    const AtlasRegion r0 = a.entries[0].region, r1 = a.entries[1].region;
    QVERIFY(!overlaps(r0, r1, a.padding)); // not even their padding touches
    for (const AtlasRegion& r : {r0, r1})
        QVERIFY(r.x >= 0 && r.y >= 0 && r.x + r.width <= a.width && r.y + r.height <= a.height);
    QCOMPARE(r0.width, 24);
    QCOMPARE(r1.height, 20);
    // The composed atlas holds each image's pixels in its region.
    QCOMPARE(a.image.rgba(r0.x + 1, r0.y + 1), glm::vec4(1, 0, 0, 1));
    QCOMPARE(a.image.rgba(r1.x + 1, r1.y + 1), glm::vec4(0, 1, 0, 1));
    // The view draws it.
    QCOMPARE(m_window->atlasPanel()->view()->displayedImage().size(), QSize(a.width, a.height));
}

void TestUiAtlasAb::dragMovesRegionInOneUndoCommand() {
    AtlasPanel* panel = m_window->atlasPanel();
    AtlasModel* model = panel->model();
    if (model->atlas(AtlasKind::Albedo).entries.empty()) {
        std::vector<AtlasEntry> images;
        images.push_back(solid(QStringLiteral("red"), 24, 16, {1, 0, 0, 1}));
        images.push_back(solid(QStringLiteral("green"), 16, 20, {0, 1, 0, 1}));
        QVERIFY(model->addImages(AtlasKind::Albedo, std::move(images), nullptr));
    }
    panel->setCurrentKind(AtlasKind::Albedo);
    AtlasView* view = panel->view();
    const AtlasDocument& a = model->atlas(AtlasKind::Albedo);
    const AtlasRegion start = a.entries[0].region;
    // Move towards whichever side has room.
    const int dx = start.x + start.width + 6 <= a.width ? 5 : -5;
    const int dy = start.y + start.height + 6 <= a.height ? 4 : -4;
    const QPointF grab(start.x + start.width * 0.4, start.y + start.height * 0.4);
    QWidget* vp = view->viewport();
    const int before = m_doc->undoStack()->count();
    sendMouse(vp, QEvent::MouseButtonPress, view->viewPosition(grab), Qt::LeftButton,
              Qt::LeftButton);
    QCOMPARE(view->selectedRegion(), 0);
    for (int step = 1; step <= 5; ++step)
        sendMouse(vp, QEvent::MouseMove,
                  view->viewPosition(grab + QPointF(dx * step / 5.0, dy * step / 5.0)),
                  Qt::NoButton, Qt::LeftButton);
    sendMouse(vp, QEvent::MouseButtonRelease, view->viewPosition(grab + QPointF(dx, dy)),
              Qt::LeftButton, Qt::NoButton);
    const AtlasRegion moved = model->atlas(AtlasKind::Albedo).entries[0].region;
    QVERIFY2(std::abs(moved.x - (start.x + dx)) <= 1 && std::abs(moved.y - (start.y + dy)) <= 1,
             qPrintable(QStringLiteral("moved to %1,%2 from %3,%4")
                            .arg(moved.x)
                            .arg(moved.y)
                            .arg(start.x)
                            .arg(start.y)));
    QCOMPARE(moved.width, start.width);
    QCOMPARE(m_doc->undoStack()->count(), before + 1); // five moves, one command
    m_doc->undoStack()->undo();
    QCOMPARE(model->atlas(AtlasKind::Albedo).entries[0].region, start);
    m_doc->undoStack()->redo();
    QCOMPARE(model->atlas(AtlasKind::Albedo).entries[0].region, moved);
}

void TestUiAtlasAb::assignRegionToBaseColour() {
    AtlasPanel* panel = m_window->atlasPanel();
    AtlasModel* model = panel->model();
    std::vector<AtlasEntry> images;
    images.push_back(solid(QStringLiteral("blue"), 16, 16, {0, 0, 1, 1}));
    QVERIFY(model->addImages(AtlasKind::Albedo, std::move(images), nullptr));
    panel->setCurrentKind(AtlasKind::Albedo);
    const int last = int(model->atlas(AtlasKind::Albedo).entries.size()) - 1;
    panel->view()->setSelectedRegion(last);
    QString error;
    QVERIFY2(panel->assignSelected(TextureSlot::BaseColor, &error), qPrintable(error));
    const TextureRef& ref = m_doc->material().texture(TextureSlot::BaseColor);
    QVERIFY(ref.useRegion);
    QCOMPARE(ref.region, model->atlas(AtlasKind::Albedo).entries[size_t(last)].region);
    QVERIFY(QFileInfo::exists(QString::fromStdString(ref.file)));
    QCOMPARE(ref.file, model->atlas(AtlasKind::Albedo).filePath);
    QVERIFY(m_doc->isDirty());
    m_doc->undoStack()->undo();
    QVERIFY(m_doc->material().texture(TextureSlot::BaseColor).empty());
}

void TestUiAtlasAb::channelIsolationAndExport() {
    AtlasPanel* panel = m_window->atlasPanel();
    AtlasModel* model = panel->model();
    std::vector<AtlasEntry> images;
    images.push_back(solid(QStringLiteral("orm"), 16, 16, {0.5f, 0.25f, 1.0f, 1.0f}));
    QVERIFY(model->addImages(AtlasKind::Material, std::move(images), nullptr));
    panel->setCurrentKind(AtlasKind::Material);
    const AtlasRegion r = model->atlas(AtlasKind::Material).entries[0].region;
    panel->view()->setChannel(AtlasView::Green); // roughness
    QCOMPARE(qRed(panel->view()->displayedImage().pixel(r.x + 2, r.y + 2)), 64);
    panel->view()->setChannel(AtlasView::AllChannels);
    const QString out = m_dir.filePath(QStringLiteral("material_atlas.exr"));
    QString error;
    QVERIFY2(model->exportAtlas(AtlasKind::Material, out, &error), qPrintable(error));
    Image back;
    std::string message;
    QVERIFY2(readImage(out.toStdString(), back, &message), message.c_str());
    QCOMPARE(back.width, model->atlas(AtlasKind::Material).width);
    QCOMPARE(back.rgba(r.x + 1, r.y + 1).y, 0.25f);
}

void TestUiAtlasAb::abSplitShowsBOnTheRight() {
    ViewportWidget* viewport = m_window->viewport();
    viewport->setReducedResolution(false);
    m_doc->editParam(ParamId::Roughness, glm::vec3(0.9f));
    const QImage single = frame();
    const int w = single.width(), half = w / 2;

    // A == B: the split image is the single one.
    m_window->setAbSplit(true);
    QVERIFY(m_window->abSplitAction()->isChecked());
    const QImage same = frame();
    QVERIFY2(maxDiff(single, same, 0, w) <= 1, "A == B must draw the unsplit image");

    // B with another roughness: the right half changes, the left does not.
    Material b = m_doc->material();
    b.setValue(ParamId::Roughness, glm::vec3(0.1f));
    m_window->setAbSplit(true, b);
    const QImage split = frame();
    QVERIFY2(maxDiff(single, split, 0, half - 2) <= 1, "the left half must stay A");
    QVERIFY2(maxDiff(single, split, half + 2, w) > 20, "the right half must show B");

    m_window->setAbSplit(false);
    QVERIFY(!m_window->abSplitAction()->isChecked());
    QVERIFY(maxDiff(single, frame(), 0, w) <= 1);
    viewport->setReducedResolution(true);
}

void TestUiAtlasAb::abSplitComparesBrdfTerms() {
    ViewportWidget* viewport = m_window->viewport();
    viewport->setReducedResolution(false);
    m_doc->editParam(ParamId::Roughness, glm::vec3(0.35f));
    const QImage single = frame();
    const int w = single.width(), half = w / 2;
    const int undoCount = m_doc->undoStack()->count();

    // The A/B button's menu: B = A with Beckmann instead of GGX, picked as an artist does.
    auto* termMenu = m_window->findChild<QMenu*>(QStringLiteral("abTermMenu"));
    QVERIFY(termMenu);
    QAction* beckmann = nullptr;
    for (QAction* sub : termMenu->actions())
        if (sub->menu() && sub->text().startsWith(QStringLiteral("Distribution")))
            for (QAction* a : sub->menu()->actions())
                if (a->text().contains(QStringLiteral("Beckmann"), Qt::CaseInsensitive))
                    beckmann = a;
    QVERIFY(beckmann);
    beckmann->trigger();
    QVERIFY(m_window->abSplitAction()->isChecked());
    QVERIFY(viewport->splitMaterial().has_value());
    QCOMPARE(viewport->splitMaterial()->distribution(), Distribution::Beckmann);
    QCOMPARE(m_doc->material().distribution(), Distribution::GGX); // A untouched
    QCOMPARE(m_doc->undoStack()->count(), undoCount);              // view state, not an edit
    const QImage split = frame();
    QVERIFY2(maxDiff(single, split, 0, half - 2) <= 1, "the left half must stay A");
    QVERIFY2(maxDiff(single, split, half + 2, w) > 2, "the right half must show Beckmann");
    m_window->setAbSplit(false);
    viewport->setReducedResolution(true);
}

void TestUiAtlasAb::editStreamRendersReducedThenRefines() {
    ViewportWidget* viewport = m_window->viewport();
    viewport->setReducedResolution(true, 0.5f);
    QSignalSpy frames(viewport, &ViewportWidget::frameCompleted);
    // A slider drag: edits in quick succession, one merge key.
    for (int i = 0; i < 3; ++i)
        m_doc->editParam(ParamId::Roughness, glm::vec3(0.3f + 0.1f * float(i)), 4242);
    QTRY_VERIFY_WITH_TIMEOUT(!frames.isEmpty(), kFrameTimeoutMs);
    QCOMPARE(viewport->lastRenderScale(), 0.5f);
    // Idle: one more frame at full size.
    QTRY_COMPARE_WITH_TIMEOUT(viewport->lastRenderScale(), 1.0f, 5000);
}

void TestUiAtlasAb::dockLayoutRestores() {
    QByteArray saved;
    QRect atlasGeometry;
    {
        MainWindow first(/*restoreLayout=*/true);
        first.resize(900, 650);
        first.show();
        QVERIFY(QTest::qWaitForWindowExposed(&first));
        auto* atlas = first.findChild<QDockWidget*>(QStringLiteral("atlasDock"));
        QVERIFY(atlas);
        first.addDockWidget(Qt::LeftDockWidgetArea, atlas); // the artist moved the Atlas
        atlas->show();
        QTest::qWait(50);
        atlasGeometry = atlas->geometry();
        saved = first.saveState(MainWindow::kLayoutVersion);
        QVERIFY(first.close());
    }
    MainWindow second(/*restoreLayout=*/true);
    second.show();
    QVERIFY(QTest::qWaitForWindowExposed(&second));
    auto* atlas = second.findChild<QDockWidget*>(QStringLiteral("atlasDock"));
    QCOMPARE(second.dockWidgetArea(atlas), Qt::LeftDockWidgetArea);
    QVERIFY(atlas->isVisible());
    QTRY_COMPARE(atlas->geometry(), atlasGeometry);
    QCOMPARE(second.saveState(MainWindow::kLayoutVersion), saved);
    QVERIFY(second.close());
}

void TestUiAtlasAb::saveReopenEqual() {
    m_doc->editParam(ParamId::Roughness, glm::vec3(0.37f));
    m_doc->editParam(ParamId::Metallic, glm::vec3(1.0f));
    const QString path = m_dir.filePath(QStringLiteral("saved.json"));
    QString error;
    QVERIFY2(m_doc->saveAs(path, &error), qPrintable(error));
    QVERIFY(!m_doc->isDirty());
    const Scene saved = m_doc->scene();
    m_doc->newDocument();
    QVERIFY(!(m_doc->scene() == saved));
    QVERIFY(m_window->openFile(path));
    QCOMPARE(sceneToJson(m_doc->scene()), sceneToJson(saved));
    QCOMPARE(m_doc->material().value(ParamId::Roughness).x, 0.37f);
}

void TestUiAtlasAb::regionDragSurvivesSaveAndReopen() {
    AtlasPanel* panel = m_window->atlasPanel();
    AtlasModel* model = panel->model();
    QVERIFY(model->atlas(AtlasKind::Albedo).entries.empty()); // a new document has none
    std::vector<AtlasEntry> images;
    images.push_back(solid(QStringLiteral("blue"), 20, 12, {0, 0, 1, 1}));
    images.push_back(solid(QStringLiteral("white"), 12, 12, {1, 1, 1, 1}));
    QVERIFY(model->addImages(AtlasKind::Albedo, std::move(images), nullptr));
    panel->setCurrentKind(AtlasKind::Albedo);
    AtlasView* view = panel->view();
    const AtlasDocument& a = model->atlas(AtlasKind::Albedo);
    const AtlasRegion start = a.entries[1].region;
    const int dx = start.x + start.width + 4 <= a.width ? 3 : -3;
    const int dy = start.y + start.height + 4 <= a.height ? 2 : -2;
    const QPointF grab(start.x + start.width * 0.5, start.y + start.height * 0.5);
    QWidget* vp = view->viewport();
    sendMouse(vp, QEvent::MouseButtonPress, view->viewPosition(grab), Qt::LeftButton,
              Qt::LeftButton);
    QCOMPARE(view->selectedRegion(), 1);
    for (int step = 1; step <= 3; ++step)
        sendMouse(vp, QEvent::MouseMove,
                  view->viewPosition(grab + QPointF(dx * step / 3.0, dy * step / 3.0)),
                  Qt::NoButton, Qt::LeftButton);
    sendMouse(vp, QEvent::MouseButtonRelease, view->viewPosition(grab + QPointF(dx, dy)),
              Qt::LeftButton, Qt::NoButton);
    const AtlasDocument dragged = model->atlas(AtlasKind::Albedo);
    QVERIFY(!(dragged.entries[1].region == start));
    QVERIFY(m_doc->isDirty());

    // Save: the atlas document lands beside the scene, which names it.
    const QString path = m_dir.filePath(QStringLiteral("with-atlas.json"));
    QString error;
    QVERIFY2(m_doc->saveAs(path, &error), qPrintable(error));
    const QString atlasFile = m_dir.filePath(QStringLiteral("with-atlas.atlas.json"));
    QVERIFY(QFileInfo::exists(atlasFile));
    QCOMPARE(QString::fromStdString(m_doc->scene().atlases),
             QFileInfo(atlasFile).absoluteFilePath());

    // A new document has no atlases; reopening the scene brings the dragged region back.
    m_doc->newDocument();
    QVERIFY(model->atlas(AtlasKind::Albedo).entries.empty());
    QVERIFY(m_window->openFile(path));
    const AtlasDocument& reopened = model->atlas(AtlasKind::Albedo);
    QCOMPARE(reopened.entries.size(), size_t(2));
    QCOMPARE(reopened.entries[1].region, dragged.entries[1].region);
    QCOMPARE(reopened.entries[0].region, dragged.entries[0].region);
    QCOMPARE(reopened.entries[1].name, std::string("white"));
    QVERIFY(reopened.image.pixels == dragged.image.pixels); // composed again, the same texels
    QVERIFY(!m_doc->isDirty());
    QCOMPARE(m_doc->undoStack()->count(), 0);
    // The panel shows the reopened atlas (the region is selectable where it was dropped).
    const AtlasRegion r = reopened.entries[1].region;
    sendMouse(vp, QEvent::MouseButtonPress,
              view->viewPosition(QPointF(r.x + r.width * 0.5, r.y + r.height * 0.5)),
              Qt::LeftButton, Qt::LeftButton);
    sendMouse(vp, QEvent::MouseButtonRelease,
              view->viewPosition(QPointF(r.x + r.width * 0.5, r.y + r.height * 0.5)),
              Qt::LeftButton, Qt::NoButton);
    QCOMPARE(view->selectedRegion(), 1);
    QCOMPARE(m_doc->undoStack()->count(), 0); // a click moves nothing
}

void TestUiAtlasAb::autosaveWritesAndRecovers() {
    // A saved file, then unsaved changes: the short-interval autosave writes them.
    const QString path = m_dir.filePath(QStringLiteral("autosaved.json"));
    QVERIFY(m_doc->saveAs(path, nullptr));
    Autosave* autosave = m_window->autosave();
    QSignalSpy written(autosave, &Autosave::saved);
    autosave->setInterval(50);
    QTest::qWait(20); // the autosave must be newer than the file
    m_doc->editParam(ParamId::Roughness, glm::vec3(0.61f));
    QTRY_VERIFY_WITH_TIMEOUT(!written.isEmpty(), 5000);
    const QString file = Autosave::autosavePathFor(path);
    QCOMPARE(written.first().first().toString(), file);
    QVERIFY(QFile::exists(file));
    QVERIFY(file.startsWith(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) +
                            QStringLiteral("/autosave/")));
    autosave->setInterval(Autosave::kDefaultIntervalMs);
    const Scene edited = m_doc->scene();

    // "Crash": a new controller (as at the next start) finds and recovers it.
    DocumentController next;
    next.newDocument();
    Autosave recovery(&next);
    QString asked;
    recovery.setPrompt([&](const QString& f, const QDateTime&) {
        asked = f;
        return true;
    });
    QCOMPARE(Autosave::recoverableFor(path), file);
    QVERIFY(recovery.offerRecovery(path));
    QCOMPARE(asked, file);
    QCOMPARE(sceneToJson(next.scene()), sceneToJson(edited));
    QCOMPARE(next.filePath(), QFileInfo(path).absoluteFilePath());
    QVERIFY(next.isDirty()); // recovered work is unsaved until saved
    // Saving it makes the autosave stale: the window removes it.
    QVERIFY(m_window->saveDocument());
    QVERIFY(!QFile::exists(file));
    QVERIFY(Autosave::recoverableFor(path).isEmpty());

    // An untitled document's autosave is offered too.
    m_doc->newDocument();
    m_doc->editParam(ParamId::Metallic, glm::vec3(0.5f));
    QVERIFY(autosave->saveNow());
    QCOMPARE(Autosave::recoverableFor(QString()), Autosave::autosavePathFor(QString()));
    m_doc->undoStack()->setClean();
    autosave->discard();
    QVERIFY(Autosave::recoverableFor(QString()).isEmpty());
}

// A drag of a region's bottom-right handle resizes it by the drag, in atlas texels, keeping its
// top-left corner: one undo command for the whole drag, and undo restores the size.
void TestUiAtlasAb::cornerDragResizesRegionInOneUndoCommand() {
    AtlasPanel* panel = m_window->atlasPanel();
    AtlasModel* model = panel->model();
    std::vector<AtlasEntry> images;
    images.push_back(solid(QStringLiteral("red"), 24, 16, {1, 0, 0, 1}));
    images.push_back(solid(QStringLiteral("green"), 16, 20, {0, 1, 0, 1}));
    QVERIFY(model->addImages(AtlasKind::Albedo, std::move(images), nullptr));
    panel->setCurrentKind(AtlasKind::Albedo);
    AtlasView* view = panel->view();
    const AtlasDocument& a = model->atlas(AtlasKind::Albedo);
    const AtlasRegion start = a.entries[0].region;
    const AtlasRegion other = a.entries[1].region;
    // Grow where the atlas has room, else shrink.
    const int dw = start.x + start.width + 7 <= a.width ? 6 : -6;
    const int dh = start.y + start.height + 5 <= a.height ? 4 : -4;
    const QPointF corner(start.x + start.width, start.y + start.height);
    QWidget* vp = view->viewport();
    QUndoStack* stack = m_doc->undoStack();
    const int before = stack->count();
    sendMouse(vp, QEvent::MouseButtonPress, view->viewPosition(corner), Qt::LeftButton,
              Qt::LeftButton);
    QCOMPARE(view->selectedRegion(), 0);
    for (int step = 1; step <= 6; ++step)
        sendMouse(vp, QEvent::MouseMove,
                  view->viewPosition(corner + QPointF(dw * step / 6.0, dh * step / 6.0)),
                  Qt::NoButton, Qt::LeftButton);
    sendMouse(vp, QEvent::MouseButtonRelease, view->viewPosition(corner + QPointF(dw, dh)),
              Qt::LeftButton, Qt::NoButton);
    const AtlasRegion resized = model->atlas(AtlasKind::Albedo).entries[0].region;
    QVERIFY2(std::abs(resized.width - (start.width + dw)) <= 1 &&
                 std::abs(resized.height - (start.height + dh)) <= 1,
             qPrintable(QStringLiteral("%1 x %2 from %3 x %4 (drag %5, %6)")
                            .arg(resized.width)
                            .arg(resized.height)
                            .arg(start.width)
                            .arg(start.height)
                            .arg(dw)
                            .arg(dh)));
    QCOMPARE(resized.x, start.x); // a resize keeps the top-left corner
    QCOMPARE(resized.y, start.y);
    QCOMPARE(model->atlas(AtlasKind::Albedo).entries[1].region, other);
    QCOMPARE(stack->count(), before + 1); // six moves, one command
    QCOMPARE(stack->text(stack->index() - 1), QStringLiteral("Resize Albedo region"));
    stack->undo();
    QCOMPARE(model->atlas(AtlasKind::Albedo).entries[0].region, start);
    stack->redo();
    QCOMPARE(model->atlas(AtlasKind::Albedo).entries[0].region, resized);
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings and autosaves go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetAtlasAbTest"));
    QApplication::setOrganizationName(QStringLiteral("VelvetTest"));
    TestUiAtlasAb test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_ui_atlas_ab.moc"
