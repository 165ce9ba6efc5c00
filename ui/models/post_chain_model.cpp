#include "ui/models/post_chain_model.h"

#include "core/post_effects.h"
#include "ui/commands/post_chain_commands.h"
#include "ui/document_controller.h"

#include <QApplication>
#include <QMimeData>
#include <QStyle>
#include <QUndoStack>

namespace velvet::ui {
namespace {

QString fromView(std::string_view s) {
    return QString::fromUtf8(s.data(), static_cast<qsizetype>(s.size()));
}

} // namespace

PostChainModel::PostChainModel(DocumentController* controller, QObject* parent)
    : QAbstractListModel(parent), m_controller(controller),
      m_warningIcon(QApplication::style()->standardIcon(QStyle::SP_MessageBoxWarning)) {
    connect(m_controller, &DocumentController::postChainChanged, this, &PostChainModel::refresh);
    refresh();
}

void PostChainModel::refresh() {
    const PostChain& chain = m_controller->scene().post;
    m_issues.clear();
    for (const ChainIssue& issue : checkStageOrder(chain)) {
        QString& text = m_issues[issue.index];
        text += (text.isEmpty() ? QString() : QStringLiteral("\n")) +
                QString::fromStdString(issue.message);
    }
    for (const ChainIssue& issue : checkEffectParams(chain)) {
        QString& text = m_issues[issue.index];
        text += (text.isEmpty() ? QString() : QStringLiteral("\n")) +
                QString::fromStdString(issue.message);
    }
    const int rows = static_cast<int>(chain.effects.size());
    if (rows != m_rows) {
        // Row count changed (add, remove, duplicate, undo of those, a preset): reset. Moves and
        // edits keep the count, so selections survive them.
        beginResetModel();
        m_rows = rows;
        endResetModel();
    } else if (rows > 0) {
        emit dataChanged(index(0), index(rows - 1));
    }
}

int PostChainModel::rowCount(const QModelIndex& parent) const {
    return parent.isValid() ? 0 : m_rows;
}

QString PostChainModel::issue(int row) const {
    const auto it = m_issues.find(static_cast<size_t>(row));
    return it == m_issues.end() ? QString() : it->second;
}

QVariant PostChainModel::data(const QModelIndex& index, int role) const {
    const auto& effects = m_controller->scene().post.effects;
    if (!index.isValid() || index.row() >= static_cast<int>(effects.size()))
        return {};
    const EffectInstance& effect = effects[static_cast<size_t>(index.row())];
    const EffectMeta* meta = findPostEffect(effect.type);
    switch (role) {
    case Qt::DisplayRole:
        return meta ? fromView(meta->label) : QString::fromStdString(effect.type);
    case Qt::CheckStateRole:
        return effect.enabled ? Qt::Checked : Qt::Unchecked;
    case Qt::DecorationRole:
        return issue(index.row()).isEmpty() ? QVariant() : QVariant(m_warningIcon);
    case Qt::ToolTipRole: {
        const QString problem = issue(index.row());
        if (!problem.isEmpty())
            return problem;
        if (!meta)
            return {};
        return tr("%1 (%2 stage)")
            .arg(fromView(meta->description), fromView(postStageName(meta->stage)));
    }
    case TypeRole:
        return QString::fromStdString(effect.type);
    case IssueRole:
        return issue(index.row());
    default:
        return {};
    }
}

bool PostChainModel::setData(const QModelIndex& index, const QVariant& value, int role) {
    if (role != Qt::CheckStateRole || !index.isValid() || index.row() >= m_rows)
        return false;
    const bool enabled = value.toInt() == Qt::Checked;
    const auto row = static_cast<size_t>(index.row());
    if (m_controller->scene().post.effects[row].enabled == enabled)
        return false;
    m_controller->undoStack()->push(new ToggleEffectCommand(m_controller, row, enabled));
    return true;
}

Qt::ItemFlags PostChainModel::flags(const QModelIndex& index) const {
    if (!index.isValid())
        return Qt::ItemIsDropEnabled; // drops between rows
    return Qt::ItemIsEnabled | Qt::ItemIsSelectable | Qt::ItemIsUserCheckable |
           Qt::ItemIsDragEnabled;
}

Qt::DropActions PostChainModel::supportedDropActions() const {
    return Qt::MoveAction;
}

QStringList PostChainModel::mimeTypes() const {
    return {QString::fromLatin1(kMimeType)};
}

QMimeData* PostChainModel::mimeData(const QModelIndexList& indexes) const {
    if (indexes.isEmpty())
        return nullptr;
    auto* data = new QMimeData;
    data->setData(QString::fromLatin1(kMimeType), QByteArray::number(indexes.first().row()));
    return data;
}

bool PostChainModel::dropMimeData(const QMimeData* data, Qt::DropAction action, int row,
                                  int /*column*/, const QModelIndex& parent) {
    if (!data || !data->hasFormat(QString::fromLatin1(kMimeType)) ||
        (action != Qt::MoveAction && action != Qt::CopyAction))
        return false;
    bool ok = false;
    const int from = data->data(QString::fromLatin1(kMimeType)).toInt(&ok);
    if (!ok)
        return false;
    // Dropped onto an item: insert before it; between items: at @p row; past the end: append.
    int insertBefore = row;
    if (insertBefore < 0)
        insertBefore = parent.isValid() ? parent.row() : m_rows;
    moveToInsertPosition(from, insertBefore);
    return true; // handled (also when nothing moved), so the view removes nothing
}

bool PostChainModel::moveRows(const QModelIndex& sourceParent, int sourceRow, int count,
                              const QModelIndex& destinationParent, int destinationChild) {
    if (sourceParent.isValid() || destinationParent.isValid() || count != 1)
        return false;
    return moveToInsertPosition(sourceRow, destinationChild);
}

bool PostChainModel::moveToInsertPosition(int from, int insertBefore) {
    if (from < 0 || from >= m_rows || insertBefore < 0 || insertBefore > m_rows)
        return false;
    const int to = insertBefore > from ? insertBefore - 1 : insertBefore;
    if (to == from)
        return false;
    m_controller->undoStack()->push(
        new MoveEffectCommand(m_controller, static_cast<size_t>(from), static_cast<size_t>(to)));
    return true;
}

} // namespace velvet::ui
