#pragma once
/// @file set_scene_command.h
/// Undoable scene edits other than material parameters: the environment (HDRI, intensity,
/// rotation) and the preview mesh.

#include "core/scene.h"

#include <QUndoCommand>

namespace velvet::ui {

class DocumentController;

/// Replaces the scene's Environment through DocumentController::setEnvironment. Commands with
/// the same non-zero merge key (one rotation drag, one slider drag) merge; a merge back to the
/// old value makes the command obsolete.
class SetEnvironmentCommand : public QUndoCommand {
public:
    static constexpr int kId = 0x5e8;
    /// A merge key no other environment gesture has used (one per drag).
    static int nextMergeKey();

    SetEnvironmentCommand(DocumentController* controller, Environment oldValue,
                          Environment newValue, const QString& text, int mergeKey,
                          QUndoCommand* parent = nullptr);

    void undo() override;
    void redo() override;
    int id() const override { return kId; }
    bool mergeWith(const QUndoCommand* other) override;

private:
    DocumentController* m_controller;
    Environment m_oldValue;
    Environment m_newValue;
    int m_mergeKey;
};

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
