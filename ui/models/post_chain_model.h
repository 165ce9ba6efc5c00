#pragma once
/// @file post_chain_model.h
/// The scene's post chain as a list model: one row per effect (label, enable check box, a
/// warning icon and the stage-rule explanation where the order is wrong). Edits made through the
/// model (check boxes, moves) become undo commands on the DocumentController; document changes
/// (undo, redo, open) refresh the rows.

#include <QAbstractListModel>
#include <QIcon>
#include <QString>
#include <cstddef>
#include <map>

namespace velvet::ui {

class DocumentController;

class PostChainModel : public QAbstractListModel {
    Q_OBJECT
public:
    /// MIME type of a dragged row (its row number as text); only this model reads it.
    static constexpr const char* kMimeType = "application/x-velvet-post-effect-row";

    enum Role {
        TypeRole = Qt::UserRole + 1, ///< the effect type id (QString)
        IssueRole,                   ///< the stage-rule / parameter explanation, empty when none
    };

    explicit PostChainModel(DocumentController* controller, QObject* parent = nullptr);

    int rowCount(const QModelIndex& parent = {}) const override;
    QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
    bool setData(const QModelIndex& index, const QVariant& value, int role) override;
    Qt::ItemFlags flags(const QModelIndex& index) const override;
    Qt::DropActions supportedDropActions() const override;
    QStringList mimeTypes() const override;
    QMimeData* mimeData(const QModelIndexList& indexes) const override;
    /// A drop of a row of this model: one MoveEffectCommand (@p row is the insert position).
    bool dropMimeData(const QMimeData* data, Qt::DropAction action, int row, int column,
                      const QModelIndex& parent) override;
    /// Moves one row (QListView's internal move): one MoveEffectCommand.
    bool moveRows(const QModelIndex& sourceParent, int sourceRow, int count,
                  const QModelIndex& destinationParent, int destinationChild) override;

    /// Moves effect @p from so that it lands before the row now at @p insertBefore (0..count):
    /// the drag-and-drop convention. Pushes one command; false when nothing would move.
    bool moveToInsertPosition(int from, int insertBefore);
    /// The explanation shown on row @p row, empty when the row is fine.
    QString issue(int row) const;

private:
    void refresh();

    DocumentController* m_controller;
    std::map<size_t, QString> m_issues; ///< row -> explanation(s)
    QIcon m_warningIcon;
    int m_rows = 0;
};

} // namespace velvet::ui
