#include "ui/viewport_widget.h"

#include "core/color_management.h"
#include "core/image.h"
#include "render/camera.h"
#include "render/offscreen.h"
#include "render/progressive_accumulation.h"
#include "ui/texture_file_watcher.h"
#include "ui/worker_gl_context.h"

#include <QCoreApplication>
#include <QDropEvent>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QPainter>
#include <QTimer>
#include <QVBoxLayout>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace velvet::ui {
namespace {

constexpr int kFlyTickMs = 16;
constexpr int kGraphPollMs = 15; // while a graph program compiles: a frame every 15 ms

/// Renderer::environmentProgress() where a colleague's renderer has it; -1 otherwise. A template,
/// so the requires-expression is checked on the type, not as a hard error.
template <class R>
double environmentProgressOf(const R& renderer) {
    if constexpr (requires { double(renderer.environmentProgress()); })
        return double(renderer.environmentProgress());
    else
        return -1.0;
}

} // namespace

/// The native GL window. Everything it receives goes to its ViewportWidget; only what the
/// widget leaves unhandled goes on to QOpenGLWindow.
class ViewportWidget::Surface final : public QOpenGLWindow {
public:
    explicit Surface(ViewportWidget* owner)
        : QOpenGLWindow(QOpenGLWindow::NoPartialUpdate), m_owner(owner) {}

protected:
    void initializeGL() override { m_owner->initializeGL(); }
    void paintGL() override { m_owner->paintGL(); }
    void mousePressEvent(QMouseEvent* event) override {
        if (!m_owner->mousePress(event))
            QOpenGLWindow::mousePressEvent(event);
    }
    void mouseMoveEvent(QMouseEvent* event) override {
        if (!m_owner->mouseMove(event))
            QOpenGLWindow::mouseMoveEvent(event);
    }
    void mouseReleaseEvent(QMouseEvent* event) override {
        if (!m_owner->mouseRelease(event))
            QOpenGLWindow::mouseReleaseEvent(event);
    }
    void wheelEvent(QWheelEvent* event) override {
        if (!m_owner->wheel(event))
            QOpenGLWindow::wheelEvent(event);
    }
    void keyPressEvent(QKeyEvent* event) override {
        if (!m_owner->keyPress(event))
            QOpenGLWindow::keyPressEvent(event);
    }
    void keyReleaseEvent(QKeyEvent* event) override {
        if (!m_owner->keyRelease(event))
            QOpenGLWindow::keyReleaseEvent(event);
    }
    void focusOutEvent(QFocusEvent* event) override {
        m_owner->focusLost();
        QOpenGLWindow::focusOutEvent(event);
    }
    bool event(QEvent* event) override {
        switch (event->type()) {
        case QEvent::DragEnter:
        case QEvent::DragMove:
        case QEvent::DragLeave:
        case QEvent::Drop:
            m_owner->forwardDrag(event);
            return true;
        case QEvent::UpdateRequest:
            m_owner->m_updatePosted = false; // paints when the window is dirty (update())
            return QOpenGLWindow::event(event);
        default:
            return QOpenGLWindow::event(event);
        }
    }

private:
    ViewportWidget* m_owner;
};

ViewportWidget::ViewportWidget(QWidget* parent)
    : QWidget(parent), m_surface(new Surface(this)),
      m_container(QWidget::createWindowContainer(m_surface, this)), m_flyTimer(new QTimer(this)),
      m_refineTimer(new QTimer(this)), m_animationTimer(new QTimer(this)),
      m_progressiveTimer(new QTimer(this)), m_textureWatcher(new TextureFileWatcher(this)) {
    setObjectName(QStringLiteral("viewport"));
    m_surface->setObjectName(QStringLiteral("viewportWindow"));
    m_container->setObjectName(QStringLiteral("viewportContainer"));
    setMinimumSize(64, 64);
    // Focus given to the viewport (Tab, setFocus) activates the GL window, which then gets keys.
    m_container->setFocusPolicy(Qt::StrongFocus);
    setFocusPolicy(Qt::StrongFocus);
    setFocusProxy(m_container);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->setSpacing(0);
    layout->addWidget(m_container);

    connect(m_textureWatcher, &TextureFileWatcher::changed, this, &ViewportWidget::requestFrame);
    m_flyTimer->setInterval(kFlyTickMs);
    connect(m_flyTimer, &QTimer::timeout, this, &ViewportWidget::flyStep);
    m_refineTimer->setSingleShot(true);
    m_refineTimer->setInterval(kRefineDelayMs);
    connect(m_refineTimer, &QTimer::timeout, this, [this] {
        // Idle: draw once more at full size; but not before the reduced frame the stream asked
        // for has been drawn (a busy event loop can deliver this timer before that frame).
        if (m_interacting && !m_reducedFrameDrawn && isVisible()) {
            m_refineTimer->start();
            return;
        }
        m_interacting = false;
        if (m_lastRenderScale < 1.0f || (m_renderer && m_renderer->specialisationPending()))
            requestFrame();
    });
    // A timer rather than a request after every frame: a steady rate that leaves the event loop
    // time for input, instead of drawing as fast as llvmpipe can.
    m_animationTimer->setInterval(kAnimationIntervalMs);
    connect(m_animationTimer, &QTimer::timeout, this, &ViewportWidget::requestFrame);
    m_progressiveTimer->setSingleShot(true);
    connect(m_progressiveTimer, &QTimer::timeout, this, &ViewportWidget::progressiveStep);
}

