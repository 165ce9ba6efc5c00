#pragma once
/// @file wheel_guard.h
/// Sliders, spin boxes and combo boxes take the mouse wheel only when they have the keyboard
/// focus (issue 17, item 3). Without this, scrolling a panel with the pointer passing over a
/// slider changes the value, adds an undo step and discards the redo history. An unfocused
/// control hands the wheel to the scroll area around it (the panel scrolls) or drops it when
/// there is none (a toolbar combo). Scroll bars keep the wheel: scrolling is their job.

#include <QObject>

namespace velvet::ui {

/// An application-wide event filter (QCoreApplication::installEventFilter): every window,
/// dock and popup is covered, including widgets made after it was installed.
class WheelGuard : public QObject {
    Q_OBJECT
public:
    /// Installs one guard on the application (parented to it); later calls return the same one.
    static WheelGuard* install();

    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    explicit WheelGuard(QObject* parent);
};

} // namespace velvet::ui
