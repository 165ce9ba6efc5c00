#include "ui/wheel_guard.h"

#include <QAbstractScrollArea>
#include <QAbstractSlider>
#include <QAbstractSpinBox>
#include <QApplication>
#include <QComboBox>
#include <QPointer>
#include <QScrollBar>
#include <QWheelEvent>

namespace velvet::ui {
namespace {

/// The value control that @p widget is (or is a part of, like a spin box's line edit), or null.
QWidget* guardedControl(QWidget* widget) {
    for (QWidget* w = widget; w && !w->isWindow(); w = w->parentWidget()) {
        if (qobject_cast<QScrollBar*>(w))
            return nullptr;
        if (qobject_cast<QAbstractSlider*>(w) || qobject_cast<QAbstractSpinBox*>(w) ||
            qobject_cast<QComboBox*>(w))
            return w;
        if (qobject_cast<QAbstractScrollArea*>(w))
            return nullptr; // e.g. a combo's popup list: its own scrolling is fine
    }
    return nullptr;
}

/// The innermost scroll area that holds @p control in its viewport.
QAbstractScrollArea* scrollAreaAround(QWidget* control) {
    for (QWidget* w = control->parentWidget(); w && !w->isWindow(); w = w->parentWidget())
        if (auto* area = qobject_cast<QAbstractScrollArea*>(w))
            return area;
    return nullptr;
}

} // namespace

WheelGuard::WheelGuard(QObject* parent) : QObject(parent) {}

WheelGuard* WheelGuard::install() {
    QCoreApplication* app = QCoreApplication::instance();
    if (auto* existing = app->findChild<WheelGuard*>(QString(), Qt::FindDirectChildrenOnly))
        return existing;
    auto* guard = new WheelGuard(app);
    app->installEventFilter(guard);
    return guard;
}

bool WheelGuard::eventFilter(QObject* watched, QEvent* event) {
    if (event->type() == QEvent::Polish || event->type() == QEvent::Show) {
        // Qt gives Qt::WheelFocus widgets (spin boxes) the focus before delivering a real wheel
        // event (QApplication::notify), which would defeat the focus test below: they get focus
        // from a click or Tab only. Show as well as Polish: a widget polished before the guard
        // was installed is still shown before any wheel can reach it.
        auto* widget = qobject_cast<QWidget*>(watched);
        if (widget && guardedControl(widget) == widget && widget->focusPolicy() == Qt::WheelFocus)
            widget->setFocusPolicy(Qt::StrongFocus);
        return false;
    }
    if (event->type() != QEvent::Wheel)
        return false;
    auto* widget = qobject_cast<QWidget*>(watched);
    QWidget* control = widget ? guardedControl(widget) : nullptr;
    if (!control || control->hasFocus())
        return false;
    // The event is not the control's: the scroll area around it scrolls instead. A new event,
    // positioned in the area's viewport, because Qt does not pass a synthesized wheel event on to
    // parents (QApplication::notify), and the original's position is the control's.
    auto* wheel = static_cast<QWheelEvent*>(event);
    if (QAbstractScrollArea* area = scrollAreaAround(control)) {
        QWidget* viewport = area->viewport();
        const QPointF pos = viewport->mapFromGlobal(wheel->globalPosition());
        QWheelEvent forwarded(pos, wheel->globalPosition(), wheel->pixelDelta(),
                              wheel->angleDelta(), wheel->buttons(), wheel->modifiers(),
                              wheel->phase(), wheel->inverted(), wheel->source(),
                              wheel->pointingDevice());
        QCoreApplication::sendEvent(viewport, &forwarded);
    }
    event->accept(); // handled: nothing else may take it as a value change
    return true;
}

} // namespace velvet::ui
