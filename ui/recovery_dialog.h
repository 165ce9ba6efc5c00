#pragma once
/// @file recovery_dialog.h
/// The start-up list of recoverable autosaves (issue 17, item 11): one row per autosave with
/// its document (or "Untitled document"), folder and time. The artist recovers one (it becomes
/// the document: Velvet edits one document at a time), discards rows, or leaves the rest for
/// later (they are offered again at the next start, and when their file is opened).

#include "ui/autosave.h"

#include <QDialog>
#include <QStringList>
#include <optional>

class QPushButton;
class QTreeWidget;

namespace velvet::ui {

class RecoveryDialog : public QDialog {
    Q_OBJECT
public:
    RecoveryDialog(const QList<Autosave::Recoverable>& autosaves, QWidget* parent = nullptr);

    /// The autosave to recover, set when the dialog was accepted with "Recover".
    std::optional<Autosave::Recoverable> chosen() const { return m_chosen; }
    /// The autosave files the artist discarded (removed by the caller).
    QStringList discarded() const { return m_discarded; }

private:
    void updateButtons();

    QList<Autosave::Recoverable> m_autosaves;
    QTreeWidget* m_list;
    QPushButton* m_recover;
    QPushButton* m_discard;
    std::optional<Autosave::Recoverable> m_chosen;
    QStringList m_discarded;
};

} // namespace velvet::ui
