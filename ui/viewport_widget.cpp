#include "ui/viewport_widget.h"

#include "core/color_management.h"
#include "render/camera.h"
#include "ui/commands/set_scene_command.h"

#include <QKeyEvent>
#include <QLabel>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QPainter>
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
constexpr float kLookDegPerPixel = 0.2f;
constexpr float kEnvironmentDegPerPixel = 0.5f; // a 720-pixel drag turns the HDRI once
constexpr float kFlySpeedPerDistance = 0.8f;    // metres per second per metre of distance
constexpr int kFlyTickMs = 16;

/// Renderer::environmentProgress() where a colleague's renderer has it; -1 otherwise. A template,
/// so the requires-expression is checked on the type, not as a hard error.
template <class R>
double environmentProgressOf(const R& renderer) {
    if constexpr (requires { double(renderer.environmentProgress()); })
        return double(renderer.environmentProgress());
    else
        return -1.0;
}

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

ViewportWidget::ViewportWidget(QWidget* parent)
    : QOpenGLWidget(parent), m_flyTimer(new QTimer(this)), m_overlay(new QLabel(this)),
      m_refineTimer(new QTimer(this)) {
    setObjectName(QStringLiteral("viewport"));
    setMinimumSize(64, 64);
    setFocusPolicy(Qt::StrongFocus);
    m_flyTimer->setInterval(kFlyTickMs);
    connect(m_flyTimer, &QTimer::timeout, this, &ViewportWidget::flyStep);
    m_refineTimer->setSingleShot(true);
    m_refineTimer->setInterval(kRefineDelayMs);
    connect(m_refineTimer, &QTimer::timeout, this, [this] {
        // Idle: draw once more at full size.
        m_interacting = false;
        if (m_lastRenderScale < 1.0f)
            update();
    });

    // A plain widget over the GL surface: Qt composes it, ui/ draws nothing with GL.
    m_overlay->setObjectName(QStringLiteral("timingOverlay"));
    m_overlay->setAttribute(Qt::WA_TransparentForMouseEvents);
    m_overlay->setStyleSheet(
        QStringLiteral("QLabel { background: rgba(0, 0, 0, 150); color: #e0e0e0; padding: 4px; "
                       "font-family: monospace; }"));
    m_overlay->move(8, 8);
    m_overlay->hide();
}

QSurfaceFormat ViewportWidget::requiredFormat() {
    QSurfaceFormat format;
    format.setRenderableType(QSurfaceFormat::OpenGL);
    format.setVersion(4, 5);
    format.setProfile(QSurfaceFormat::CoreProfile);
    format.setDepthBufferSize(24);
    format.setStencilBufferSize(8);
    return format;
}

ViewportWidget::~ViewportWidget() {
    releaseRenderer();
}

void ViewportWidget::releaseRenderer() {
    if (!m_renderer)
        return;
    // GL objects belong to our context: free them with it current (Krita's canvas does the same).
    makeCurrent();
    m_renderer.reset();
    doneCurrent();
}

void ViewportWidget::setScene(const Scene& scene) {
    m_scene = scene;
    m_sceneDirty = true;
    noteInteraction();
    update();
}

void ViewportWidget::noteInteraction() {
    // The second change within the refine delay is a drag: reduce until it pauses.
    const bool streaming =
        m_lastInteraction.isValid() && m_lastInteraction.elapsed() < kRefineDelayMs;
    m_lastInteraction.start();
    if (!m_reducedEnabled)
        return;
    if (streaming)
        m_interacting = true;
    m_refineTimer->start();
}

void ViewportWidget::setSplitMaterial(std::optional<Material> b) {
    m_splitMaterial = std::move(b);
    update();
}

void ViewportWidget::setSplitPosition(float fraction) {
    m_splitPosition = std::clamp(fraction, 0.0f, 1.0f);
    update();
}

void ViewportWidget::setReducedResolution(bool enabled, float scale) {
    m_reducedEnabled = enabled;
    m_reducedScale = std::clamp(scale, 0.1f, 1.0f);
    if (!enabled) {
        m_interacting = false;
        m_refineTimer->stop();
    }
    update();
}

void ViewportWidget::resetView() {
    m_orbit.reset();
    m_sceneDirty = true;
    update();
}

void ViewportWidget::setFrameSettings(const render::FrameSettings& settings) {
    m_settings = settings;
    update();
}

void ViewportWidget::setColorManagement(std::shared_ptr<const ColorManagement> colorManagement) {
    m_colorManagement = std::move(colorManagement);
    if (m_renderer && m_colorManagement) {
        makeCurrent();
        m_renderer->setColorManagement(m_colorManagement);
        doneCurrent();
        update();
    }
}

