#pragma once
/// @file viewport_widget.h
/// The 3D viewport: a thin QWidget hosting a QOpenGLWindow through QWidget::createWindowContainer
/// (a QOpenGLWidget made Qt read back and compose every frame, ~30 ms on llvmpipe;
/// BENCHMARKS.md, "Responsiveness"). The window forwards initializeGL / paintGL and its input
/// events here; this class calls velvet::render::Renderer and holds no GL logic of its own
/// (DESIGN.md, "Layers"). Setters store a value, mark it dirty and request a frame; the paint hands
/// dirty state to the renderer.
///
/// Navigation (view state, never in the document): left drag orbits, middle drag pans, the wheel
/// zooms, right drag looks around (fly mode) while W A S D Q E move, F frames the mesh.
/// Shift + right drag rotates the HDRI: that is a document edit, so the widget only reports it
/// (environmentRotationDragged) and the window turns it into an undoable command.
///
/// The GL window is a native child window: drags and drops over it are forwarded to the nearest
/// ancestor widget that accepts drops (the main window), with positions mapped; the main window's
/// shortcuts (F, T, Ctrl+Z…) reach it through Qt's shortcut map while the GL window has focus;
/// QWidget::grab does not capture it, so screenshots compose grabFramebuffer() themselves
/// (ui/screenshot.h).

#include "core/image_ops.h"
#include "core/scene.h"
#include "core/scene_parts.h"
#include "render/graph_preview.h"
#include "render/renderer.h"

#include <QElapsedTimer>
#include <QImage>
#include <QOpenGLWindow>
#include <QPoint>
#include <QPointer>
#include <QSet>
#include <QString>
#include <QStringList>
#include <QSurfaceFormat>
#include <QWidget>
#include <memory>
#include <optional>

class QKeyEvent;
class QPainter;
class QMouseEvent;
class QTimer;
class QWheelEvent;

namespace velvet {
class ColorManagement;
}

namespace velvet::render {
class OffscreenTarget;
}

namespace velvet::ui {

class TextureFileWatcher;

class ViewportWidget : public QWidget {
    Q_OBJECT
public:
    explicit ViewportWidget(QWidget* parent = nullptr);
    /// The surface format the renderer needs (OpenGL 4.5 core, 24-bit depth). Set it with
    /// QSurfaceFormat::setDefaultFormat before the QApplication is created.
    static QSurfaceFormat requiredFormat();
    /// Frees the renderer with the GL window's context current.
    ~ViewportWidget() override;

