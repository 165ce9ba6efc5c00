#pragma once
/// @file undo_shortcuts.h
/// Ctrl+Z, Ctrl+Shift+Z and Ctrl+Y undo and redo the document wherever the keyboard focus is
/// (issue 17, item 4), a floating dock included.
///
/// Qt sends a ShortcutOverride to the focus widget first, and every QLineEdit (so every spin box)
/// accepts it for its own text undo, even when it has nothing of its own to undo: after typing
/// 0.35 and Enter in a number field, Ctrl+Z did nothing. The rule here: a text field keeps the
/// keys only while it holds text the artist typed and has not committed (Enter or leaving the
/// field), so Ctrl+Z first takes back the typing, as in any text field; once committed, the edit
/// is the document's and so is Ctrl+Z. A QAbstractSpinBox clears its line edit's undo history
/// on Enter; a plain QLineEdit is marked unmodified after Enter or focus out. Read-only text (the
/// Log) never keeps them.

#include <QObject>

class QAction;
class QWidget;

namespace velvet::ui {

class UndoShortcuts : public QObject {
    Q_OBJECT
public:
    /// Gives @p undo Ctrl+Z and @p redo Ctrl+Shift+Z and Ctrl+Y, application wide (modal dialogs
    /// still block them), and installs the filter on the application; it lives as long as
    /// @p undo.
    static UndoShortcuts* install(QAction* undo, QAction* redo);

    /// True when the focus widget @p focus keeps the undo (or @p redo) keys for its own text.
    static bool widgetKeepsKeys(const QWidget* focus, bool redo);

    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    UndoShortcuts(QAction* undo, QAction* redo);

    QAction* m_undo;
    QAction* m_redo;
};

} // namespace velvet::ui