void ViewportWidget::setTimingOverlayVisible(bool visible) {
    m_overlay->setVisible(visible);
    updateOverlay();
    update();
}

bool ViewportWidget::isTimingOverlayVisible() const {
    return m_overlay->isVisible();
}

void ViewportWidget::frameMesh() {
    // Every preview mesh is modelled to fit the unit sphere at the origin (core/mesh.h), which
    // the default Camera's distance frames at ~70 % of the height.
    Camera camera = viewCamera();
    const Camera framing;
    camera.target = framing.target;
    camera.distance = framing.distance;
    camera.orthoHeight = framing.orthoHeight;
    setViewCamera(camera);
}

bool ViewportWidget::reloadShaders(QString* error) {
    if (!m_renderer) {
        if (error)
            *error = m_error.isEmpty() ? tr("No renderer to reload shaders into") : m_error;
        return false;
    }
    makeCurrent();
    std::string message;
    const bool ok = m_renderer->reloadShaders(&message);
    doneCurrent();
    if (!ok && error)
        *error = QString::fromStdString(message);
    update();
    return ok;
}

double ViewportWidget::environmentProgress() const {
    return m_renderer ? environmentProgressOf(*m_renderer) : -1.0;
}

void ViewportWidget::setViewCamera(const Camera& camera) {
    m_orbit = camera;
    m_sceneDirty = true;
    noteInteraction();
    update();
}

void ViewportWidget::updateOverlay() {
    if (!m_overlay->isVisible())
        return;
    if (!m_renderer) {
        m_overlay->setText(tr("no renderer"));
    } else {
        // Called from paintGL (or with no frame yet): lastTimings reads GL queries, so only ask
        // while our context is current.
        const render::FrameTimings t = QOpenGLContext::currentContext() == context()
                                           ? m_renderer->lastTimings()
                                           : render::FrameTimings{};
        if (t.totalMs <= 0.0) {
            m_overlay->setText(tr("GPU timings unavailable"));
        } else {
            m_overlay->setText(tr("G-buffer  %1 ms\nLighting  %2 ms\nPost      %3 ms\n"
                                  "Total     %4 ms")
                                   .arg(t.gbufferMs, 6, 'f', 2)
                                   .arg(t.lightingMs, 6, 'f', 2)
                                   .arg(t.postMs, 6, 'f', 2)
                                   .arg(t.totalMs, 6, 'f', 2));
        }
    }
    m_overlay->adjustSize();
}

Camera ViewportWidget::viewCamera() const {
    return m_orbit ? *m_orbit : m_scene.camera;
}

void ViewportWidget::initializeGL() {
    // The context may be recreated (the widget moved to another top-level window): start over.
    m_renderer.reset();
    m_error.clear();
    connect(context(), &QOpenGLContext::aboutToBeDestroyed, this, &ViewportWidget::releaseRenderer,
            Qt::UniqueConnection);

    const QSurfaceFormat format = context()->format();
    if (format.version() < qMakePair(4, 5) || format.profile() != QSurfaceFormat::CoreProfile) {
        fail(tr("OpenGL 4.5 core is needed; this context is %1.%2")
                 .arg(format.majorVersion())
                 .arg(format.minorVersion()));
        return;
    }
    auto renderer = std::make_unique<render::Renderer>();
    std::string error;
    if (!renderer->initialize(&error)) {
        fail(tr("The renderer could not start: %1").arg(QString::fromStdString(error)));
        return;
    }
    if (m_colorManagement)
        renderer->setColorManagement(m_colorManagement);
    m_renderer = std::move(renderer);
    m_sceneDirty = true;
}

void ViewportWidget::resizeGL(int, int) {
    // Nothing to forward: the renderer sizes its targets from the FrameSettings of each frame.
}

void ViewportWidget::paintGL() {
    if (!m_renderer) {
        paintError();
        return;
    }
    if (m_sceneDirty) {
        Scene scene = m_scene;
        if (m_orbit)
            scene.camera = *m_orbit;
        Problems problems;
        m_renderer->setScene(scene, &problems);
        m_sceneDirty = false;
        if (!problems.items.empty()) {
            QStringList lines;
            for (const Problem& p : problems.items)
                lines << QString::fromStdString(p.toString());
            emit sceneProblems(lines);
        }
    }
    render::FrameSettings settings = m_settings;
    const qreal dpr = devicePixelRatioF();
    settings.width = std::max(1, static_cast<int>(std::lround(width() * dpr)));
    settings.height = std::max(1, static_cast<int>(std::lround(height() * dpr)));
    settings.splitMaterial = m_splitMaterial;
    settings.splitPosition = m_splitPosition;
    settings.renderScale = m_interacting && m_reducedEnabled ? m_reducedScale : 1.0f;

    QElapsedTimer timer;
    timer.start();
    std::string error;
    if (!m_renderer->render(settings, defaultFramebufferObject(), &error)) {
        m_renderer.reset(); // keep the widget alive; show what went wrong instead of drawing
        fail(tr("Rendering failed: %1").arg(QString::fromStdString(error)));
        paintError();
        return;
    }
    ++m_frameCount;
    m_lastRenderScale = settings.renderScale;
    updateOverlay();
    emit frameCompleted(static_cast<double>(timer.nsecsElapsed()) / 1.0e6);
}