    /// The parts @p parts of @p scene changed (DocumentController::sceneChanged): they are
    /// copied and reach the renderer at the next frame (Renderer::update), the rest is kept.
    /// The camera the viewport draws is the orbit (a per-frame setting) or the scene's.
    void setScene(const Scene& scene, ScenePart parts = ScenePart::All);
    /// Forgets orbit/zoom and shows the scene's own camera again (on new/open).
    void resetView();
    /// Frame settings other than the size (exposure, tone mapper, debug view).
    void setFrameSettings(const render::FrameSettings& settings);
    const render::FrameSettings& frameSettings() const { return m_settings; }
    /// The OCIO config the display transform uses (shared with the toolbar and pickers).
    void setColorManagement(std::shared_ptr<const ColorManagement> colorManagement);
    /// @name A/B split
    /// Set: the right part of the viewport (from splitPosition, a fraction of the width) shows
    /// material @p b, the left the document's material (render::FrameSettings::splitMaterial).
    /// Unset: one material over the whole viewport. View state, never in the document.
    /// @{
    void setSplitMaterial(std::optional<Material> b);
    const std::optional<Material>& splitMaterial() const { return m_splitMaterial; }
    void setSplitPosition(float fraction);
    float splitPosition() const { return m_splitPosition; }
    /// What B is ("snapshot of A", "gold", "A with Beckmann"): drawn in B's label over the frame.
    void setSplitLabel(const QString& label);
    QString splitLabel() const { return m_splitLabel; }
    /// B left of the seam and A right of it (the X shortcut swaps).
    void setSplitSwapped(bool swapped);
    bool splitSwapped() const { return m_splitSwapped; }
    /// The seam's x in the viewport's (and the GL window's) logical coordinates.
    int splitSeamX() const;
    /// Whether x (viewport coordinates) is on B's side of the seam; false without a split.
    bool isOnSplitB(int x) const;
    /// The divider and the A / B labels, drawn over the frame by Qt's paint engine while the
    /// split is on (nothing otherwise); also what grabDecorated() adds to a frame.
    void paintSplitDecorations(QPainter& painter, QSize size) const;
    /// grabFramebuffer(settled) with the split's divider and labels painted over it (what the
    /// artist sees; screenshots).
    QImage grabDecorated();
    /// A press within this many pixels of the seam drags it instead of orbiting.
    static constexpr int kSeamGrabPixels = 6;
    /// @}
    /// @name Reduced resolution while editing
    /// A scene or camera change that comes within kRefineDelayMs of the previous one (a slider
    /// or orbit drag) renders at reducedScale() of the size; kRefineDelayMs after the last change
    /// the viewport draws once more at full size. A single edit draws at full size at once.
    /// @{
    static constexpr int kRefineDelayMs = 150;
    void setReducedResolution(bool enabled, float scale = 0.5f);
    bool reducedResolutionEnabled() const { return m_reducedEnabled; }
    float reducedScale() const { return m_reducedScale; }
    /// The render scale of the last frame drawn (1 at full size).
    float lastRenderScale() const { return m_lastRenderScale; }
    /// Whether the last frame was drawn as the camera moved (an orbit, pan or look drag, or
    /// fly keys) at full size: its look-dev stage's shadow masks and occlusion at a quarter
    /// (FrameSettings::navigating); the release of the drag draws the view at rest again.
    bool lastFrameNavigating() const { return m_lastNavigating; }
    /// @}
    /// @name Progressive anti-aliasing at rest (render/progressive_accumulation.h)
    /// kProgressiveDelayMs after the last change, a still view — nothing dragged, animating,
    /// loading or compiling, drawn at full size — draws kProgressiveSamples more frames, each
    /// offset by a sub-pixel jitter, one per event-loop turn, and shows their running mean: its
    /// edges, highlights and threads settle to the supersampled picture in about half a second,
    /// then the viewport stops drawing. Any change shows the plain frame again at once and starts
    /// over. View state (the viewport toolbar's Refine, kept in QSettings), on by default.
    /// @{
    static constexpr int kProgressiveDelayMs = 200;
    static constexpr int kProgressiveSamples = render::kRefinementFrames;
    void setProgressiveAntialiasing(bool enabled);
    bool progressiveAntialiasing() const { return m_progressiveEnabled; }
    /// The frames in the mean the viewport shows (0: a plain frame).
    int progressiveSamples() const { return m_progressiveShown; }
    /// @}
    /// @name The settled view, scene-linear (the Reference panel's comparison)
    /// The view at rest is the mean of the refinement's frames, and on a mesh that traces its
    /// own light each frame reads the light of the one before: the mean holds one to
    /// kProgressiveSamples bounces, which no single frame does. While kept, the refinement's
    /// frames go through the scene-linear target (no display step inside the lighting pass) and
    /// their linear images are averaged as they are drawn; when the refinement ends,
    /// settledLinearReady() is emitted and settledLinear() holds the mean until the view changes.
    /// Turning it on over a view that has already settled draws the refinement again.
    /// @{
    void setKeepsSettledLinear(bool keep);
    bool keepsSettledLinear() const { return m_keepSettledLinear; }
    /// The scene-linear mean of the refinement the view shows now, RGBA; empty while the view
    /// has not settled since its last change, or when it is not kept.
    const Image& settledLinear() const { return m_settledLinear; }
    /// @}
    /// @name Animation
    /// Film grain, night-vision grain, vaporwave static, paintbrush strokes and the procedural
    /// FBM background read FrameSettings::time. While the scene reads time (sceneReadsTime) and
    /// the animation is not paused, the viewport feeds the seconds it has animated so far and
    /// draws kAnimationIntervalMs apart; a still scene draws only on changes, so an idle editor
    /// costs nothing. The time pauses with the animation and while the scene is still, and goes
    /// on from there (strokes do not jump when an effect is re-enabled). View state, never in the
    /// document.
    /// @{
    static constexpr int kAnimationIntervalMs = 33;
    void setAnimationPaused(bool paused);
    bool isAnimationPaused() const { return m_animationPaused; }
    /// True while frames are drawn for time alone (a time-dependent scene, not paused).
    bool isAnimating() const;
    /// The time, in seconds, the next frame is drawn at.
    double animationTime() const;
    /// @}
    /// Shows the last frame's per-pass GPU timings in a label over the viewport.
    void setTimingOverlayVisible(bool visible);
    bool isTimingOverlayVisible() const;
    /// Centres the view on the mesh at the default framing distance (keeps yaw and pitch).
    void frameMesh();
    /// Recompiles every shader program from disk (Renderer::reloadShaders). On a compile error
    /// the last good programs stay, the viewport keeps drawing, and @p error gets file:line and
    /// the driver's message. False also when there is no renderer yet.
    bool reloadShaders(QString* error);
    /// Environment prefiltering progress in [0, 1], or a negative value when the renderer does
    /// not report one.
    double environmentProgress() const;
    /// The material's textures on their way to the GPU (loading == 0: all complete).
    render::TextureLoadProgress textureProgress() const;

