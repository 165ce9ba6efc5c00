#pragma once
/// @file ui_test_window.h
/// Bringing the real MainWindow up for a widget test under xvfb-run: shown, active (Xvfb has no
/// window manager to activate it, and shortcuts go to the active window) and past its first
/// frame (llvmpipe compiles every shader for it).

#include "ui/main_window.h"
#include "ui/viewport_widget.h"

#include <QAbstractButton>
#include <QApplication>
#include <QColor>
#include <QImage>
#include <QMessageBox>
#include <QSignalSpy>
#include <QTest>
#include <QTimer>

namespace velvet::test {

inline constexpr int kFrameTimeoutMs = 120000;

/// Makes @p window the active window; false when it does not become active.
inline bool activate(QWidget* window) {
    window->activateWindow();
    QApplication::setActiveWindow(window);
    return QTest::qWaitFor([window] { return window->isActiveWindow(); });
}

/// Shows @p window at @p size and waits for its first frame. Empty when it is up; otherwise what
/// went wrong.
inline QString showWithFirstFrame(ui::MainWindow* window, QSize size) {
    ui::ViewportWidget* viewport = window->viewport();
    QSignalSpy frames(viewport, &ui::ViewportWidget::frameCompleted);
    QSignalSpy failures(viewport, &ui::ViewportWidget::renderFailed);
    window->resize(size);
    window->show();
    if (!QTest::qWaitForWindowExposed(window))
        return QStringLiteral("the window was not exposed");
    if (!activate(window))
        return QStringLiteral("the window did not become active");
    if (!QTest::qWaitFor([&] { return !frames.isEmpty() || !failures.isEmpty(); }, kFrameTimeoutMs))
        return QStringLiteral("no frame within %1 s").arg(kFrameTimeoutMs / 1000);
    if (!failures.isEmpty())
        return viewport->errorMessage();
    return {};
}

/// Mean luma of a 9x9 block around the centre (on the sphere), 0..255.
inline double centreLuma(const QImage& image) {
    double sum = 0.0;
    const int cx = image.width() / 2, cy = image.height() / 2;
    for (int y = cy - 4; y <= cy + 4; ++y)
        for (int x = cx - 4; x <= cx + 4; ++x) {
            const QColor c = image.pixelColor(x, y);
            sum += 0.2126 * c.red() + 0.7152 * c.green() + 0.0722 * c.blue();
        }
    return sum / 81.0;
}

/// Answers the next modal message box with the button whose role is @p role (as a click).
inline void answerNextMessageBox(QMessageBox::StandardButton which) {
    QTimer::singleShot(0, [which] {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        if (!box) {
            answerNextMessageBox(which); // not shown yet: look again on the next turn
            return;
        }
        QTest::mouseClick(box->button(which), Qt::LeftButton);
    });
}

/// Draws frames of @p viewport until its environment's bake is complete (each frame runs a slice
/// of it, and each test bakes afresh in its own cache folder: frames before the end differ from
/// later ones), so images compared across an edit are both baked. False after @p timeoutMs.
inline bool drawUntilEnvironmentBaked(ui::ViewportWidget* viewport, int timeoutMs = 60000) {
    return QTest::qWaitFor(
        [viewport] {
            viewport->grabFramebuffer();
            return viewport->environmentProgress() >= 1.0;
        },
        timeoutMs);
}

} // namespace velvet::test
