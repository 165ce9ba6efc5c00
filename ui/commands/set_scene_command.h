#pragma once
/// @file set_scene_command.h
/// Undoable scene edits other than material parameters: the environment (HDRI, intensity,
/// rotation), the preview mesh and the lights.

#include "core/scene.h"
#include "ui/commands/value_edit_command.h"
#include "ui/document_controller.h"

#include <QUndoCommand>

namespace velvet::ui {

/// Replaces one value of the scene through a DocumentController setter (@p Apply). Commands of
/// the same kind (@p Id) with the same non-zero merge key (one drag, one typing session) merge
/// (ValueEditCommand); a merge back to the old value makes the command obsolete, so the gesture
/// leaves nothing behind.
template <class T, void (DocumentController::*Apply)(const T&), int Id>
class MergingSceneCommand : public ValueEditCommand<MergingSceneCommand<T, Apply, Id>, T> {
    using Base = ValueEditCommand<MergingSceneCommand<T, Apply, Id>, T>;

public:
    static constexpr int kId = Id;
    /// A merge key no other gesture of this kind has used (one per drag).
    static int nextMergeKey() {
        static int key = 0;
        return ++key;
    }

    MergingSceneCommand(DocumentController* controller, T oldValue, T newValue, const QString& text,
                        int mergeKey, QUndoCommand* parent = nullptr)
        : Base(std::move(oldValue), std::move(newValue), mergeKey, parent),
          m_controller(controller) {
        this->setText(text);
    }

    void undo() override { (m_controller->*Apply)(this->m_old); }
    void redo() override { (m_controller->*Apply)(this->m_new); }

private:
    friend Base;
    /// The scene has one value of this kind: every command of the kind targets it.
    bool sameTarget(const MergingSceneCommand&) const { return true; }

    DocumentController* m_controller;
};

/// Replaces the scene's Environment (HDRI, intensity, rotation, background); rotation and slider
/// drags merge.
using SetEnvironmentCommand =
    MergingSceneCommand<Environment, &DocumentController::setEnvironment, 0x5e8>;

/// Replaces the scene's lights (the whole list: an add, remove, edit or rig is one command);
/// spin-box gestures merge.
using SetLightsCommand =
    MergingSceneCommand<std::vector<Light>, &DocumentController::setLights, 0x5e9>;

/// Replaces the scene's preview mesh (a built-in kind or a custom file).
class SetMeshCommand : public QUndoCommand {
public:
    SetMeshCommand(DocumentController* controller, MeshRef oldValue, MeshRef newValue,
                   QUndoCommand* parent = nullptr);

    void undo() override;
    void redo() override;

private:
    DocumentController* m_controller;
    MeshRef m_oldValue;
    MeshRef m_newValue;
};

} // namespace velvet::ui
