// ScenePart masks (core/scene_parts.h): changedParts names exactly the parts two scenes differ
// in, and copyParts takes exactly the named parts, each material share on its own.
#include "core/scene.h"
#include "core/scene_parts.h"

#include <QTest>

using namespace velvet;

class TestCoreSceneParts : public QObject {
    Q_OBJECT

private slots:
    void changedPartsNamesEachPart() {
        const Scene base;
        QVERIFY(changedParts(base, base) == ScenePart::None);
        Scene s = base;
        s.camera.yawDeg += 10.0f;
        QVERIFY(changedParts(base, s) == ScenePart::Camera);
        s = base;
        s.material.setValue(ParamId::Roughness, glm::vec3(0.77f));
        QVERIFY(changedParts(base, s) == ScenePart::MaterialValues);
        s = base;
        TextureRef ref;
        ref.file = "checker.png";
        s.material.setTexture(TextureSlot::BaseColor, ref);
        QVERIFY(changedParts(base, s) == ScenePart::MaterialStructure);
        s = base;
        s.lights.push_back(Light{});
        s.mesh.kind = PreviewMeshKind::Cube;
        QVERIFY(changedParts(base, s) == (ScenePart::Lights | ScenePart::Mesh));
        s = base;
        s.environment.intensity = 3.0f;
        s.atlases = "a.atlas.json";
        QVERIFY(changedParts(base, s) == (ScenePart::Environment | ScenePart::Atlases));
    }

    void copyPartsTakesOnlyTheNamedParts() {
        Scene src;
        src.camera.yawDeg = 42.0f;
        src.material.setValue(ParamId::Roughness, glm::vec3(0.9f));
        TextureRef ref;
        ref.file = "checker.png";
        src.material.setTexture(TextureSlot::BaseColor, ref);
        src.lights.push_back(Light{});
        src.mesh.kind = PreviewMeshKind::ShaderBall;

        Scene dst;
        copyParts(dst, src, ScenePart::MaterialValues);
        QCOMPARE(dst.material.scalar(ParamId::Roughness), 0.9f);
        QVERIFY(dst.material.texture(TextureSlot::BaseColor).file.empty()); // structure kept
        QCOMPARE(dst.camera.yawDeg, Scene{}.camera.yawDeg);
        QVERIFY(dst.lights.empty());
        QVERIFY(dst.mesh.kind == PreviewMeshKind::Sphere);

        copyParts(dst, src, ScenePart::MaterialStructure | ScenePart::Lights);
        QCOMPARE(dst.material.texture(TextureSlot::BaseColor).file, std::string("checker.png"));
        QCOMPARE(dst.lights.size(), size_t(1));
        QVERIFY(dst.mesh.kind == PreviewMeshKind::Sphere);

        copyParts(dst, src, ScenePart::All);
        QVERIFY(dst == src);
        QVERIFY(changedParts(dst, src) == ScenePart::None);
    }
};

QTEST_APPLESS_MAIN(TestCoreSceneParts)
#include "test_core_scene_parts.moc"
