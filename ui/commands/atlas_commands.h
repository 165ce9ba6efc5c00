#pragma once
/// @file atlas_commands.h
/// Undoable atlas edits (ui/models/atlas_model.h) and texture slot assignment.

#include "core/texture_ref.h"
#include "ui/models/atlas_model.h"
#include "ui/commands/value_edit_command.h"

#include <QUndoCommand>

namespace velvet::ui {

class DocumentController;

/// Replaces a whole atlas (add images, repack).
class ReplaceAtlasCommand : public QUndoCommand {
public:
    ReplaceAtlasCommand(AtlasModel* model, AtlasKind kind, AtlasDocument oldValue,
                        AtlasDocument newValue, const QString& text,
                        QUndoCommand* parent = nullptr);
    void undo() override;
    void redo() override;

private:
    AtlasModel* m_model;
    AtlasKind m_kind;
    AtlasDocument m_old;
    AtlasDocument m_new;
};

/// Moves or resizes one region. Commands on the same atlas and region with the same non-zero
/// merge key (one drag) merge; a drag back to where it started makes the command obsolete.
class SetAtlasRegionCommand : public ValueEditCommand<SetAtlasRegionCommand, AtlasRegion> {
public:
    static constexpr int kId = 0xa71a; ///< distinct from every other command's id (merging)
    SetAtlasRegionCommand(AtlasModel* model, AtlasKind kind, int index, AtlasRegion oldValue,
                          AtlasRegion newValue, int mergeKey, QUndoCommand* parent = nullptr);
    void undo() override;
    void redo() override;

private:
    friend ValueEditCommand;
    bool sameTarget(const SetAtlasRegionCommand& next) const {
        return next.m_kind == m_kind && next.m_index == m_index;
    }

    AtlasModel* m_model;
    AtlasKind m_kind;
    int m_index;
};

/// Sets one texture slot of the material (e.g. an atlas region as base colour).
class SetTextureCommand : public QUndoCommand {
public:
    SetTextureCommand(DocumentController* controller, TextureSlot slot, TextureRef oldValue,
                      TextureRef newValue, const QString& text, QUndoCommand* parent = nullptr);
    void undo() override;
    void redo() override;

private:
    DocumentController* m_controller;
    TextureSlot m_slot;
    TextureRef m_old;
    TextureRef m_new;
};

} // namespace velvet::ui
