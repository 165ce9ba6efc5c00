#include "ui/undo_shortcuts.h"

#include <QAbstractSpinBox>
#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QKeyEvent>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QTextDocument>
#include <QTextEdit>
#include <QTimer>

namespace velvet::ui {
namespace {

bool matches(const QAction* action, const QKeySequence& keys) {
    for (const QKeySequence& s : action->shortcuts())
        if (s == keys)
            return true;
    return false;
}

/// The line edit a focus widget types into: itself, or the one inside a spin box or an
/// editable combo box.
const QLineEdit* lineEditOf(const QWidget* w) {
    if (auto* edit = qobject_cast<const QLineEdit*>(w))
        return edit;
    if (qobject_cast<const QAbstractSpinBox*>(w) || qobject_cast<const QComboBox*>(w))
        return w->findChild<const QLineEdit*>(QString(), Qt::FindDirectChildrenOnly);
    return nullptr;
}

} // namespace

UndoShortcuts::UndoShortcuts(QAction* undo, QAction* redo)
    : QObject(undo), m_undo(undo), m_redo(redo) {}

UndoShortcuts* UndoShortcuts::install(QAction* undo, QAction* redo) {
    undo->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_Z));
    redo->setShortcuts(
        {QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_Z), QKeySequence(Qt::CTRL | Qt::Key_Y)});
    // A floating dock is a window of its own: a window shortcut would not reach it.
    undo->setShortcutContext(Qt::ApplicationShortcut);
    redo->setShortcutContext(Qt::ApplicationShortcut);
    auto* shortcuts = new UndoShortcuts(undo, redo);
    QCoreApplication::instance()->installEventFilter(shortcuts);
    return shortcuts;
}

bool UndoShortcuts::widgetKeepsKeys(const QWidget* focus, bool redo) {
    if (!focus)
        return false;
    if (const QLineEdit* edit = lineEditOf(focus)) {
        if (edit->isReadOnly())
            return false;
        // isModified(): typed since the text was last set or committed (see the file comment).
        return redo ? edit->isRedoAvailable() : edit->isModified() && edit->isUndoAvailable();
    }
    const QTextDocument* document = nullptr;
    if (auto* text = qobject_cast<const QTextEdit*>(focus); text && !text->isReadOnly())
        document = text->document();
    else if (auto* plain = qobject_cast<const QPlainTextEdit*>(focus);
             plain && !plain->isReadOnly())
        document = plain->document();
    if (!document)
        return false;
    return redo ? document->isRedoAvailable() : document->isUndoAvailable();
}

bool UndoShortcuts::eventFilter(QObject* watched, QEvent* event) {
    if (event->type() == QEvent::KeyPress || event->type() == QEvent::FocusOut) {
        // A plain line edit's text is committed on Enter or when the focus leaves it (Qt's
        // editingFinished); from then on Ctrl+Z is the document's. Marked after the line edit
        // has handled the event, so its own handlers still see it modified. (Spin boxes clear
        // their line edit's history on Enter by themselves.)
        auto* edit = qobject_cast<QLineEdit*>(watched);
        const bool commit = event->type() == QEvent::FocusOut ||
                            static_cast<QKeyEvent*>(event)->key() == Qt::Key_Return ||
                            static_cast<QKeyEvent*>(event)->key() == Qt::Key_Enter;
        if (edit && commit)
            QTimer::singleShot(0, edit, [edit] { edit->setModified(false); });
        return false;
    }
    if (event->type() != QEvent::ShortcutOverride)
        return false;
    auto* key = static_cast<QKeyEvent*>(event);
    const QKeySequence keys(key->keyCombination());
    const bool undo = matches(m_undo, keys);
    const bool redo = !undo && matches(m_redo, keys);
    if (!undo && !redo)
        return false;
    if (widgetKeepsKeys(qobject_cast<QWidget*>(watched), redo))
        return false;
    // Not accepted and not delivered: the shortcut map goes on to the Edit menu's action.
    event->ignore();
    return true;
}

} // namespace velvet::ui
