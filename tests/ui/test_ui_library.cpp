// The Library panel (issue 5) under xvfb-run: library presets apply as one undoable command; the
// search filters by name and tag; a user preset is saved and listed; thumbnails render in the
// background and a second panel loads them from the disk cache without rendering; `velvet
// thumbnails` writes the same pixels as the Library's (fabrics on the cloth drape).
#include "../app/run_velvet.h"
#include "core/document_io.h"
#include "core/image.h"
#include "core/post_effects.h"
#include "core/resources.h"
#include "ui/document_controller.h"
#include "ui/library/library_panel.h"
#include "ui/library/thumbnail_renderer.h"
#include "ui/main_window.h"
#include "ui/viewport_widget.h"
#include "ui_test_util.h"

#include <QApplication>
#include <QDir>
#include <QFile>
#include <QGroupBox>
#include <QLabel>
#include <QLineEdit>
#include <QListView>
#include <QMenu>
#include <QPushButton>
#include <QSignalSpy>
#include <QSortFilterProxyModel>
#include <QStandardItemModel>
#include <QStandardPaths>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>

using namespace velvet;
using namespace velvet::ui;

namespace {

constexpr int kThumbnailTimeoutMs = 180000; // llvmpipe, two shared cores, shaders compiled once

QString presetDir() {
    return QString::fromStdString(resources::path("presets").string());
}

/// True when @p image is not one flat colour (a rendered thumbnail, not the flat grey one the
/// Library shows until the render arrives: LibraryPanel::placeholderCount()).
bool hasDetail(const QImage& image) {
    const QRgb first = image.pixel(0, 0);
    for (int y = 0; y < image.height(); y += 3)
        for (int x = 0; x < image.width(); x += 3)
            if (image.pixel(x, y) != first)
                return true;
    return false;
}

} // namespace

class TestUiLibrary : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void libraryPresetAppliesAndUndoes();
    void searchFiltersByNameAndTag();
    void userPresetSavedAndListed();
    void thumbnailsRenderThenComeFromCache();

private:
    QTemporaryDir m_tmp;
};

void TestUiLibrary::initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
    QVERIFY(m_tmp.isValid());
}

void TestUiLibrary::libraryPresetAppliesAndUndoes() {
    DocumentController controller;
    controller.newDocument();
    LibraryPanel::Options options;
    options.userDir = m_tmp.filePath(QStringLiteral("user-presets-apply"));
    options.cacheDir = m_tmp.filePath(QStringLiteral("cache-apply"));
    LibraryPanel panel(&controller, options);
    QVERIFY(panel.model()->rowCount() >= 12);

    const std::string nameBefore = controller.scene().material.name;
    const float metallicBefore = controller.scene().material.scalar(ParamId::Metallic);
    const float roughnessBefore = controller.scene().material.scalar(ParamId::Roughness);
    QVERIFY(nameBefore != "Polished gold");

    // Select gold in the grid and press Apply.
    const int row = panel.rowOfName(QStringLiteral("Polished gold"));
    QVERIFY(row >= 0);
    const QModelIndex proxyIndex =
        panel.filteredModel()->mapFromSource(panel.model()->index(row, 0));
    panel.view()->setCurrentIndex(proxyIndex);
    auto* apply = panel.findChild<QPushButton*>(QStringLiteral("libraryApply"));
    QVERIFY(apply && apply->isEnabled());
    QTest::mouseClick(apply, Qt::LeftButton);
    QCOMPARE(controller.scene().material.name, std::string("Polished gold"));
    QCOMPARE(controller.scene().material.scalar(ParamId::Metallic), 1.0f);
    QCOMPARE(controller.scene().material.scalar(ParamId::Roughness), 0.2f);
    QCOMPARE(controller.undoStack()->count(), 1);

    controller.undoStack()->undo();
    QCOMPARE(controller.scene().material.name, nameBefore);
    QCOMPARE(controller.scene().material.scalar(ParamId::Metallic), metallicBefore);
    QCOMPARE(controller.scene().material.scalar(ParamId::Roughness), roughnessBefore);
    controller.undoStack()->redo();
    QCOMPARE(controller.scene().material.name, std::string("Polished gold"));
}

