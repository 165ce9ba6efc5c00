#include "ui/commands/atlas_commands.h"

#include "ui/document_controller.h"

namespace velvet::ui {

ReplaceAtlasCommand::ReplaceAtlasCommand(AtlasModel* model, AtlasKind kind, AtlasDocument oldValue,
                                         AtlasDocument newValue, const QString& text,
                                         QUndoCommand* parent)
    : QUndoCommand(text, parent), m_model(model), m_kind(kind), m_old(std::move(oldValue)),
      m_new(std::move(newValue)) {}

void ReplaceAtlasCommand::undo() {
    m_model->setAtlas(m_kind, m_old);
}

void ReplaceAtlasCommand::redo() {
    m_model->setAtlas(m_kind, m_new);
}

SetAtlasRegionCommand::SetAtlasRegionCommand(AtlasModel* model, AtlasKind kind, int index,
                                             AtlasRegion oldValue, AtlasRegion newValue,
                                             int mergeKey, QUndoCommand* parent)
    : ValueEditCommand(oldValue, newValue, mergeKey, parent), m_model(model), m_kind(kind),
      m_index(index) {
    const bool moved = oldValue.width == newValue.width && oldValue.height == newValue.height;
    setText(moved ? QObject::tr("Move %1 region").arg(AtlasModel::kindLabel(kind))
                  : QObject::tr("Resize %1 region").arg(AtlasModel::kindLabel(kind)));
}

void SetAtlasRegionCommand::undo() {
    m_model->setRegion(m_kind, m_index, m_old);
}

void SetAtlasRegionCommand::redo() {
    m_model->setRegion(m_kind, m_index, m_new);
}

SetTextureCommand::SetTextureCommand(DocumentController* controller, TextureSlot slot,
                                     TextureRef oldValue, TextureRef newValue, const QString& text,
                                     QUndoCommand* parent)
    : QUndoCommand(text, parent), m_controller(controller), m_slot(slot),
      m_old(std::move(oldValue)), m_new(std::move(newValue)) {}

void SetTextureCommand::undo() {
    m_controller->setTexture(m_slot, m_old);
}

void SetTextureCommand::redo() {
    m_controller->setTexture(m_slot, m_new);
}

} // namespace velvet::ui