void ViewportWidget::fail(const QString& message) {
    m_error = message;
    qWarning("velvet: %s", qPrintable(message));
    emit renderFailed(message);
}

void ViewportWidget::paintError() {
    // QPainter on a QOpenGLWidget: Qt's paint engine draws the message, ui/ issues no GL itself.
    QPainter painter(this);
    painter.fillRect(rect(), QColor(40, 40, 40));
    painter.setPen(QColor(230, 120, 120));
    painter.drawText(rect().adjusted(16, 16, -16, -16), Qt::AlignCenter | Qt::TextWordWrap,
                     m_error.isEmpty() ? tr("No renderer") : m_error);
}

void ViewportWidget::mousePressEvent(QMouseEvent* event) {
    if (m_drag != Drag::None) {
        event->accept();
        return;
    }
    switch (event->button()) {
    case Qt::LeftButton:
        m_drag = Drag::Orbit;
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
        QOpenGLWidget::mousePressEvent(event);
        return;
    }
    m_lastMouse = event->position().toPoint();
    setFocus(Qt::MouseFocusReason);
    event->accept();
}

void ViewportWidget::mouseMoveEvent(QMouseEvent* event) {
    if (m_drag == Drag::None) {
        QOpenGLWidget::mouseMoveEvent(event);
        return;
    }
    const QPoint pos = event->position().toPoint();
    const QPoint delta = pos - m_lastMouse;
    m_lastMouse = pos;
    if (delta.isNull())
        return;
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
        const float metresPerPixel = visibleHeight / float(std::max(1, height()));
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
        event->accept();
        return;
    case Drag::None:
        break;
    }
    setViewCamera(camera);
    event->accept();
}

void ViewportWidget::mouseReleaseEvent(QMouseEvent* event) {
    const bool ends = (m_drag == Drag::Orbit && event->button() == Qt::LeftButton) ||
                      (m_drag == Drag::Pan && event->button() == Qt::MiddleButton) ||
                      ((m_drag == Drag::Look || m_drag == Drag::RotateEnvironment) &&
                       event->button() == Qt::RightButton);
    if (ends) {
        m_drag = Drag::None;
        m_flyTimer->stop();
        event->accept();
        return;
    }
    QOpenGLWidget::mouseReleaseEvent(event);
}

void ViewportWidget::keyPressEvent(QKeyEvent* event) {
    if (isFlyKey(event->key()) && !event->isAutoRepeat()) {
        m_flyKeys.insert(event->key());
        if (m_drag == Drag::Look && !m_flyTimer->isActive()) {
            m_flyClock.start();
            m_flyTimer->start();
        }
        event->accept();
        return;
    }
    QOpenGLWidget::keyPressEvent(event);
}

void ViewportWidget::keyReleaseEvent(QKeyEvent* event) {
    if (isFlyKey(event->key()) && !event->isAutoRepeat()) {
        m_flyKeys.remove(event->key());
        if (m_flyKeys.isEmpty())
            m_flyTimer->stop();
        event->accept();
        return;
    }
    QOpenGLWidget::keyReleaseEvent(event);
}

void ViewportWidget::focusOutEvent(QFocusEvent* event) {
    // Keys released elsewhere never reach us: stop flying rather than drift forever.
    m_flyKeys.clear();
    m_flyTimer->stop();
    QOpenGLWidget::focusOutEvent(event);
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

void ViewportWidget::wheelEvent(QWheelEvent* event) {
    const float notches = static_cast<float>(event->angleDelta().y()) / 120.0f;
    if (notches == 0.0f)
        return;
    Camera camera = viewCamera();
    camera.distance =
        std::clamp(camera.distance * std::pow(kZoomPerNotch, notches), kMinDistance, kMaxDistance);
    camera.orthoHeight = std::max(0.05f, camera.orthoHeight * std::pow(kZoomPerNotch, notches));
    setViewCamera(camera);
    event->accept();
}

} // namespace velvet::ui