void TestUiLibrary::searchFiltersByNameAndTag() {
    DocumentController controller;
    LibraryPanel::Options options;
    options.userDir = m_tmp.filePath(QStringLiteral("user-presets-search"));
    options.cacheDir = m_tmp.filePath(QStringLiteral("cache-search"));
    LibraryPanel panel(&controller, options);
    const int all = panel.filteredModel()->rowCount();
    QCOMPARE(all, panel.model()->rowCount());
    QTest::keyClicks(panel.searchField(), QStringLiteral("gold"));
    QSortFilterProxyModel* proxy = panel.filteredModel();
    QVERIFY(proxy->rowCount() >= 1);
    QVERIFY(proxy->rowCount() < all);
    bool sawGold = false;
    for (int r = 0; r < proxy->rowCount(); ++r) {
        const QModelIndex index = proxy->index(r, 0);
        QVERIFY(index.data(LibraryPanel::SearchRole)
                    .toString()
                    .contains(QStringLiteral("gold"), Qt::CaseInsensitive));
        sawGold |= index.data().toString() == QStringLiteral("Polished gold");
    }
    QVERIFY(sawGold);
    QVERIFY(panel.rowOfName(QStringLiteral("Polished gold")) >= 0);

    // By tag: "metal" finds gold and copper, not velvet.
    panel.searchField()->clear();
    QTest::keyClicks(panel.searchField(), QStringLiteral("metal"));
    QStringList names;
    for (int r = 0; r < proxy->rowCount(); ++r)
        names << proxy->index(r, 0).data().toString();
    QVERIFY2(names.size() >= 2, qPrintable(names.join(QStringLiteral(", "))));
    QVERIFY(!names.join(QLatin1Char(',')).contains(QStringLiteral("elvet")));
    panel.searchField()->clear();
    QCOMPARE(proxy->rowCount(), all);
}

void TestUiLibrary::userPresetSavedAndListed() {
    DocumentController controller;
    controller.newDocument();
    controller.editParam(ParamId::Roughness, glm::vec3(0.37f));
    LibraryPanel::Options options;
    options.userDir = m_tmp.filePath(QStringLiteral("user-presets-save"));
    options.cacheDir = m_tmp.filePath(QStringLiteral("cache-save"));
    LibraryPanel panel(&controller, options);
    const int before = panel.model()->rowCount();
    QString error;
    QVERIFY2(panel.saveUserPreset(QStringLiteral("My Velvet"),
                                  {QStringLiteral("fabric"), QStringLiteral("mine")}, &error),
             qPrintable(error));
    QVERIFY(QFile::exists(options.userDir + QStringLiteral("/my_velvet.json")));
    QCOMPARE(panel.model()->rowCount(), before + 1);
    const int row = panel.rowOfName(QStringLiteral("My Velvet"));
    QVERIFY(row >= 0);
    QVERIFY(panel.model()->item(row)->data(LibraryPanel::UserPresetRole).toBool());
    QTest::keyClicks(panel.searchField(), QStringLiteral("mine"));
    QCOMPARE(panel.filteredModel()->rowCount(), 1);

    // A new panel lists it too, and applying it restores the saved roughness.
    LibraryPanel again(&controller, options);
    QCOMPARE(again.model()->rowCount(), before + 1);
    controller.editParam(ParamId::Roughness, glm::vec3(0.9f));
    QVERIFY(again.applyPreset(options.userDir + QStringLiteral("/my_velvet.json")));
    QCOMPARE(controller.scene().material.scalar(ParamId::Roughness), 0.37f);
    QCOMPARE(controller.scene().material.name, std::string("My Velvet"));
}

