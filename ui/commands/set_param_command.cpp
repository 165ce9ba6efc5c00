#include "ui/commands/set_param_command.h"

#include "ui/document_controller.h"

#include <QCoreApplication>

namespace velvet::ui {

SetParamCommand::SetParamCommand(DocumentController* controller, ParamId param, glm::vec3 oldValue,
                                 glm::vec3 newValue, int mergeKey, QUndoCommand* parent)
    : ValueEditCommand(oldValue, newValue, mergeKey, parent), m_controller(controller),
      m_param(param) {
    setText(QCoreApplication::translate("velvet::ui::SetParamCommand", "Set %1")
                .arg(QString::fromUtf8(paramMeta(param).label)));
}

void SetParamCommand::undo() {
    m_controller->setParam(m_param, m_old);
}

void SetParamCommand::redo() {
    m_controller->setParam(m_param, m_new);
}

} // namespace velvet::ui
