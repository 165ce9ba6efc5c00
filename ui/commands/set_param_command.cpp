#include "ui/commands/set_param_command.h"

#include "ui/document_controller.h"

#include <QCoreApplication>

namespace velvet::ui {

SetParamCommand::SetParamCommand(DocumentController* controller, ParamId param, glm::vec3 oldValue,
                                 glm::vec3 newValue, int mergeKey, QUndoCommand* parent)
    : QUndoCommand(parent), m_controller(controller), m_param(param), m_oldValue(oldValue),
      m_newValue(newValue), m_mergeKey(mergeKey) {
    setText(QCoreApplication::translate("velvet::ui::SetParamCommand", "Set %1")
                .arg(QString::fromUtf8(paramMeta(param).label)));
}

void SetParamCommand::undo() {
    m_controller->setParam(m_param, m_oldValue);
}

void SetParamCommand::redo() {
    m_controller->setParam(m_param, m_newValue);
}

bool SetParamCommand::mergeWith(const QUndoCommand* other) {
    if (other->id() != id())
        return false;
    const auto* next = static_cast<const SetParamCommand*>(other);
    if (m_mergeKey == 0 || next->m_mergeKey != m_mergeKey || next->m_param != m_param)
        return false;
    m_newValue = next->m_newValue;
    // A drag that ends where it started leaves nothing to undo.
    setObsolete(m_newValue == m_oldValue);
    return true;
}

} // namespace velvet::ui
