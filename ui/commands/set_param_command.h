#pragma once
/// @file set_param_command.h
/// Undoable change of one material parameter.

#include "core/material.h"
#include "ui/commands/value_edit_command.h"

#include <glm/vec3.hpp>

namespace velvet::ui {

class DocumentController;

/// Sets one parameter through DocumentController::setParam. Commands with the same parameter and
/// the same non-zero merge key (one slider drag) merge; a merge back to the old value makes the
/// command obsolete, so the stack drops it.
class SetParamCommand : public ValueEditCommand<SetParamCommand, glm::vec3> {
public:
    /// Command id for QUndoCommand::id(): merging is further restricted by parameter and key.
    static constexpr int kId = 0x5e7;

    SetParamCommand(DocumentController* controller, ParamId param, glm::vec3 oldValue,
                    glm::vec3 newValue, int mergeKey, QUndoCommand* parent = nullptr);

    void undo() override;
    void redo() override;

    ParamId param() const { return m_param; }
    glm::vec3 oldValue() const { return m_old; }
    glm::vec3 newValue() const { return m_new; }

private:
    friend ValueEditCommand;
    bool sameTarget(const SetParamCommand& next) const { return next.m_param == m_param; }

    DocumentController* m_controller;
    ParamId m_param;
};

} // namespace velvet::ui