void TestUiLibrary::thumbnailsRenderThenComeFromCache() {
    // Two presets in their own folder keep the render time short on llvmpipe.
    const QString presets = m_tmp.filePath(QStringLiteral("thumb-presets"));
    QVERIFY(QDir().mkpath(presets));
    for (const char* name : {"gold.json", "denim.json"})
        QVERIFY(QFile::copy(presetDir() + QLatin1Char('/') + QLatin1String(name),
                            presets + QLatin1Char('/') + QLatin1String(name)));
    LibraryPanel::Options options;
    options.presetDirs = {presets};
    options.userDir = m_tmp.filePath(QStringLiteral("thumb-user"));
    options.cacheDir = m_tmp.filePath(QStringLiteral("thumb-cache"));
    DocumentController controller;

    {
        LibraryPanel panel(&controller, options);
        QCOMPARE(panel.model()->rowCount(), 2);
        QCOMPARE(panel.placeholderCount(), 2); // nothing rendered before the panel is shown
        QCOMPARE(panel.thumbnails()->renderCount(), 0);
        panel.show();
        QVERIFY(QTest::qWaitForWindowExposed(&panel));
        QTRY_COMPARE_WITH_TIMEOUT(panel.placeholderCount(), 0, kThumbnailTimeoutMs);
        QCOMPARE(panel.thumbnails()->renderCount(), 2);
        QCOMPARE(panel.thumbnails()->cacheHits(), 0);
        const QImage icon = panel.model()
                                ->item(0)
                                ->icon()
                                .pixmap(ThumbnailRenderer::kSize, ThumbnailRenderer::kSize)
                                .toImage();
        QVERIFY(hasDetail(icon));
        // Gold's thumbnail is a gold sphere: yellow at the centre, not the flat grey stand-in.
        const int goldRow = panel.rowOfName(QStringLiteral("Polished gold"));
        QVERIFY(goldRow >= 0);
        const QImage goldIcon = panel.model()
                                    ->item(goldRow)
                                    ->icon()
                                    .pixmap(ThumbnailRenderer::kSize, ThumbnailRenderer::kSize)
                                    .toImage();
        if (qEnvironmentVariableIsSet("VELVET_KEEP_THUMBNAIL"))
            goldIcon.save(qEnvironmentVariable("VELVET_KEEP_THUMBNAIL"));
        const QColor centre = goldIcon.pixelColor(goldIcon.width() / 2, goldIcon.height() / 2);
        QVERIFY2(centre.red() > centre.blue() + 20,
                 qPrintable(QStringLiteral("centre %1").arg(centre.name())));
        const QStringList cached = QDir(options.cacheDir).entryList({QStringLiteral("*.png")});
        QCOMPARE(cached.size(), 2);
        // The cache files are written through core::writeImage (OpenImageIO): 8-bit PNGs of the
        // thumbnail size, no temp file left beside them.
        QCOMPARE(QDir(options.cacheDir).entryList(QDir::Files).size(), 2);
        for (const QString& name : cached) {
            ImageInfo info;
            std::string error;
            QVERIFY2(
                readImageInfo(QDir(options.cacheDir).filePath(name).toStdString(), info, &error),
                error.c_str());
            QCOMPARE(info.format, std::string("png"));
            QCOMPARE(info.bitsPerSample, 8);
            QCOMPARE(info.width, ThumbnailRenderer::kSize);
        }
        // `velvet thumbnails` renders what the Library shows (one rule, core/default_stage.h's
        // thumbnailScene): denim's CLI thumbnail at the Library's size is its cached one, pixel
        // for pixel (both are the renderer's display-encoded frame written as an 8-bit PNG; a
        // 1/255 step is allowed for a rounding difference between the two paths).
        QFile denim(presets + QStringLiteral("/denim.json"));
        QVERIFY(denim.open(QIODevice::ReadOnly));
        Image library, cli;
        std::string error;
        QVERIFY2(readImage(panel.thumbnails()->cachePath(denim.readAll()).toStdString(), library,
                           &error),
                 error.c_str());
        const QString cliDir = m_tmp.filePath(QStringLiteral("thumb-cli"));
        test::RunOptions run;
        run.timeoutMs = kThumbnailTimeoutMs;
        const test::Result r = test::runVelvet(
            {QStringLiteral("thumbnails"), denim.fileName(), QStringLiteral("-o"), cliDir,
             QStringLiteral("--size"), QString::number(ThumbnailRenderer::kSize)},
            run);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(readImage((cliDir + QStringLiteral("/denim.png")).toStdString(), cli, &error),
                 error.c_str());
        QCOMPARE(cli.width, library.width);
        QCOMPARE(cli.height, library.height);
        float worst = 0.0f;
        double sum = 0.0;
        for (int y = 0; y < cli.height; ++y)
            for (int x = 0; x < cli.width; ++x)
                for (int c = 0; c < 3; ++c) {
                    const float d = std::abs(cli.rgba(x, y)[c] - library.rgba(x, y)[c]);
                    worst = std::max(worst, d);
                    sum += d;
                }
        const double mean = sum / (3.0 * cli.width * cli.height);
        qInfo("denim thumbnail, CLI against Library: mean |difference| %.4f, worst %.4f", mean,
              worst);
        QVERIFY2(mean < 0.5 / 255.0 && worst < 1.5f / 255.0f,
                 qPrintable(QStringLiteral("mean %1 worst %2").arg(mean).arg(worst)));
    }

    LibraryPanel second(&controller, options);
    second.show();
    QVERIFY(QTest::qWaitForWindowExposed(&second));
    QTRY_COMPARE_WITH_TIMEOUT(second.placeholderCount(), 0, 5000);
    QCOMPARE(second.thumbnails()->renderCount(), 0);
    QCOMPARE(second.thumbnails()->cacheHits(), 2);

    // A changed preset file has a new key: rendered again.
    QFile gold(presets + QStringLiteral("/gold.json"));
    QVERIFY(gold.open(QIODevice::Append));
    gold.write("\n");
    gold.close();
    second.reload();
    QTRY_COMPARE_WITH_TIMEOUT(second.placeholderCount(), 0, kThumbnailTimeoutMs);
    QCOMPARE(second.thumbnails()->renderCount(), 1);
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetTest"));
    TestUiLibrary test;
    return QTest::qExec(&test, argc, argv);
}
#include "test_ui_library.moc"
