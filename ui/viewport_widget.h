#pragma once
/// @file viewport_widget.h
/// The 3D viewport: a thin QOpenGLWidget that forwards initializeGL / resizeGL / paintGL to
/// velvet::render::Renderer and holds no GL logic of its own (DESIGN.md, "Layers"). Setters store
/// a value, mark it dirty and call update(); paintGL hands dirty state to the renderer.
///
/// Navigation (view state, never in the document): left drag orbits, middle drag pans, the wheel
/// zooms, right drag looks around (fly mode) while W A S D Q E move, F frames the mesh.
/// Shift + right drag rotates the HDRI: that is a document edit, so the widget only reports it
/// (environmentRotationDragged) and the window turns it into an undoable command.

#include "core/scene.h"
#include "render/renderer.h"

#include <QElapsedTimer>
#include <QOpenGLWidget>
#include <QPoint>
#include <QSet>
#include <QString>
#include <QStringList>
#include <QSurfaceFormat>
#include <memory>
#include <optional>

class QLabel;
class QTimer;

namespace velvet {
class ColorManagement;
}

namespace velvet::ui {

class ViewportWidget : public QOpenGLWidget {
    Q_OBJECT
public:
    explicit ViewportWidget(QWidget* parent = nullptr);
    /// The surface format the renderer needs (OpenGL 4.5 core, 24-bit depth). Set it with
    /// QSurfaceFormat::setDefaultFormat before the QApplication is created.
    static QSurfaceFormat requiredFormat();
    /// Frees the renderer with the widget's context current.
    ~ViewportWidget() override;

    /// The scene to draw (copied; cheap for value edits).
    void setScene(const Scene& scene);
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

    /// The camera the viewport draws with: the scene's, or the artist's orbit of it.
    Camera viewCamera() const;
    /// Renderer initialisation or render error; empty while drawing works.
    QString errorMessage() const { return m_error; }
    /// Completed frames since construction.
    int frameCount() const { return m_frameCount; }
    /// The renderer (null before initializeGL or after the context went away). For tests and
    /// benchmarks: shaderCompileCount, lastTimings.
    const render::Renderer* renderer() const { return m_renderer.get(); }

    QSize sizeHint() const override { return {800, 600}; }

signals:
    /// A frame was drawn; @p cpuMs is the time spent in Renderer::render on the CPU side.
    void frameCompleted(double cpuMs);
    /// The renderer could not be created or could not draw; the widget shows @p message.
    void renderFailed(const QString& message);
    /// Problems found while taking a scene (a missing HDRI or texture); a fallback is used.
    void sceneProblems(const QStringList& problems);
    /// Shift + right drag moved by @p deltaDeg degrees of HDRI rotation. Every move of one drag
    /// carries the same @p gestureKey, so the edits merge into one undo command.
    void environmentRotationDragged(float deltaDeg, int gestureKey);

protected:
    void initializeGL() override;
    void resizeGL(int w, int h) override;
    void paintGL() override;

    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
    void keyReleaseEvent(QKeyEvent* event) override;
    void focusOutEvent(QFocusEvent* event) override;

private:
    enum class Drag { None, Orbit, Pan, Look, RotateEnvironment };

    void setViewCamera(const Camera& camera);
    void flyStep();
    void updateOverlay();
    void releaseRenderer();
    void fail(const QString& message);
    /// A scene or view change: decides whether the next frame is reduced (see kRefineDelayMs).
    void noteInteraction();
    void paintError();

    std::unique_ptr<render::Renderer> m_renderer;
    Scene m_scene;
    std::optional<Camera> m_orbit; ///< view state, never part of the document or the undo stack
    render::FrameSettings m_settings;
    bool m_sceneDirty = true;
    QString m_error;
    int m_frameCount = 0;
    std::shared_ptr<const ColorManagement> m_colorManagement;
    Drag m_drag = Drag::None;
    int m_gestureKey = 0;
    QPoint m_lastMouse;
    QSet<int> m_flyKeys; ///< W A S D Q E held while looking
    QTimer* m_flyTimer;
    QElapsedTimer m_flyClock;
    QLabel* m_overlay;
    std::optional<Material> m_splitMaterial;
    float m_splitPosition = 0.5f;
    bool m_reducedEnabled = true;
    float m_reducedScale = 0.5f;
    bool m_interacting = false; ///< the next frame is reduced
    float m_lastRenderScale = 1.0f;
    QElapsedTimer m_lastInteraction;
    QTimer* m_refineTimer;
};

} // namespace velvet::ui
