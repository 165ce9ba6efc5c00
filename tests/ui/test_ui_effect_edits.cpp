// One edit route for post effects (issue 11, "One edit route"): the Properties panel asks the
// DocumentController for an edit of the effect it shows, addressed by id; core's value rules
// clamp and round it; each edit is one undo step; and the edit, its undo and the panel itself
// keep following the same effect after the chain is reordered.
#include "core/post_effects.h"
#include "ui/document_controller.h"
#include "ui/post_chain/post_chain_panel.h"
#include "ui/properties/param_editor.h"
#include "ui/properties/property_panel.h"

#include <QUndoStack>
#include <QtTest>

using namespace velvet;
using namespace velvet::ui;

namespace {

void setChain(DocumentController& controller, std::initializer_list<const char*> types) {
    Scene scene = controller.scene();
    scene.post.effects.clear();
    for (const char* type : types)
        scene.post.effects.push_back(makeEffect(type));
    controller.setDocument(std::move(scene), QString());
}

float valueAt(const DocumentController& controller, size_t index, const char* param) {
    return effectFloat(controller.scene().post.effects[index], param);
}

} // namespace

class TestUiEffectEdits : public QObject {
    Q_OBJECT
private slots:
    void init() {
        m_controller = std::make_unique<DocumentController>();
        m_chain = std::make_unique<PostChainPanel>(m_controller.get());
        m_properties = std::make_unique<PropertyPanel>(m_controller.get());
        connect(m_chain.get(), &PostChainPanel::effectSelected, m_properties.get(),
                &PropertyPanel::showEffect);
    }
    void cleanup() {
        m_properties.reset();
        m_chain.reset();
        m_controller.reset();
    }

    /// The editor asks for 5 on a [0, 1] parameter: one command, and the document holds 1.
    void panelEditIsOneClampedUndoStep() {
        setChain(*m_controller, {"tonemap", "vignette"});
        m_chain->setCurrentRow(1);
        QCOMPARE(m_properties->effectId(), m_controller->scene().post.effects[1].id);
        ParamEditor* intensity = m_properties->subjectEditor(QStringLiteral("intensity"));
        QVERIFY(intensity);
        const float before = valueAt(*m_controller, 1, "intensity");
        emit intensity->edited(glm::vec4(5.0f), 0);
        QCOMPARE(m_controller->undoStack()->count(), 1);
        QCOMPARE(valueAt(*m_controller, 1, "intensity"), 1.0f); // the parameter's max
        emit intensity->edited(glm::vec4(7.0f), 0);             // clamps to what it holds
        QCOMPARE(m_controller->undoStack()->count(), 1);
        m_controller->undoStack()->undo();
        QCOMPARE(valueAt(*m_controller, 1, "intensity"), before);

        // A choice is rounded to the nearest index: 1.6 is Reinhard (2).
        m_chain->setCurrentRow(0);
        ParamEditor* curve = m_properties->subjectEditor(QStringLiteral("operator"));
        QVERIFY(curve);
        emit curve->edited(glm::vec4(1.6f), 0);
        QCOMPARE(valueAt(*m_controller, 0, "operator"), 2.0f);
        emit curve->edited(glm::vec4(-3.0f), 0);
        QCOMPARE(valueAt(*m_controller, 0, "operator"), 0.0f);
        QCOMPARE(m_controller->undoStack()->index(), 2);
    }

    /// A drag (one merge key) is one step, even across values the rules clamp.
    void dragMergesIntoOneStep() {
        setChain(*m_controller, {"vignette"});
        m_chain->setCurrentRow(0);
        ParamEditor* intensity = m_properties->subjectEditor(QStringLiteral("intensity"));
        QVERIFY(intensity);
        for (float v : {0.2f, 0.6f, 3.0f, 0.9f})
            emit intensity->edited(glm::vec4(v), 42);
        QCOMPARE(m_controller->undoStack()->count(), 1);
        QCOMPARE(valueAt(*m_controller, 0, "intensity"), 0.9f);
    }

    /// Addressed by id, not index: the panel follows its effect through a move, an edit made
    /// before the move is undone on the same effect after it, and an unknown id edits nothing.
    void editsFollowTheEffectThroughAReorder() {
        setChain(*m_controller, {"color_grading", "vignette"});
        const EffectId vignette = m_controller->scene().post.effects[1].id;
        m_chain->setCurrentRow(1);
        QCOMPARE(m_properties->effectIndex(), 1);
        const float before = valueAt(*m_controller, 1, "intensity");
        emit m_properties->subjectEditor(QStringLiteral("intensity"))->edited(glm::vec4(0.8f), 0);
        QCOMPARE(valueAt(*m_controller, 1, "intensity"), 0.8f);

        m_chain->moveCurrent(-1); // the vignette goes first
        QCOMPARE(m_controller->scene().post.effects[0].id, vignette);
        QCOMPARE(m_properties->effectId(), vignette);
        QCOMPARE(m_properties->effectIndex(), 0);
        QVERIFY2(m_properties->title().contains(QStringLiteral("post effect 1")),
                 qPrintable(m_properties->title()));

        // An edit after the move reaches the vignette, not the effect now at its old index.
        const PostChain movedChain = m_controller->scene().post;
        emit m_properties->subjectEditor(QStringLiteral("intensity"))->edited(glm::vec4(0.4f), 0);
        QCOMPARE(valueAt(*m_controller, 0, "intensity"), 0.4f);
        QCOMPARE(m_controller->scene().post.effects[1], movedChain.effects[1]);

        // Undo: the second edit, the move, then the first edit, each on the vignette.
        QUndoStack* stack = m_controller->undoStack();
        QCOMPARE(stack->count(), 3);
        stack->undo();
        QCOMPARE(valueAt(*m_controller, 0, "intensity"), 0.8f);
        stack->undo();
        QCOMPARE(m_controller->scene().post.effects[1].id, vignette);
        QCOMPARE(m_properties->effectIndex(), 1);
        stack->undo();
        QCOMPARE(valueAt(*m_controller, 1, "intensity"), before);

        QVERIFY(!m_controller->editEffectParam(vignette + 1000, "intensity", glm::vec3(0.5f)));
        QVERIFY(!m_controller->editEffectParam(vignette, "no_such_param", glm::vec3(0.5f)));
        QCOMPARE(stack->count(), 3);
    }

    /// Duplicating gives the copy its own id; editing it leaves the original alone.
    void duplicateHasItsOwnId() {
        setChain(*m_controller, {"vignette"});
        m_chain->setCurrentRow(0);
        m_chain->duplicateCurrent();
        const auto& effects = m_controller->scene().post.effects;
        QCOMPARE(effects.size(), size_t(2));
        QVERIFY(effects[0].id != effects[1].id);
        QVERIFY(m_controller->editEffectParam(effects[1].id, "intensity", glm::vec3(0.1f)));
        QCOMPARE(valueAt(*m_controller, 1, "intensity"), 0.1f);
        QVERIFY(valueAt(*m_controller, 0, "intensity") != 0.1f);
    }

private:
    std::unique_ptr<DocumentController> m_controller;
    std::unique_ptr<PostChainPanel> m_chain;
    std::unique_ptr<PropertyPanel> m_properties;
};

QTEST_MAIN(TestUiEffectEdits)
#include "test_ui_effect_edits.moc"
