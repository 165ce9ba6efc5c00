#include "ui/viewport_widget.h"

#include <QElapsedTimer>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QPainter>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

namespace velvet::ui {
namespace {

constexpr float kOrbitDegPerPixel = 0.4f;
constexpr float kMaxPitchDeg = 89.0f;
constexpr float kZoomPerNotch = 0.9f; // distance factor per 15° wheel notch
constexpr float kMinDistance = 0.2f;
constexpr float kMaxDistance = 50.0f;

} // namespace

ViewportWidget::ViewportWidget(QWidget* parent) : QOpenGLWidget(parent) {
    setObjectName(QStringLiteral("viewport"));
    setMinimumSize(64, 64);
    setFocusPolicy(Qt::ClickFocus);
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
    if (event->button() == Qt::LeftButton) {
        m_dragging = true;
        m_lastMouse = event->position().toPoint();
        event->accept();
        return;
    }
    QOpenGLWidget::mousePressEvent(event);
}

void ViewportWidget::mouseMoveEvent(QMouseEvent* event) {
    if (!m_dragging) {
        QOpenGLWidget::mouseMoveEvent(event);
        return;
    }
    const QPoint pos = event->position().toPoint();
    const QPoint delta = pos - m_lastMouse;
    m_lastMouse = pos;
    Camera camera = viewCamera();
    camera.yawDeg = std::fmod(camera.yawDeg - delta.x() * kOrbitDegPerPixel, 360.0f);
    camera.pitchDeg =
        std::clamp(camera.pitchDeg + delta.y() * kOrbitDegPerPixel, -kMaxPitchDeg, kMaxPitchDeg);
    m_orbit = camera;
    m_sceneDirty = true;
    update();
}

void ViewportWidget::mouseReleaseEvent(QMouseEvent* event) {
    if (event->button() == Qt::LeftButton)
        m_dragging = false;
    QOpenGLWidget::mouseReleaseEvent(event);
}

void ViewportWidget::wheelEvent(QWheelEvent* event) {
    const float notches = static_cast<float>(event->angleDelta().y()) / 120.0f;
    if (notches == 0.0f)
        return;
    Camera camera = viewCamera();
    camera.distance =
        std::clamp(camera.distance * std::pow(kZoomPerNotch, notches), kMinDistance, kMaxDistance);
    camera.orthoHeight = std::max(0.05f, camera.orthoHeight * std::pow(kZoomPerNotch, notches));
    m_orbit = camera;
    m_sceneDirty = true;
    update();
    event->accept();
}

} // namespace velvet::ui
