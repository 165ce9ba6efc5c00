// The undo commands that set one value share one merge rule (ui/commands/value_edit_command.h):
// the commands of one drag (same kind, same non-zero merge key, same target) merge into one, a
// drag back to where it began leaves nothing on the stack, and a key of 0, another key, another
// target or another kind of command never merges. Each command kind is checked, so a command
// that stops using the shared rule, or names its target wrongly, fails here.
#include "ui/models/atlas_model.h"
#include "ui/commands/atlas_commands.h"
#include "ui/commands/graph_commands.h"
#include "ui/commands/post_chain_commands.h"
#include "ui/commands/set_param_command.h"
#include "ui/commands/set_scene_command.h"
#include "ui/document_controller.h"
#include "ui/models/graph_model.h"

#include <QTest>
#include <QUndoStack>
#include <memory>

using namespace velvet;
using namespace velvet::ui;

namespace {

/// Whether @p next merges into @p first (QUndoStack asks exactly this before pushing).
bool merges(QUndoCommand& first, const QUndoCommand& next) {
    return first.mergeWith(&next);
}

} // namespace

class TestUiCommands : public QObject {
    Q_OBJECT

private slots:
    // Through a real stack: one drag is one undo step, undo returns to where the drag began, and
    // a drag that comes back to its start is dropped.
    void aDragIsOneUndoStep() {
        DocumentController controller;
        QUndoStack stack;
        const glm::vec3 start = controller.param(ParamId::Roughness);
        const glm::vec3 a(0.25f), b(0.75f);
        stack.push(new SetParamCommand(&controller, ParamId::Roughness, start, a, 7));
        stack.push(new SetParamCommand(&controller, ParamId::Roughness, a, b, 7));
        QCOMPARE(stack.count(), 1);
        QCOMPARE(controller.param(ParamId::Roughness), b);
        stack.undo();
        QCOMPARE(controller.param(ParamId::Roughness), start);
        stack.redo();
        QCOMPARE(controller.param(ParamId::Roughness), b);
        // The same drag coming back to its start: the merged command is obsolete and dropped.
        stack.push(new SetParamCommand(&controller, ParamId::Roughness, b, start, 7));
        QCOMPARE(stack.count(), 0);
        QCOMPARE(controller.param(ParamId::Roughness), start);
        // Another drag (another key) is another step.
        stack.push(new SetParamCommand(&controller, ParamId::Roughness, start, a, 8));
        stack.push(new SetParamCommand(&controller, ParamId::Roughness, a, b, 9));
        QCOMPARE(stack.count(), 2);
    }

    void materialParameter() {
        DocumentController c;
        using C = SetParamCommand;
        const glm::vec3 x(0.1f), y(0.2f);
        C first(&c, ParamId::Roughness, x, y, 3);
        QVERIFY(merges(first, C(&c, ParamId::Roughness, y, x, 3)));
        QVERIFY(first.isObsolete());                                 // back to x
        QVERIFY(!merges(first, C(&c, ParamId::Metallic, y, x, 3)));  // another target
        QVERIFY(!merges(first, C(&c, ParamId::Roughness, y, x, 4))); // another drag
        C typed(&c, ParamId::Roughness, x, y, 0);
        QVERIFY(!merges(typed, C(&c, ParamId::Roughness, y, x, 0))); // key 0 never merges
    }

    void effectParameter() {
        DocumentController c;
        using C = SetEffectParamCommand;
        C first(&c, 0, "intensity", {0.1f}, {0.2f}, 3);
        QVERIFY(merges(first, C(&c, 0, "intensity", {0.2f}, {0.3f}, 3)));
        QVERIFY(!first.isObsolete());
        QVERIFY(!merges(first, C(&c, 1, "intensity", {0.2f}, {0.3f}, 3))); // another effect
        QVERIFY(!merges(first, C(&c, 0, "radius", {0.2f}, {0.3f}, 3)));    // another parameter
        QVERIFY(!merges(first, C(&c, 0, "intensity", {0.2f}, {0.3f}, 5)));
        C typed(&c, 0, "intensity", {0.1f}, {0.2f}, 0);
        QVERIFY(!merges(typed, C(&c, 0, "intensity", {0.2f}, {0.3f}, 0)));
        // Another kind of command with the same key never merges.
        QVERIFY(!merges(first, SetParamCommand(&c, ParamId::Roughness, {}, {}, 3)));
    }

    void nodeInput() {
        DocumentController c;
        GraphModel model(&c);
        using C = SetNodeInputCommand;
        const glm::vec4 x(0.1f), y(0.2f);
        C first(&model, 1, 0, x, y, 3);
        QVERIFY(merges(first, C(&model, 1, 0, y, x, 3)));
        QVERIFY(first.isObsolete());
        QVERIFY(!merges(first, C(&model, 2, 0, y, x, 3))); // another node
        QVERIFY(!merges(first, C(&model, 1, 1, y, x, 3))); // another input
        QVERIFY(!merges(first, C(&model, 1, 0, y, x, 4)));
        C typed(&model, 1, 0, x, y, 0);
        QVERIFY(!merges(typed, C(&model, 1, 0, y, x, 0)));
    }

    void atlasRegion() {
        DocumentController c;
        AtlasModel model(&c);
        using C = SetAtlasRegionCommand;
        const AtlasRegion x{0, 0, 8, 8}, y{4, 0, 8, 8};
        C first(&model, AtlasKind::Albedo, 0, x, y, 3);
        QVERIFY(merges(first, C(&model, AtlasKind::Albedo, 0, y, AtlasRegion{6, 0, 8, 8}, 3)));
        QVERIFY(!first.isObsolete());
        QVERIFY(!merges(first, C(&model, AtlasKind::Normal, 0, y, x, 3))); // another atlas
        QVERIFY(!merges(first, C(&model, AtlasKind::Albedo, 1, y, x, 3))); // another region
        QVERIFY(!merges(first, C(&model, AtlasKind::Albedo, 0, y, x, 4)));
        C typed(&model, AtlasKind::Albedo, 0, x, y, 0);
        QVERIFY(!merges(typed, C(&model, AtlasKind::Albedo, 0, y, x, 0)));
    }

    // The scene has one environment and one light list: any two of one kind and key merge.
    void sceneValues() {
        DocumentController c;
        Environment e0, e1;
        e1.intensity = e0.intensity + 1.0f;
        SetEnvironmentCommand first(&c, e0, e1, "Environment", 3);
        QVERIFY(merges(first, SetEnvironmentCommand(&c, e1, e0, "Environment", 3)));
        QVERIFY(first.isObsolete());
        QVERIFY(!merges(first, SetEnvironmentCommand(&c, e1, e0, "Environment", 4)));
        SetEnvironmentCommand typed(&c, e0, e1, "Environment", 0);
        QVERIFY(!merges(typed, SetEnvironmentCommand(&c, e1, e0, "Environment", 0)));
        std::vector<Light> none, one(1);
        SetLightsCommand lights(&c, none, one, "Lights", 3);
        QVERIFY(!merges(lights, SetEnvironmentCommand(&c, e1, e0, "Environment", 3)));
        QVERIFY(merges(lights, SetLightsCommand(&c, one, one, "Lights", 3)));
        QVERIFY(!lights.isObsolete());
    }
};

QTEST_GUILESS_MAIN(TestUiCommands)
#include "test_ui_commands.moc"