    /// The camera the viewport draws with: the scene's, or the artist's orbit of it.
    Camera viewCamera() const;
    /// Renderer initialisation or render error; empty while drawing works.
    QString errorMessage() const { return m_error; }
    /// Completed frames since construction.
    int frameCount() const { return m_frameCount; }
    /// The renderer (null before initializeGL or after the context went away). For tests and
    /// benchmarks: shaderCompileCount, lastTimings.
    const render::Renderer* renderer() const { return m_renderer.get(); }
    /// Renders a fresh frame at the viewport's size (off screen, with the GL window's context) and
    /// returns it as the renderer wrote it (display-encoded, RGB32; no timing overlay). A null
    /// image before the renderer exists. Counts as a frame (frameCompleted). @p linear, when
    /// given, gets the same frame's scene-linear colour (Renderer::readLinear; the Reference view
    /// compares it with the path tracer's). The plain frame, never the still view's refinement
    /// (so grabs repeat), unless @p settled and the view has finished refining: then its
    /// anti-aliased mean, what the artist sees (screenshots).
    QImage grabFramebuffer(Image* linear = nullptr, bool settled = false);
    /// Renders material-graph node thumbnails (render/graph_preview.h) with the GL window's
    /// context current, texture nodes loading through the renderer's cache. Empty (no thumbnail
    /// drawn) before the renderer exists; one entry per request otherwise. Reasons a request
    /// could not be drawn go to @p problems.
    std::vector<Image> renderGraphPreviews(const graph::Graph& graph,
                                           const std::vector<render::PreviewRequest>& requests,
                                           Problems* problems = nullptr);
    /// The native window the viewport draws in (inside a window container): the target of mouse,
    /// key and drop events, and its frameSwapped signal, for tests and benchmarks.
    QOpenGLWindow* glWindow() const;

    QSize sizeHint() const override { return {800, 600}; }

public slots:
    /// Asks for a new frame (QWidget::update() would repaint only the container, not the GL
    /// window).
    void requestFrame();

signals:
    /// A frame was drawn; @p cpuMs is the time spent in Renderer::render on the CPU side.
    void frameCompleted(double cpuMs);
    /// The renderer could not be created or could not draw; the widget shows @p message.
    void renderFailed(const QString& message);
    /// Problems found while taking a scene (a missing HDRI or texture; a fallback is used) and
    /// the renderer's warnings (Renderer::takeWarnings: no OCIO config, no encoding view).
    void sceneProblems(const QStringList& problems);
    /// The artist moved the view (orbit, pan, zoom, fly, frame): the camera the viewport now
    /// draws with. The main window keeps it with the document (DocumentController::setViewCamera).
    void viewCameraChanged(const velvet::Camera& camera);
    /// Shift + right drag moved by @p deltaDeg degrees of HDRI rotation. Every move of one drag
    /// carries the same @p gestureKey, so the edits merge into one undo command.
    void environmentRotationDragged(float deltaDeg, int gestureKey);
    /// The artist dragged the A/B seam to @p fraction of the width.
    void splitPositionChanged(float fraction);
    /// The refinement ended with settledLinear() kept (setKeepsSettledLinear).
    void settledLinearReady();

private:
    enum class Drag { None, Orbit, Pan, Look, RotateEnvironment, Seam };
    class Surface; ///< the QOpenGLWindow; forwards everything to the methods below

    /// @name Called by the Surface (its context current for the GL ones)
    /// @{
    void initializeGL();
    void paintGL();
    bool mousePress(QMouseEvent* event);
    bool mouseMove(QMouseEvent* event);
    bool mouseRelease(QMouseEvent* event);
    bool wheel(QWheelEvent* event);
    bool keyPress(QKeyEvent* event);
    bool keyRelease(QKeyEvent* event);
    void focusLost();
    /// DragEnter / DragMove / DragLeave / Drop over the GL window, sent on to the nearest
    /// ancestor that accepts drops.
    void forwardDrag(QEvent* event);
    /// @}

