#include "ui/commands/apply_preset_command.h"

#include "ui/document_controller.h"

#include <QCoreApplication>

namespace velvet::ui {

ApplyPresetCommand::ApplyPresetCommand(DocumentController* controller, Material newMaterial,
                                       std::string newPreset, QUndoCommand* parent)
    : QUndoCommand(parent), m_controller(controller), m_oldMaterial(controller->scene().material),
      m_oldPreset(controller->scene().materialPreset), m_newMaterial(std::move(newMaterial)),
      m_newPreset(std::move(newPreset)) {
    setText(QCoreApplication::translate("velvet::ui::ApplyPresetCommand", "Apply preset %1")
                .arg(QString::fromStdString(m_newMaterial.name)));
}

void ApplyPresetCommand::redo() {
    m_controller->setMaterial(m_newMaterial, m_newPreset);
}

void ApplyPresetCommand::undo() {
    m_controller->setMaterial(m_oldMaterial, m_oldPreset);
}

} // namespace velvet::ui
