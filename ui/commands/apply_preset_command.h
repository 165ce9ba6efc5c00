#pragma once
/// @file apply_preset_command.h
/// Undoable replacement of the whole material by a library preset (issue 5, "Library").

#include "core/material.h"

#include <QUndoCommand>
#include <string>

namespace velvet::ui {

class DocumentController;

/// Replaces the scene's material and its preset path through DocumentController::setMaterial;
/// undo restores the previous material (name, tags, every parameter and texture).
class ApplyPresetCommand : public QUndoCommand {
public:
    ApplyPresetCommand(DocumentController* controller, Material newMaterial, std::string newPreset,
                       QUndoCommand* parent = nullptr);
    void undo() override;
    void redo() override;

private:
    DocumentController* m_controller;
    Material m_oldMaterial;
    std::string m_oldPreset;
    Material m_newMaterial;
    std::string m_newPreset;
};

} // namespace velvet::ui
