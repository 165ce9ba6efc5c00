// The viewport's navigation (ViewportWidget's input half): orbit, pan, look and HDRI rotation
// drags, fly keys, the wheel's zoom. Each move is a per-frame camera (setViewCamera), never a
// scene edit; only Shift + right drag edits the document (the environment's rotation). And the
// drags of files and presets over the native GL window, handed to the widget that takes drops.
#include "render/camera.h"
#include "ui/commands/set_scene_command.h"
#include "ui/viewport_widget.h"

#include <QCoreApplication>
#include <QDropEvent>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLWindow>
#include <QTimer>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace velvet::ui {
namespace {

constexpr float kOrbitDegPerPixel = 0.4f;
constexpr float kMaxPitchDeg = 89.0f;
constexpr float kZoomPerNotch = 0.9f; // distance factor per 15° wheel notch
constexpr float kMinDistance = 0.2f;
constexpr float kMaxDistance = 50.0f;
constexpr float kMinOrthoHeight = 0.05f;
constexpr float kMaxOrthoHeight = 1000.0f;
constexpr float kLookDegPerPixel = 0.2f;
constexpr float kEnvironmentDegPerPixel = 0.5f; // a 720-pixel drag turns the HDRI once
constexpr float kFlySpeedPerDistance = 0.8f;    // metres per second per metre of distance

bool isFlyKey(int key) {
    switch (key) {
    case Qt::Key_W:
    case Qt::Key_A:
    case Qt::Key_S:
    case Qt::Key_D:
    case Qt::Key_Q:
    case Qt::Key_E:
        return true;
    default:
        return false;
    }
}

/// Unit vector from the target to the eye (render::cameraEye's convention).
glm::vec3 orbitOffset(const Camera& c) {
    const float yaw = glm::radians(c.yawDeg), pitch = glm::radians(c.pitchDeg);
    return {std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw)};
}

} // namespace

bool ViewportWidget::mousePress(QMouseEvent* event) {
    if (m_drag != Drag::None) {
        event->accept();
        return true;
    }
    switch (event->button()) {
    case Qt::LeftButton:
        // On the A/B seam: drag the seam, not the view.
        m_drag =
            m_splitMaterial && std::abs(event->position().x() - splitSeamX()) <= kSeamGrabPixels
                ? Drag::Seam
                : Drag::Orbit;
        break;
    case Qt::MiddleButton:
        m_drag = Drag::Pan;
        break;
    case Qt::RightButton:
        if (event->modifiers() & Qt::ShiftModifier) {
            m_drag = Drag::RotateEnvironment;
            m_gestureKey = SetEnvironmentCommand::nextMergeKey();
        } else {
            m_drag = Drag::Look;
            m_flyClock.start();
            if (!m_flyKeys.isEmpty())
                m_flyTimer->start();
        }
        break;
    default:
        return false;
    }
    m_lastMouse = event->position().toPoint();
    glWindow()->requestActivate(); // keys (fly mode) come to the GL window
    event->accept();
    return true;
}

