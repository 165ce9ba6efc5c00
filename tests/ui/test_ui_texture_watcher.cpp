// ui/texture_file_watcher (issue 6, live reload): the files of the material's texture slots, of
// its graph's image-texture nodes and the HDRI are watched, only while there are some, and a file
// rewritten by another program (here: by this test, to another size) is reported within a few
// polls.
#include "core/graph/graph.h"
#include "core/image.h"
#include "ui/texture_file_watcher.h"

#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>

using namespace velvet;
using namespace velvet::ui;

namespace {

bool writeFlat(const QString& path, int size, float value) {
    Image image(size, size, 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int c = 0; c < 3; ++c)
                image.at(x, y)[c] = value;
    std::string error;
    return writeImage(path.toStdString(), image, PixelFormat::UInt8, &error);
}

} // namespace

class TestUiTextureWatcher : public QObject {
    Q_OBJECT

private slots:
    void watchesSlotAndGraphFiles() {
        QTemporaryDir dir;
        const QString slotFile = dir.filePath(QStringLiteral("slot.png"));
        const QString nodeFile = dir.filePath(QStringLiteral("node.png"));
        QVERIFY(writeFlat(slotFile, 8, 0.5f));
        QVERIFY(writeFlat(nodeFile, 8, 0.5f));

        TextureFileWatcher watcher;
        Scene scene;
        watcher.setScene(scene);
        QVERIFY(watcher.files().isEmpty());
        QVERIFY(!watcher.isPolling()); // nothing to watch: no timer

        TextureRef ref;
        ref.file = slotFile.toStdString();
        scene.material.setTexture(TextureSlot::Normal, ref);
        graph::Graph g;
        const graph::EditResult added = g.addNode("texture.image");
        QVERIFY2(added.ok, added.message.c_str());
        QVERIFY(g.setSetting(added.node, "file", nodeFile.toStdString()).ok);
        scene.material.graph = SharedGraph(g);
        watcher.setScene(scene);
        QCOMPARE(watcher.files().size(), 2);
        QVERIFY(watcher.files().contains(slotFile));
        QVERIFY(watcher.files().contains(nodeFile));
        QVERIFY(watcher.isPolling());

        QSignalSpy changed(&watcher, &TextureFileWatcher::changed);
        QTest::qWait(2 * TextureFileWatcher::kPollIntervalMs);
        QCOMPARE(changed.count(), 0);            // nothing changed yet
        QVERIFY(writeFlat(nodeFile, 16, 0.25f)); // the graph's image, edited elsewhere
        QTRY_VERIFY_WITH_TIMEOUT(changed.count() >= 1, 5000);
        changed.clear();
        QVERIFY(writeFlat(slotFile, 16, 0.25f));
        QTRY_VERIFY_WITH_TIMEOUT(changed.count() >= 1, 5000);

        // The HDRI too (the renderer reads an edited one again at the next frame).
        const QString hdri = dir.filePath(QStringLiteral("sky.png"));
        QVERIFY(writeFlat(hdri, 8, 0.5f));
        Scene lit;
        lit.environment.hdri = hdri.toStdString();
        watcher.setScene(lit);
        QCOMPARE(watcher.files(), QStringList{hdri});
        changed.clear();
        QVERIFY(writeFlat(hdri, 16, 0.25f));
        QTRY_VERIFY_WITH_TIMEOUT(changed.count() >= 1, 5000);

        watcher.setScene(Scene());
        QVERIFY(!watcher.isPolling());
    }
};

QTEST_GUILESS_MAIN(TestUiTextureWatcher)
#include "test_ui_texture_watcher.moc"
