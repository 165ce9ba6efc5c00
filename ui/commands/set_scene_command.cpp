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

} // namespace velvet::ui
