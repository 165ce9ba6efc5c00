#pragma once
/// @file busy_work.h
/// Work that takes seconds (a GPU bake, a mesh import in its child process) run off the UI thread
/// while the window keeps painting and a modal busy dialog says what is going on: the editor
/// never freezes on it, and no input reaches the document meanwhile.

#include <QApplication>
#include <QCoreApplication>
#include <QProgressDialog>
#include <QString>
#include <chrono>
#include <future>
#include <utility>

namespace velvet::ui {

/// Runs @p work on a worker thread and returns its result; meanwhile the UI thread keeps
/// processing events, and a modal dialog titled @p text shows once the work has taken 300 ms.
template <class Work>
auto runWithBusyDialog(const QString& text, Work work) -> decltype(work()) {
    auto job = std::async(std::launch::async, std::move(work));
    QProgressDialog progress(text, QString(), 0, 0, QApplication::activeWindow());
    progress.setObjectName(QStringLiteral("busyDialog"));
    progress.setWindowModality(Qt::ApplicationModal);
    progress.setMinimumDuration(300);
    progress.setValue(0); // starts the minimum-duration timer: without a value it never shows
    while (job.wait_for(std::chrono::milliseconds(20)) != std::future_status::ready)
        QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
    return job.get();
}

} // namespace velvet::ui
