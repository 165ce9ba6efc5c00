#pragma once
/// @file post_chain_commands.h
/// Undoable edits of the scene's post-effect chain (issue 5, "Post chain panel"): add, remove,
/// duplicate, move, enable/disable, set one parameter (slider drags merge) and replace the whole
/// chain (a chain preset). Each command applies its change through
/// DocumentController::setPostChain, using the chain operations of core/post_effects.h.

#include "core/post_chain.h"
#include "ui/commands/value_edit_command.h"

#include <QUndoCommand>
#include <cstddef>
#include <string>
#include <vector>

namespace velvet::ui {

class DocumentController;

/// Inserts an effect instance at an index (append when the index is past the end).
class AddEffectCommand : public QUndoCommand {
public:
    AddEffectCommand(DocumentController* controller, size_t index, EffectInstance effect,
                     QUndoCommand* parent = nullptr);
    void undo() override;
    void redo() override;
    size_t index() const { return m_index; }

private:
    DocumentController* m_controller;
    size_t m_index;
    EffectInstance m_effect;
};

/// Removes the effect at an index; undo puts the same instance back.
class RemoveEffectCommand : public QUndoCommand {
public:
    RemoveEffectCommand(DocumentController* controller, size_t index,
                        QUndoCommand* parent = nullptr);
    void undo() override;
    void redo() override;

private:
    DocumentController* m_controller;
    size_t m_index;
    EffectInstance m_effect;
};

/// Inserts a copy of the effect at an index right after it.
class DuplicateEffectCommand : public QUndoCommand {
public:
    DuplicateEffectCommand(DocumentController* controller, size_t index,
                           QUndoCommand* parent = nullptr);
    void undo() override;
    void redo() override;

private:
    DocumentController* m_controller;
    size_t m_index;
};

/// Moves the effect at @p from to position @p to (core moveEffect semantics).
class MoveEffectCommand : public QUndoCommand {
public:
    MoveEffectCommand(DocumentController* controller, size_t from, size_t to,
                      QUndoCommand* parent = nullptr);
    void undo() override;
    void redo() override;

private:
    DocumentController* m_controller;
    size_t m_from;
    size_t m_to;
};

/// Enables or disables the effect at an index.
class ToggleEffectCommand : public QUndoCommand {
public:
    ToggleEffectCommand(DocumentController* controller, size_t index, bool enabled,
                        QUndoCommand* parent = nullptr);
    void undo() override;
    void redo() override;

private:
    DocumentController* m_controller;
    size_t m_index;
    bool m_enabled;
};

/// Sets one parameter of the effect with an id (wherever the effect has moved to meanwhile):
/// built by DocumentController::editEffectParam with values core's rules already constrained.
/// Commands with the same effect, parameter and non-zero merge key (one slider drag) merge; a
/// drag back to the old value is obsolete.
class SetEffectParamCommand : public ValueEditCommand<SetEffectParamCommand, std::vector<float>> {
public:
    static constexpr int kId = 0x5f0;

    SetEffectParamCommand(DocumentController* controller, EffectId effect, std::string param,
                          std::vector<float> oldValue, std::vector<float> newValue, int mergeKey,
                          QUndoCommand* parent = nullptr);
    void undo() override;
    void redo() override;

private:
    friend ValueEditCommand;
    bool sameTarget(const SetEffectParamCommand& next) const {
        return next.m_effect == m_effect && next.m_param == m_param;
    }
    /// Sets the parameter to @p value; an empty value (m_old when the parameter was absent)
    /// removes it, so the effect falls back to its default.
    void apply(const std::vector<float>& value);

    DocumentController* m_controller;
    EffectId m_effect;
    std::string m_param;
};

/// Replaces the whole chain (a chain preset loaded).
class ReplacePostChainCommand : public QUndoCommand {
public:
    ReplacePostChainCommand(DocumentController* controller, PostChain oldChain, PostChain newChain,
                            const QString& text, QUndoCommand* parent = nullptr);
    void undo() override;
    void redo() override;

private:
    DocumentController* m_controller;
    PostChain m_oldChain;
    PostChain m_newChain;
};

} // namespace velvet::ui