QOpenGLWindow* ViewportWidget::glWindow() const {
    return m_surface;
}

void ViewportWidget::requestFrame() {
    restartProgressive(); // a change: the plain frame now, the refinement after a pause
    postFrame();
}

void ViewportWidget::postFrame() {
    m_surface->update(); // marks the window dirty and asks Qt for an update request
    // Qt delivers that request from a timer of QT_QPA_UPDATE_IDLE_TIME (5 ms by default): 5 ms
    // added to every frame, the whole of the viewport_overhead_ms budget. Post the request now;
    // the timer's later one finds the window clean and paints nothing. One in flight at a time.
    if (!m_updatePosted && m_surface->isExposed()) {
        m_updatePosted = true;
        QCoreApplication::postEvent(m_surface, new QEvent(QEvent::UpdateRequest));
    }
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
    // The GL window (and its context) goes now, while this object is whole: its signals and
    // events reach the members above.
    if (QOpenGLContext* context = m_surface->context())
        disconnect(context, nullptr, this, nullptr);
    delete m_container;
}

void ViewportWidget::releaseRenderer() {
    if (!m_renderer)
        return;
    // GL objects belong to our context: free them with it current (Krita's canvas does the same).
    m_surface->makeCurrent();
    m_grabTarget.reset();
    m_graphPreview.reset();
    m_renderer.reset();
    m_surface->doneCurrent();
}

void ViewportWidget::setScene(const Scene& scene, ScenePart parts) {
    // Only the parts that changed are copied, and only they reach the renderer at the next frame
    // (Renderer::update): a roughness tick re-packs one material record, nothing else.
    copyParts(m_scene, scene, parts);
    m_pendingParts |= parts;
    if (touches(parts, ScenePart::Material | ScenePart::Environment))
        m_textureWatcher->setScene(m_scene);
    if (!touches(parts, ~ScenePart::Atlases))
        return; // atlas documents are not drawn (their regions reach the slots as
                // MaterialStructure)
    noteInteraction();
    updateAnimation();
    requestFrame();
}

bool ViewportWidget::isAnimating() const {
    return !m_animationPaused && sceneReadsTime(m_scene);
}

double ViewportWidget::animationTime() const {
    const double running =
        m_animationClock.isValid() ? double(m_animationClock.nsecsElapsed()) / 1.0e9 : 0.0;
    return m_animatedSeconds + running;
}

void ViewportWidget::setAnimationPaused(bool paused) {
    m_animationPaused = paused;
    updateAnimation();
    requestFrame();
}

void ViewportWidget::updateAnimation() {
    const bool animate = isAnimating();
    if (animate == m_animationClock.isValid())
        return;
    if (animate) {
        m_animationClock.start();
        m_animationTimer->start();
    } else {
        m_animatedSeconds = animationTime(); // keep the time reached; go on from it later
        m_animationClock.invalidate();
        m_animationTimer->stop();
    }
}

void ViewportWidget::noteInteraction() {
    // The second change within the refine delay is a drag: reduce until it pauses. A change
    // under a held mouse drag streams however slow the frames between its moves are (a frame
    // slower than the delay is where reducing matters most).
    const bool streaming = m_drag != Drag::None || (m_lastInteraction.isValid() &&
                                                    m_lastInteraction.elapsed() < kRefineDelayMs);
    m_lastInteraction.start();
    if (!m_reducedEnabled)
        return;
    if (streaming) {
        m_interacting = true;
        m_reducedFrameDrawn = false;
    }
    m_refineTimer->start();
}

