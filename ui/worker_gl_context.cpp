#include "ui/worker_gl_context.h"

#include <QOffscreenSurface>
#include <QOpenGLContext>

namespace velvet::ui {

WorkerGlContext::WorkerGlContext(QOpenGLContext* share)
    : m_share(share), m_surface(new QOffscreenSurface) {
    m_surface->setFormat(share->format());
    m_surface->create();
}

WorkerGlContext::~WorkerGlContext() {
    if (m_context)
        m_context->doneCurrent();
    m_context.reset();
    m_surface->deleteLater(); // destroyed by the GUI thread's event loop, where it lives
}

bool WorkerGlContext::makeCurrent(std::string* error) {
    if (!m_context) {
        m_context = std::make_unique<QOpenGLContext>();
        m_context->setFormat(m_share->format());
        m_context->setShareContext(m_share);
        if (!m_context->create() || !m_context->shareContext()) {
            if (error)
                *error = "the worker's OpenGL context could not be created in the viewport's "
                         "share group";
            m_context.reset();
            return false;
        }
    }
    if (!m_surface->isValid() || !m_context->makeCurrent(m_surface)) {
        if (error)
            *error = "the worker's OpenGL context could not be made current";
        return false;
    }
    return true;
}

} // namespace velvet::ui
