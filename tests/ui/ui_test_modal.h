#pragma once
/// @file ui_test_modal.h
/// Answering the editor's modal dialogs in widget tests as a user would: the test arms an answer,
/// then triggers the action that opens the dialog (its exec() runs a nested event loop).

#include <QApplication>
#include <QFileDialog>
#include <QString>
#include <QTimer>
#include <functional>

namespace velvet::test {

/// Runs @p answer on the next modal dialog of type T once it is shown.
template <class T>
void onNextModal(std::function<void(T*)> answer) {
    QTimer::singleShot(10, [answer] {
        auto* dialog = qobject_cast<T*>(QApplication::activeModalWidget());
        if (!dialog || !dialog->isVisible()) {
            onNextModal<T>(answer); // not shown yet: look again
            return;
        }
        answer(dialog);
    });
}

/// Answers Qt's own file dialog (no native dialog under xvfb) with @p path, and with the name
/// filter @p filter when one is given.
inline void answerFileDialog(const QString& path, const QString& filter = {}) {
    onNextModal<QFileDialog>([path, filter](QFileDialog* dialog) {
        if (!filter.isEmpty())
            dialog->selectNameFilter(filter);
        dialog->selectFile(path);
        QMetaObject::invokeMethod(dialog, "accept", Qt::QueuedConnection);
    });
}

} // namespace velvet::test