void ViewportWidget::setReducedResolution(bool enabled, float scale) {
    m_reducedEnabled = enabled;
    m_reducedScale = std::clamp(scale, 0.1f, 1.0f);
    if (!enabled) {
        m_interacting = false;
        m_refineTimer->stop();
    }
    requestFrame();
}

void ViewportWidget::resetView() {
    m_orbit.reset();
    requestFrame();
}

void ViewportWidget::setFrameSettings(const render::FrameSettings& settings) {
    m_settings = settings;
    requestFrame();
}

void ViewportWidget::setColorManagement(std::shared_ptr<const ColorManagement> colorManagement) {
    m_colorManagement = std::move(colorManagement);
    if (m_renderer && m_colorManagement) {
        m_surface->makeCurrent();
        m_renderer->setColorManagement(m_colorManagement);
        m_surface->doneCurrent();
        requestFrame();
    }
}

void ViewportWidget::frameMesh() {
    // The built-in meshes fit the unit sphere at the origin (core/mesh.h), which the default
    // Camera's distance frames at ~70 % of the height; an imported mesh is scaled into
    // [-1, 1]^3 (a cube's corners are sqrt 3 away), so the distance scales with the mesh's
    // bounding sphere (Renderer::meshRadius) to frame it the same way.
    Camera camera = viewCamera();
    const Camera framing;
    const float radius = m_renderer ? std::max(0.05f, m_renderer->meshRadius()) : 1.0f;
    camera.target = framing.target;
    camera.distance = framing.distance * radius;
    camera.orthoHeight = framing.orthoHeight * radius;
    setViewCamera(camera);
}

bool ViewportWidget::reloadShaders(QString* error) {
    if (!m_renderer) {
        if (error)
            *error = m_error.isEmpty() ? tr("No renderer to reload shaders into") : m_error;
        return false;
    }
    m_surface->makeCurrent();
    std::string message;
    const bool ok = m_renderer->reloadShaders(&message);
    m_surface->doneCurrent();
    if (!ok && error)
        *error = QString::fromStdString(message);
    requestFrame();
    return ok;
}

render::TextureLoadProgress ViewportWidget::textureProgress() const {
    return m_renderer ? m_renderer->textureProgress() : render::TextureLoadProgress{};
}

double ViewportWidget::environmentProgress() const {
    return m_renderer ? environmentProgressOf(*m_renderer) : -1.0;
}

void ViewportWidget::setViewCamera(const Camera& camera) {
    m_orbit = camera; // a per-frame setting (FrameSettings::camera): the scene is not touched
    emit viewCameraChanged(camera);
    noteInteraction();
    requestFrame();
}

Camera ViewportWidget::viewCamera() const {
    return m_orbit ? *m_orbit : m_scene.camera;
}

void ViewportWidget::initializeGL() {
    // The context may be recreated (the window was destroyed and created again): start over.
    m_grabTarget.reset();
    m_graphPreview.reset();
    m_renderer.reset();
    m_error.clear();
    QOpenGLContext* context = m_surface->context();
    connect(context, &QOpenGLContext::aboutToBeDestroyed, this, &ViewportWidget::releaseRenderer,
            Qt::UniqueConnection);

    const QSurfaceFormat format = context->format();
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
    // Texture files load on a worker thread and upload a bounded slice a frame: the window
    // keeps drawing (parameter value, then a coarse proxy) while a 4K map loads (issue 16).
    renderer->setAsyncTextures(true);
    // ... and a large texture's storage is made on a thread of its own, in this context's share
    // group, so that no frame waits while the driver zero-fills it
    // (render/texture_storage_thread.h).
    renderer->setTextureStorageContext(std::make_unique<WorkerGlContext>(context));
    renderer->setAsyncMeshBake(true);
    m_renderer = std::move(renderer);
    m_pendingParts = ScenePart::All; // a new renderer has none of the scene
}

QSize ViewportWidget::frameSize() const {
    // The renderer sizes its targets from the FrameSettings of each frame: nothing to resize.
    const qreal dpr = m_surface->devicePixelRatio();
    return {std::max(1, static_cast<int>(std::lround(m_surface->width() * dpr))),
            std::max(1, static_cast<int>(std::lround(m_surface->height() * dpr)))};
}

