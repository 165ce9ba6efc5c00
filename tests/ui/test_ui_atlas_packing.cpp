// The material atlas (R specular, G roughness, B metallic, the seeds' packing) exported in an
// engine's channel layout (AtlasModel::exportMaterialAtlasPacked, core/channel_packing.h): the
// texels land in the channels glTF, Unreal and Unity HDRP read, the maps the atlas lacks get the
// neutral value, nothing is written for an empty atlas, and the export is no undoable edit.
#include "core/image.h"
#include "ui/document_controller.h"
#include "ui/models/atlas_model.h"

#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>

using namespace velvet;
using namespace velvet::ui;

namespace {

AtlasEntry solid(const char* name, glm::vec4 rgba) {
    AtlasEntry e;
    e.name = name;
    e.source = Image(8, 8, 4);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            float* p = e.source.at(x, y);
            p[0] = rgba.r, p[1] = rgba.g, p[2] = rgba.b, p[3] = rgba.a;
        }
    return e;
}

} // namespace

class TestUiAtlasPacking : public QObject {
    Q_OBJECT

private slots:
    void materialAtlasLandsInEngineChannels() {
        QTemporaryDir dir;
        DocumentController controller;
        AtlasModel model(&controller);
        std::vector<AtlasEntry> images;
        // specular 0.5, roughness 0.25, metallic 1 (values exact in 16-bit PNG to 1/65535).
        images.push_back(solid("srm", {0.5f, 0.25f, 1.0f, 1.0f}));
        QString error;
        QVERIFY2(model.addImages(AtlasKind::Material, std::move(images), &error),
                 qPrintable(error));
        const AtlasRegion r = model.atlas(AtlasKind::Material).entries[0].region;
        const int undo = controller.undoStack()->count();

        struct Case {
            PackLayout layout;
            const char* file;
            glm::vec4 expected; ///< rgba of a texel inside the region (a: 1 where none)
            int channels;
        } cases[] = {
            // glTF: G roughness, B metallic; R occlusion (absent: 1).
            {PackLayout::GltfMetallicRoughness, "gltf.png", {1.0f, 0.25f, 1.0f, 1.0f}, 3},
            // Unreal ORM: R occlusion, G roughness, B metallic.
            {PackLayout::UnrealOrm, "orm.exr", {1.0f, 0.25f, 1.0f, 1.0f}, 3},
            // HDRP MODS: R metallic, G occlusion, B detail mask (absent: 1), A smoothness.
            {PackLayout::HdrpMaskMap, "mask.png", {1.0f, 1.0f, 1.0f, 0.75f}, 4},
        };
        for (const Case& c : cases) {
            const QString path = dir.filePath(QString::fromLatin1(c.file));
            QVERIFY2(model.exportMaterialAtlasPacked(c.layout, path, &error), qPrintable(error));
            Image back;
            std::string message;
            QVERIFY2(readImage(path.toStdString(), back, &message), message.c_str());
            QCOMPARE(back.width, model.atlas(AtlasKind::Material).width);
            QCOMPARE(back.channels, c.channels);
            const glm::vec4 texel = back.rgba(r.x + 3, r.y + 3);
            for (int k = 0; k < c.channels; ++k)
                QVERIFY2(std::abs(texel[k] - c.expected[k]) < 1e-3f,
                         qPrintable(QStringLiteral("%1 channel %2: %3, expected %4")
                                        .arg(QLatin1String(c.file))
                                        .arg(k)
                                        .arg(double(texel[k]))
                                        .arg(double(c.expected[k]))));
        }
        QCOMPARE(controller.undoStack()->count(), undo); // exports are not edits
    }

    void emptyAtlasWritesNothing() {
        QTemporaryDir dir;
        DocumentController controller;
        AtlasModel model(&controller);
        const QString path = dir.filePath(QStringLiteral("empty.png"));
        QString error;
        QVERIFY(!model.exportMaterialAtlasPacked(PackLayout::UnrealOrm, path, &error));
        QVERIFY(error.contains(QStringLiteral("empty")));
        QVERIFY(!QFileInfo::exists(path));
    }
};

QTEST_GUILESS_MAIN(TestUiAtlasPacking)
#include "test_ui_atlas_packing.moc"
