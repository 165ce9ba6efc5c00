#include "ui/commands/set_scene_command.h"

#include "ui/document_controller.h"

#include <QCoreApplication>
#include <QFileInfo>

namespace velvet::ui {
namespace {

QString meshName(PreviewMeshKind kind) {
    const std::string_view name = previewMeshKindNames()[static_cast<size_t>(kind)];
    return QString::fromUtf8(name.data(), static_cast<qsizetype>(name.size()));
}

} // namespace

SetEnvironmentCommand::SetEnvironmentCommand(DocumentController* controller, Environment oldValue,
                                             Environment newValue, const QString& text,
                                             int mergeKey, QUndoCommand* parent)
    : QUndoCommand(text, parent), m_controller(controller), m_oldValue(std::move(oldValue)),
      m_newValue(std::move(newValue)), m_mergeKey(mergeKey) {}

int SetEnvironmentCommand::nextMergeKey() {
    static int key = 0;
    return ++key;
}

void SetEnvironmentCommand::undo() {
    m_controller->setEnvironment(m_oldValue);
}

void SetEnvironmentCommand::redo() {
    m_controller->setEnvironment(m_newValue);
}

bool SetEnvironmentCommand::mergeWith(const QUndoCommand* other) {
    if (other->id() != id())
        return false;
    const auto* next = static_cast<const SetEnvironmentCommand*>(other);
    if (m_mergeKey == 0 || next->m_mergeKey != m_mergeKey)
        return false;
    m_newValue = next->m_newValue;
    setObsolete(m_newValue == m_oldValue);
    return true;
}

SetMeshCommand::SetMeshCommand(DocumentController* controller, MeshRef oldValue, MeshRef newValue,
                               QUndoCommand* parent)
    : QUndoCommand(parent), m_controller(controller), m_oldValue(std::move(oldValue)),
      m_newValue(std::move(newValue)) {
    const QString what = m_newValue.kind == PreviewMeshKind::Custom
                             ? QFileInfo(QString::fromStdString(m_newValue.file)).fileName()
                             : meshName(m_newValue.kind);
    setText(QCoreApplication::translate("velvet::ui::SetMeshCommand", "Preview mesh %1").arg(what));
}

void SetMeshCommand::undo() {
    m_controller->setMesh(m_oldValue);
}

void SetMeshCommand::redo() {
    m_controller->setMesh(m_newValue);
}

SetLightsCommand::SetLightsCommand(DocumentController* controller, std::vector<Light> oldValue,
                                   std::vector<Light> newValue, const QString& text, int mergeKey,
                                   QUndoCommand* parent)
    : QUndoCommand(text, parent), m_controller(controller), m_oldValue(std::move(oldValue)),
      m_newValue(std::move(newValue)), m_mergeKey(mergeKey) {}

int SetLightsCommand::nextMergeKey() {
    static int key = 0;
    return ++key;
}

void SetLightsCommand::undo() {
    m_controller->setLights(m_oldValue);
}

void SetLightsCommand::redo() {
    m_controller->setLights(m_newValue);
}

bool SetLightsCommand::mergeWith(const QUndoCommand* other) {
    if (other->id() != id())
        return false;
    const auto* next = static_cast<const SetLightsCommand*>(other);
    if (m_mergeKey == 0 || next->m_mergeKey != m_mergeKey)
        return false;
    m_newValue = next->m_newValue;
    setObsolete(m_newValue == m_oldValue);
    return true;
}

} // namespace velvet::ui
