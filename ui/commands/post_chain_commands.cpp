#include "ui/commands/post_chain_commands.h"

#include "core/post_effects.h"
#include "ui/document_controller.h"

#include <QCoreApplication>
#include <algorithm>

namespace velvet::ui {
namespace {

QString tr(const char* text) {
    return QCoreApplication::translate("velvet::ui::PostChainCommands", text);
}

QString effectLabel(const std::string& type) {
    if (const EffectMeta* meta = findPostEffect(type))
        return QString::fromUtf8(meta->label.data(), static_cast<qsizetype>(meta->label.size()));
    return QString::fromStdString(type);
}

QString effectLabelAt(const DocumentController* controller, size_t index) {
    const auto& effects = controller->scene().post.effects;
    return index < effects.size() ? effectLabel(effects[index].type) : QString();
}

} // namespace

AddEffectCommand::AddEffectCommand(DocumentController* controller, size_t index,
                                   EffectInstance effect, QUndoCommand* parent)
    : QUndoCommand(parent), m_controller(controller),
      m_index(std::min(index, controller->scene().post.effects.size())),
      m_effect(std::move(effect)) {
    setText(tr("Add %1").arg(effectLabel(m_effect.type)));
}

void AddEffectCommand::redo() {
    PostChain chain = m_controller->scene().post;
    chain.effects.insert(chain.effects.begin() + static_cast<std::ptrdiff_t>(m_index), m_effect);
    m_controller->setPostChain(chain);
}

void AddEffectCommand::undo() {
    PostChain chain = m_controller->scene().post;
    removeEffect(chain, m_index);
    m_controller->setPostChain(chain);
}

RemoveEffectCommand::RemoveEffectCommand(DocumentController* controller, size_t index,
                                         QUndoCommand* parent)
    : QUndoCommand(parent), m_controller(controller), m_index(index) {
    const auto& effects = controller->scene().post.effects;
    if (index < effects.size())
        m_effect = effects[index];
    setText(tr("Remove %1").arg(effectLabel(m_effect.type)));
}

void RemoveEffectCommand::redo() {
    PostChain chain = m_controller->scene().post;
    removeEffect(chain, m_index);
    m_controller->setPostChain(chain);
}

void RemoveEffectCommand::undo() {
    PostChain chain = m_controller->scene().post;
    const size_t at = std::min(m_index, chain.effects.size());
    chain.effects.insert(chain.effects.begin() + static_cast<std::ptrdiff_t>(at), m_effect);
    m_controller->setPostChain(chain);
}

DuplicateEffectCommand::DuplicateEffectCommand(DocumentController* controller, size_t index,
                                               QUndoCommand* parent)
    : QUndoCommand(parent), m_controller(controller), m_index(index) {
    setText(tr("Duplicate %1").arg(effectLabelAt(controller, index)));
}

void DuplicateEffectCommand::redo() {
    PostChain chain = m_controller->scene().post;
    duplicateEffect(chain, m_index);
    m_controller->setPostChain(chain);
}

void DuplicateEffectCommand::undo() {
    PostChain chain = m_controller->scene().post;
    removeEffect(chain, m_index + 1);
    m_controller->setPostChain(chain);
}

MoveEffectCommand::MoveEffectCommand(DocumentController* controller, size_t from, size_t to,
                                     QUndoCommand* parent)
    : QUndoCommand(parent), m_controller(controller), m_from(from), m_to(to) {
    setText(tr("Move %1").arg(effectLabelAt(controller, from)));
}

void MoveEffectCommand::redo() {
    PostChain chain = m_controller->scene().post;
    moveEffect(chain, m_from, m_to);
    m_controller->setPostChain(chain);
}

void MoveEffectCommand::undo() {
    PostChain chain = m_controller->scene().post;
    moveEffect(chain, m_to, m_from);
    m_controller->setPostChain(chain);
}

ToggleEffectCommand::ToggleEffectCommand(DocumentController* controller, size_t index, bool enabled,
                                         QUndoCommand* parent)
    : QUndoCommand(parent), m_controller(controller), m_index(index), m_enabled(enabled) {
    setText((enabled ? tr("Enable %1") : tr("Disable %1")).arg(effectLabelAt(controller, index)));
}

void ToggleEffectCommand::redo() {
    PostChain chain = m_controller->scene().post;
    setEffectEnabled(chain, m_index, m_enabled);
    m_controller->setPostChain(chain);
}

void ToggleEffectCommand::undo() {
    PostChain chain = m_controller->scene().post;
    setEffectEnabled(chain, m_index, !m_enabled);
    m_controller->setPostChain(chain);
}

SetEffectParamCommand::SetEffectParamCommand(DocumentController* controller, EffectId effect,
                                             std::string param, std::vector<float> oldValue,
                                             std::vector<float> newValue, int mergeKey,
                                             QUndoCommand* parent)
    : ValueEditCommand(std::move(oldValue), std::move(newValue), mergeKey, parent),
      m_controller(controller), m_effect(effect), m_param(std::move(param)) {
    QString label = QString::fromStdString(m_param);
    const PostChain& chain = controller->scene().post;
    const long index = findEffectIndex(chain, effect);
    const std::string type = index >= 0 ? chain.effects[size_t(index)].type : std::string();
    if (const EffectMeta* meta = findPostEffect(type))
        if (const ParamMeta* p = findEffectParam(*meta, m_param))
            label = effectLabel(type) + QStringLiteral(" ") +
                    QString::fromUtf8(p->label.data(), static_cast<qsizetype>(p->label.size()));
    setText(tr("Set %1").arg(label));
}

void SetEffectParamCommand::apply(const std::vector<float>& value) {
    PostChain chain = m_controller->scene().post;
    const long index = findEffectIndex(chain, m_effect);
    if (index < 0)
        return;
    auto& params = chain.effects[size_t(index)].params;
    if (value.empty())
        params.erase(m_param);
    else
        params[m_param] = value;
    m_controller->setPostChain(chain);
}

void SetEffectParamCommand::redo() {
    apply(m_new);
}

void SetEffectParamCommand::undo() {
    apply(m_old);
}

ReplacePostChainCommand::ReplacePostChainCommand(DocumentController* controller, PostChain oldChain,
                                                 PostChain newChain, const QString& text,
                                                 QUndoCommand* parent)
    : QUndoCommand(text, parent), m_controller(controller), m_oldChain(std::move(oldChain)),
      m_newChain(std::move(newChain)) {}

void ReplacePostChainCommand::redo() {
    m_controller->setPostChain(m_newChain);
}

void ReplacePostChainCommand::undo() {
    m_controller->setPostChain(m_oldChain);
}

} // namespace velvet::ui
