#include "render/texture_storage_thread.h"

#include <chrono>
#include <epoxy/gl.h>

namespace velvet::render {
namespace {

void freeStorage(unsigned& texture, void*& fence) {
    if (fence)
        glDeleteSync(static_cast<GLsync>(fence));
    if (texture)
        glDeleteTextures(1, &texture);
    texture = 0;
    fence = nullptr;
}

} // namespace

unsigned createSlotTexture(const TextureStorageRequest& r) {
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, r.levels, GLenum(r.internalFormat), r.width, r.height);
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTextureParameteri(texture, GL_TEXTURE_MAX_LEVEL, r.levels - 1);
    return texture;
}

TextureStorageThread::TextureStorageThread(std::unique_ptr<WorkerGlContext> context)
    : m_context(std::move(context)), m_thread([this] { run(); }) {}

TextureStorageThread::~TextureStorageThread() {
    {
        const std::lock_guard<std::mutex> lock(m_mutex);
        m_stop = true;
    }
    m_wake.notify_all();
    m_thread.join();
}

std::shared_ptr<PendingTextureStorage>
TextureStorageThread::allocate(const TextureStorageRequest& request) {
    auto pending = std::make_shared<PendingTextureStorage>();
    pending->m_request = request;
    {
        const std::lock_guard<std::mutex> lock(m_mutex);
        m_queue.push_back(pending);
    }
    m_wake.notify_one();
    return pending;
}

void TextureStorageThread::run() {
    std::unique_lock<std::mutex> lock(m_mutex);
    for (;;) {
        m_wake.wait(lock, [&] { return m_stop || !m_queue.empty(); });
        if (m_stop)
            break;
        std::shared_ptr<PendingTextureStorage> pending = std::move(m_queue.front());
        m_queue.pop_front();
        lock.unlock();
        // The context is made current on first use, on this thread (WorkerGlContext).
        if (!m_current && m_contextError.empty()) {
            std::string error;
            m_current = m_context && m_context->makeCurrent(&error);
            if (!m_current)
                m_contextError = error.empty() ? "no worker context" : error;
        }
        if (m_current) {
            allocateNow(*pending);
        } else {
            const std::lock_guard<std::mutex> pendingLock(pending->mutex);
            pending->error = m_contextError;
            pending->done = true;
        }
        lock.lock();
    }
    lock.unlock();
    // Whatever was asked and never made needs no freeing; the context goes with this thread.
    m_context.reset();
}

void TextureStorageThread::allocateNow(PendingTextureStorage& pending) {
    {
        const std::lock_guard<std::mutex> pendingLock(pending.mutex);
        if (pending.abandoned)
            return;
    }
    const unsigned texture = createSlotTexture(pending.m_request);
    // The drawing context may use the texture once this fence has signalled (OpenGL 4.5, 5.3
    // "Propagating Changes to Objects": complete in the changing context, then bound anew).
    GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    glFlush();
    const std::lock_guard<std::mutex> pendingLock(pending.mutex);
    pending.texture = texture;
    pending.fence = fence;
    pending.done = true;
    if (pending.abandoned) // given up on while it was being made (GL defers the deletion)
        freeStorage(pending.texture, pending.fence);
}

TextureStorageThread::State TextureStorageThread::take(PendingTextureStorage& pending,
                                                       unsigned& texture, std::string* error) {
    const std::lock_guard<std::mutex> lock(pending.mutex);
    if (!pending.done)
        return State::Waiting;
    if (!pending.error.empty()) {
        if (error)
            *error = pending.error;
        return State::Failed;
    }
    if (pending.fence) {
        const GLenum status = glClientWaitSync(static_cast<GLsync>(pending.fence), 0, 0); // no wait
        if (status != GL_ALREADY_SIGNALED && status != GL_CONDITION_SATISFIED)
            return State::Waiting;
        glDeleteSync(static_cast<GLsync>(pending.fence));
        pending.fence = nullptr;
    }
    texture = pending.texture;
    pending.texture = 0;
    return State::Ready;
}

void TextureStorageThread::abandon(PendingTextureStorage& pending) {
    const std::lock_guard<std::mutex> lock(pending.mutex);
    pending.abandoned = true;
    if (pending.done)
        freeStorage(pending.texture, pending.fence); // shared objects: any context may free them
}

TextureStorageThread::State TextureStorageThread::wait(PendingTextureStorage& pending,
                                                       unsigned& texture, std::string* error) {
    State state;
    while ((state = take(pending, texture, error)) == State::Waiting)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return state;
}

} // namespace velvet::render