void ViewportWidget::paintGL() {
    if (!m_renderer) {
        paintError();
        return;
    }
    if (!drawFrame(m_surface->defaultFramebufferObject())) {
        paintError();
        return;
    }
    paintOverlay();
}

bool ViewportWidget::drawFrame(unsigned fbo, bool displayOnly, bool settledGrab) {
    // A grab (any other target) never adds to the refinement (below).
    const bool grab = fbo != m_surface->defaultFramebufferObject();
    if (m_pendingParts != ScenePart::None) {
        // A drawn change is never averaged with the frames before it (setScene asked the window
        // for its frame); atlas documents are not drawn: the mean stays what the view shows.
        if (touches(m_pendingParts, ~ScenePart::Atlases))
            restartProgressive();
        Problems problems;
        m_renderer->update(m_scene, m_pendingParts, &problems);
        m_pendingParts = ScenePart::None;
        QStringList lines;
        for (const Problem& p : problems.items)
            lines << QString::fromStdString(p.toString());
        // update runs on every scene change (each slider tick): report a problem list once,
        // not again while it stays the same.
        if (lines != m_lastSceneProblems && !lines.isEmpty())
            emit sceneProblems(lines);
        m_lastSceneProblems = lines;
    }
    render::FrameSettings settings = m_settings;
    settings.camera = viewCamera(); // the orbit, or the document's camera
    const QSize size = frameSize();
    settings.width = size.width();
    settings.height = size.height();
    settings.splitMaterial = m_splitMaterial;
    settings.splitPosition = m_splitPosition;
    settings.splitSwapped = m_splitSwapped;
    settings.renderScale = m_interacting && m_reducedEnabled ? m_reducedScale : 1.0f;
    // The camera moving under a drag or the fly keys: the stage's screen-space passes coarser
    // (a reduced frame is coarse already). mouseRelease() draws the view at rest again.
    const bool cameraDrag = m_drag == Drag::Orbit || m_drag == Drag::Pan || m_drag == Drag::Look;
    settings.navigating =
        (cameraDrag || m_flyTimer->isActive()) && settings.renderScale == 1.0f && !grab;
    settings.time = float(animationTime());
    settings.displayOnly = displayOnly;
    // A refinement frame (viewport_progressive.cpp). A grab draws the plain frame, or with
    // @p settledGrab the settled mean once there is one; one that reads the linear image draws
    // the plain frame, its reflections sampled as the settled view's are (below).
    // Resized while refining: the plain frame at the new size first, as after any change.
    if (!grab && m_progressiveIndex > 0 && size != m_progressiveSize)
        restartProgressive();
    const bool refined =
        grab ? settledGrab && m_progressiveIndex >= kProgressiveSamples : m_progressiveIndex >= 0;
    if (refined && settings.renderScale == 1.0f && displayOnly) {
        settings.accumulation = m_progressiveIndex;
        // Their linear images kept for the settled mean (setKeepsSettledLinear).
        if (!grab && m_keepSettledLinear)
            settings.displayOnly = false;
        settings.jitter = render::progressiveJitter(m_progressiveIndex);
        // The reflections sampled, each frame another set (FrameSettings::reflectionSamples).
        settings.reflectionSamples = render::kRefinementReflectionSamples;
        settings.reflectionSampleTotal = render::kRefinementReflectionSamples * kProgressiveSamples;
        settings.reflectionSampleSet = m_progressiveIndex;
    } else if (grab && !displayOnly && m_progressiveEnabled) {
        // A grab of the linear image (the Reference panel's comparison) stands for the view the
        // artist judges at rest: its reflections sampled as the settled mean holds them, in one
        // frame of four refinement frames' samples filtered as the mean's 256 (the panel's box
        // filter down to its width averages the rest; 32 filtered for 32 blurred the lamp behind
        // a copper sphere into its rim: mean ΔE2000 2.52 against the split sum's 2.46, this 1.11).
        settings.reflectionSamples = 4 * render::kRefinementReflectionSamples;
        settings.reflectionSampleTotal = render::kRefinementReflectionSamples * kProgressiveSamples;
    }

    QElapsedTimer timer;
    timer.start();
    std::string error;
    // A still view that has finished refining repaints (an expose, a grab) with its mean as it
    // is: the same picture every time, and nothing drawn.
    bool showMean = false;
    if (settings.accumulation >= kProgressiveSamples) {
        showMean = m_renderer->showAccumulated(settings.width, settings.height, fbo);
        if (!showMean) { // resized since: a plain frame, refined again after it
            restartProgressive();
            settings.accumulation = -1;
            settings.jitter = glm::vec2(0.0f);
            settings.reflectionSamples = 0;
        }
    }
    if (!showMean && !m_renderer->render(settings, fbo, &error)) {
        m_grabTarget.reset();
        m_graphPreview.reset();
        m_renderer.reset(); // keep the viewport alive; show what went wrong instead of drawing
        fail(tr("Rendering failed: %1").arg(QString::fromStdString(error)));
        return false;
    }
    // What the renderer noticed while drawing (no OCIO config, no encoding view): each once.
    if (const Problems warnings = m_renderer->takeWarnings(); !warnings.items.empty()) {
        QStringList lines;
        for (const Problem& p : warnings.items)
            lines << QString::fromStdString(p.toString());
        emit sceneProblems(lines);
    }
    ++m_frameCount;
    m_lastRenderScale = settings.renderScale;
    m_lastNavigating = settings.navigating;
    m_reducedFrameDrawn = m_reducedFrameDrawn || settings.renderScale < 1.0f;
    // A structural graph edit compiles on the driver's threads; the renderer adopts the new
    // program at a later frame, so keep frames coming (a short pause each: polling, not spinning).
    if (m_renderer->graphPending())
        QTimer::singleShot(kGraphPollMs, this, &ViewportWidget::requestFrame);
    // Textures loading or uploading, or a mesh's visibility baking: frames keep coming until
    // every one is complete.
    if (m_renderer->textureProgress().loading > 0 || m_renderer->meshBakePending())
        QTimer::singleShot(kGraphPollMs, this, &ViewportWidget::requestFrame);
    // A value edit drew with a generic program: once the edits pause, one more frame builds the
    // specialised one (render/lighting_features.h), so no compile ever lands inside a drag.
    if (m_renderer->specialisationPending())
        m_refineTimer->start();
    if (!grab && !showMean)
        keepLinearFrame(settings);
    if (!grab)
        progressiveFrameDrawn(settings);
    updateOverlay();
    emit frameCompleted(static_cast<double>(timer.nsecsElapsed()) / 1.0e6);
    return true;
}