bool ViewportWidget::mouseMove(QMouseEvent* event) {
    if (m_drag == Drag::None) {
        // Hovering the seam shows that it can be dragged.
        const bool onSeam =
            m_splitMaterial && std::abs(event->position().x() - splitSeamX()) <= kSeamGrabPixels;
        if (onSeam)
            glWindow()->setCursor(Qt::SplitHCursor);
        else
            glWindow()->unsetCursor();
        return false;
    }
    if (m_drag == Drag::Seam) {
        const int width = std::max(1, glWindow()->width());
        setSplitPosition(float(event->position().x() / width));
        emit splitPositionChanged(m_splitPosition);
        event->accept();
        return true;
    }
    const QPoint pos = event->position().toPoint();
    const QPoint delta = pos - m_lastMouse;
    m_lastMouse = pos;
    event->accept();
    if (delta.isNull())
        return true;
    Camera camera = viewCamera();
    switch (m_drag) {
    case Drag::Orbit:
        camera.yawDeg = std::fmod(camera.yawDeg - delta.x() * kOrbitDegPerPixel, 360.0f);
        camera.pitchDeg = std::clamp(camera.pitchDeg + delta.y() * kOrbitDegPerPixel, -kMaxPitchDeg,
                                     kMaxPitchDeg);
        break;
    case Drag::Pan: {
        // Move the target in the view plane so the point under the cursor follows it.
        const glm::mat4 view = render::viewMatrix(camera);
        const glm::vec3 right(view[0][0], view[1][0], view[2][0]);
        const glm::vec3 up(view[0][1], view[1][1], view[2][1]);
        const float visibleHeight =
            camera.orthographic
                ? camera.orthoHeight
                : 2.0f * camera.distance * std::tan(glm::radians(camera.fovYDeg) * 0.5f);
        const float metresPerPixel = visibleHeight / float(std::max(1, glWindow()->height()));
        camera.target += metresPerPixel * (-float(delta.x()) * right + float(delta.y()) * up);
        break;
    }
    case Drag::Look: {
        // Turn the camera about its eye: the eye stays, the target moves.
        const glm::vec3 eye = render::cameraEye(camera);
        camera.yawDeg = std::fmod(camera.yawDeg - delta.x() * kLookDegPerPixel, 360.0f);
        camera.pitchDeg =
            std::clamp(camera.pitchDeg + delta.y() * kLookDegPerPixel, -kMaxPitchDeg, kMaxPitchDeg);
        camera.target = eye - camera.distance * orbitOffset(camera);
        break;
    }
    case Drag::RotateEnvironment:
        emit environmentRotationDragged(float(delta.x()) * kEnvironmentDegPerPixel, m_gestureKey);
        return true;
    case Drag::None:
    case Drag::Seam:
        break;
    }
    setViewCamera(camera);
    return true;
}

bool ViewportWidget::mouseRelease(QMouseEvent* event) {
    const bool ends =
        ((m_drag == Drag::Orbit || m_drag == Drag::Seam) && event->button() == Qt::LeftButton) ||
        (m_drag == Drag::Pan && event->button() == Qt::MiddleButton) ||
        ((m_drag == Drag::Look || m_drag == Drag::RotateEnvironment) &&
         event->button() == Qt::RightButton);
    if (ends) {
        m_drag = Drag::None;
        m_flyTimer->stop();
        if (m_lastNavigating) // its stage was drawn coarser: the view at rest draws it again
            requestFrame();
        event->accept();
        return true;
    }
    return false;
}

bool ViewportWidget::keyPress(QKeyEvent* event) {
    if (isFlyKey(event->key()) && !event->isAutoRepeat()) {
        m_flyKeys.insert(event->key());
        if (m_drag == Drag::Look && !m_flyTimer->isActive()) {
            m_flyClock.start();
            m_flyTimer->start();
        }
        event->accept();
        return true;
    }
    return false;
}

bool ViewportWidget::keyRelease(QKeyEvent* event) {
    if (isFlyKey(event->key()) && !event->isAutoRepeat()) {
        m_flyKeys.remove(event->key());
        if (m_flyKeys.isEmpty())
            m_flyTimer->stop();
        event->accept();
        return true;
    }
    return false;
}

void ViewportWidget::focusLost() {
    // Keys released elsewhere never reach us: stop flying rather than drift forever.
    m_flyKeys.clear();
    m_flyTimer->stop();
}

