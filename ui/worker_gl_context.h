#pragma once
/// @file worker_gl_context.h
/// The editor's context for render::TextureStorageThread: a QOpenGLContext in the viewport's
/// share group, created and made current on the worker thread (Qt allows a context current only
/// on the thread it lives in), on an offscreen surface made here on the GUI thread (which
/// QOffscreenSurface requires).

#include "render/texture_storage_thread.h"

#include <memory>

class QOpenGLContext;
class QOffscreenSurface;

namespace velvet::ui {

class WorkerGlContext final : public render::WorkerGlContext {
public:
    /// On the GUI thread, with @p share the viewport's context.
    explicit WorkerGlContext(QOpenGLContext* share);
    /// On the worker thread: the context goes here, the surface back to the GUI thread.
    ~WorkerGlContext() override;
    bool makeCurrent(std::string* error) override;

private:
    QOpenGLContext* m_share;
    QOffscreenSurface* m_surface;
    std::unique_ptr<QOpenGLContext> m_context;
};

} // namespace velvet::ui