QImage ViewportWidget::grabFramebuffer(Image* linear, bool settled) {
    if (!m_renderer || !m_surface->context())
        return {};
    m_surface->makeCurrent();
    QImage result;
    std::string error;
    if (!m_grabTarget)
        m_grabTarget = std::make_unique<render::OffscreenTarget>();
    const QSize size = frameSize();
    if (!m_grabTarget->resize(size.width(), size.height(), &error)) {
        qWarning("velvet: grabFramebuffer: %s", error.c_str());
    } else if (drawFrame(m_grabTarget->framebuffer(), /*displayOnly=*/linear == nullptr, settled)) {
        const Image frame = m_renderer->readDisplay(); // top row first, display-encoded RGBA
        result = QImage(frame.width, frame.height, QImage::Format_RGB32);
        for (int y = 0; y < frame.height; ++y) {
            auto* line = reinterpret_cast<QRgb*>(result.scanLine(y));
            for (int x = 0; x < frame.width; ++x) {
                const float* p = frame.at(x, y);
                const auto byte = [](float v) {
                    return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
                };
                line[x] = qRgb(byte(p[0]), byte(p[1]), byte(p[2]));
            }
        }
        result.setDevicePixelRatio(m_surface->devicePixelRatio());
        if (linear)
            *linear = m_renderer->readLinear();
    } else {
        requestFrame(); // the window shows the error
    }
    m_surface->doneCurrent();
    return result;
}

std::vector<Image>
ViewportWidget::renderGraphPreviews(const graph::Graph& graph,
                                    const std::vector<render::PreviewRequest>& requests,
                                    Problems* problems) {
    if (!m_renderer || !m_surface->context())
        return {};
    m_surface->makeCurrent();
    if (!m_graphPreview)
        m_graphPreview = std::make_unique<render::GraphPreview>();
    std::vector<Image> images =
        m_graphPreview->render(graph, requests, &m_renderer->graphTextureCache(), problems);
    m_surface->doneCurrent();
    return images;
}

void ViewportWidget::fail(const QString& message) {
    m_error = message;
    qWarning("velvet: %s", qPrintable(message));
    emit renderFailed(message);
}

} // namespace velvet::ui