    /// Hands dirty state to the renderer and draws one frame into @p fbo; false when it failed.
    /// @p displayOnly: nothing reads the frame's linear image (render::FrameSettings).
    /// @p settledGrab: a grab that takes the refined mean if the view has settled.
    bool drawFrame(unsigned fbo, bool displayOnly = true, bool settledGrab = false);

    void setViewCamera(const Camera& camera);
    void flyStep();
    void updateOverlay();
    void paintOverlay();
    void releaseRenderer();
    void fail(const QString& message);
    /// Posts an update request without counting it as a change (requestFrame does).
    void postFrame();
    /// @name Progressive anti-aliasing (viewport_progressive.cpp)
    /// @{
    void restartProgressive();
    /// After a frame drawn with @p settings: schedules the next refinement frame while the
    /// view is still (or the first one kProgressiveDelayMs later), or stops.
    void progressiveFrameDrawn(const render::FrameSettings& settings);
    void progressiveStep();
    /// Adds the frame just drawn with @p settings to the settled mean when it is kept.
    void keepLinearFrame(const render::FrameSettings& settings);
    /// @}
    /// A scene or view change: decides whether the next frame is reduced (see kRefineDelayMs).
    void noteInteraction();
    /// Starts or stops the animation clock and timer after a scene or pause change.
    void updateAnimation();
    void paintError();
    /// The frame size in device pixels.
    QSize frameSize() const;

    Surface* m_surface;   ///< owned by m_container
    QWidget* m_container; ///< QWidget::createWindowContainer(m_surface)
    std::unique_ptr<render::Renderer> m_renderer;
    std::unique_ptr<render::OffscreenTarget> m_grabTarget; ///< grabFramebuffer's, with m_renderer
    std::unique_ptr<render::GraphPreview> m_graphPreview;  ///< node thumbnails, with m_renderer
    Scene m_scene;
    std::optional<Camera> m_orbit; ///< view state, never part of the document or the undo stack
    render::FrameSettings m_settings;
    ScenePart m_pendingParts = ScenePart::All; ///< changed since the renderer's last update
    QString m_error;
    int m_frameCount = 0;
    std::shared_ptr<const ColorManagement> m_colorManagement;
    Drag m_drag = Drag::None;
    int m_gestureKey = 0;
    QPoint m_lastMouse;
    QSet<int> m_flyKeys; ///< W A S D Q E held while looking
    QTimer* m_flyTimer;
    QElapsedTimer m_flyClock;
    bool m_overlayVisible = false;
    QString m_overlayText;          ///< painted over the frame by Qt's paint engine
    bool m_updatePosted = false;    ///< an UpdateRequest posted by requestFrame, not yet delivered
    QPointer<QWidget> m_dragTarget; ///< the widget the current drag over the GL window went to
    std::optional<Material> m_splitMaterial;
    float m_splitPosition = 0.5f;
    QString m_splitLabel;
    bool m_splitSwapped = false;
    bool m_reducedEnabled = true;
    float m_reducedScale = 0.5f;
    bool m_interacting = false;      ///< the next frame is reduced
    bool m_reducedFrameDrawn = true; ///< a reduced frame drawn since the stream's last change
    float m_lastRenderScale = 1.0f;
    bool m_lastNavigating = false;
    QElapsedTimer m_lastInteraction;
    QTimer* m_refineTimer;
    bool m_animationPaused = false;
    double m_animatedSeconds = 0.0; ///< time accumulated before m_animationClock started
    QElapsedTimer m_animationClock; ///< valid while animating
    QTimer* m_animationTimer;
    bool m_progressiveEnabled = true;
    /// The next frame's FrameSettings::accumulation: -1 a plain frame, n the n-th of the mean.
    int m_progressiveIndex = -1;
    int m_progressiveShown = 0; ///< frames in the mean on screen (0: a plain frame)
    QSize m_progressiveSize;    ///< the frame size the refinement's mean has
    bool m_keepSettledLinear = false;
    ImageMean m_linearMean; ///< the refinement's linear frames so far
    Image m_settledLinear;  ///< their mean once the refinement has ended
    QTimer* m_progressiveTimer;
    /// Draws a frame when a texture file the material uses changes on disk (an idle viewport
    /// would otherwise not notice; ui/texture_file_watcher.h).
    QStringList m_lastSceneProblems; ///< the problems update reported last (no repeats)
    TextureFileWatcher* m_textureWatcher;
};

} // namespace velvet::ui
