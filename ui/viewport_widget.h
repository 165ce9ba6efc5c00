#pragma once
/// @file viewport_widget.h
/// The 3D viewport: a thin QOpenGLWidget that forwards initializeGL / resizeGL / paintGL to
/// velvet::render::Renderer and holds no GL logic of its own (DESIGN.md, "Layers"). Setters store
/// a value, mark it dirty and call update(); paintGL hands dirty state to the renderer.

#include "core/scene.h"
#include "render/renderer.h"

#include <QOpenGLWidget>
#include <QPoint>
#include <QString>
#include <QStringList>
#include <QSurfaceFormat>
#include <memory>
#include <optional>

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

protected:
    void initializeGL() override;
    void resizeGL(int w, int h) override;
    void paintGL() override;

    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;

private:
    void releaseRenderer();
    void fail(const QString& message);
    void paintError();

    std::unique_ptr<render::Renderer> m_renderer;
    Scene m_scene;
    std::optional<Camera> m_orbit; ///< view state, never part of the document or the undo stack
    render::FrameSettings m_settings;
    bool m_sceneDirty = true;
    QString m_error;
    int m_frameCount = 0;
    bool m_dragging = false;
    QPoint m_lastMouse;
};

} // namespace velvet::ui