void ViewportWidget::flyStep() {
    if (m_drag != Drag::Look || m_flyKeys.isEmpty()) {
        m_flyTimer->stop();
        return;
    }
    const float seconds = std::min(0.1f, float(m_flyClock.restart()) / 1000.0f);
    Camera camera = viewCamera();
    const glm::vec3 forward = -orbitOffset(camera);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    glm::vec3 move(0.0f);
    if (m_flyKeys.contains(Qt::Key_W))
        move += forward;
    if (m_flyKeys.contains(Qt::Key_S))
        move -= forward;
    if (m_flyKeys.contains(Qt::Key_D))
        move += right;
    if (m_flyKeys.contains(Qt::Key_A))
        move -= right;
    if (m_flyKeys.contains(Qt::Key_E))
        move += up;
    if (m_flyKeys.contains(Qt::Key_Q))
        move -= up;
    if (glm::length(move) < 1e-6f)
        return;
    const float speed = kFlySpeedPerDistance * std::max(0.5f, camera.distance);
    camera.target += glm::normalize(move) * speed * seconds;
    setViewCamera(camera);
}

bool ViewportWidget::wheel(QWheelEvent* event) {
    const float notches = static_cast<float>(event->angleDelta().y()) / 120.0f;
    if (notches == 0.0f)
        return false;
    Camera camera = viewCamera();
    camera.distance =
        std::clamp(camera.distance * std::pow(kZoomPerNotch, notches), kMinDistance, kMaxDistance);
    // Bounded as the distance is, well inside the scene schema's lengths (docs/file-formats.md,
    // "Bounds"), so the editor never saves a view its own reader would refuse.
    camera.orthoHeight = std::clamp(camera.orthoHeight * std::pow(kZoomPerNotch, notches),
                                    kMinOrthoHeight, kMaxOrthoHeight);
    setViewCamera(camera);
    event->accept();
    return true;
}

void ViewportWidget::forwardDrag(QEvent* event) {
    // What QWidgetWindow does for widgets: the nearest ancestor accepting drops gets the drag,
    // enter, moves and drop, in its own coordinates.
    if (event->type() == QEvent::DragEnter) {
        m_dragTarget = nullptr;
        for (QWidget* w = this; w; w = w->isWindow() ? nullptr : w->parentWidget())
            if (w->acceptDrops() && w->isEnabled()) {
                m_dragTarget = w;
                break;
            }
    }
    QWidget* target = m_dragTarget;
    if (!target) {
        event->ignore();
        return;
    }
    if (event->type() == QEvent::DragLeave) {
        QDragLeaveEvent leave;
        QCoreApplication::sendEvent(target, &leave);
        m_dragTarget = nullptr;
        return;
    }
    auto* drop = static_cast<QDropEvent*>(event); // QDragEnterEvent and QDragMoveEvent derive
    const QPoint pos = m_container->mapTo(target, drop->position().toPoint());
    switch (event->type()) {
    case QEvent::DragEnter: {
        QDragEnterEvent enter(pos, drop->possibleActions(), drop->mimeData(), drop->buttons(),
                              drop->modifiers());
        enter.setAccepted(false);
        QCoreApplication::sendEvent(target, &enter);
        drop->setDropAction(enter.dropAction());
        drop->setAccepted(enter.isAccepted());
        if (!enter.isAccepted())
            m_dragTarget = nullptr; // refused at the door: no moves, no drop
        break;
    }
    case QEvent::DragMove: {
        QDragMoveEvent move(pos, drop->possibleActions(), drop->mimeData(), drop->buttons(),
                            drop->modifiers());
        move.setDropAction(drop->dropAction());
        move.setAccepted(drop->isAccepted());
        QCoreApplication::sendEvent(target, &move);
        drop->setDropAction(move.dropAction());
        drop->setAccepted(move.isAccepted());
        break;
    }
    case QEvent::Drop: {
        QDropEvent dropped(QPointF(pos), drop->possibleActions(), drop->mimeData(), drop->buttons(),
                           drop->modifiers());
        dropped.setDropAction(drop->dropAction());
        dropped.setAccepted(false);
        QCoreApplication::sendEvent(target, &dropped);
        drop->setDropAction(dropped.dropAction());
        drop->setAccepted(dropped.isAccepted());
        m_dragTarget = nullptr;
        break;
    }
    default:
        break;
    }
}

} // namespace velvet::ui
