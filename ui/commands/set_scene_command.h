#pragma once
/// @file set_scene_command.h
/// Undoable scene edits other than material parameters: the environment (HDRI, intensity,
/// rotation), the preview mesh and the lights.

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

/// Replaces the scene's lights (the whole list: an add, remove, edit or rig is one command).
/// Commands with the same non-zero merge key (one spin-box or slider gesture) merge; a merge
/// back to the old lights makes the command obsolete.
class SetLightsCommand : public QUndoCommand {
public:
    static constexpr int kId = 0x5e9;
    /// A merge key no other light gesture has used.
    static int nextMergeKey();

    SetLightsCommand(DocumentController* controller, std::vector<Light> oldValue,
                     std::vector<Light> newValue, const QString& text, int mergeKey,
                     QUndoCommand* parent = nullptr);

    void undo() override;
    void redo() override;
    int id() const override { return kId; }
    bool mergeWith(const QUndoCommand* other) override;

private:
    DocumentController* m_controller;
    std::vector<Light> m_oldValue;
    std::vector<Light> m_newValue;
    int m_mergeKey;
};

} // namespace velvet::ui
