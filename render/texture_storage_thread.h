#pragma once
/// @file texture_storage_thread.h
/// Allocates textures' immutable storage on a thread of its own, in an OpenGL context that shares
/// objects with the drawing one, so that no frame waits on it. Mesa's llvmpipe zero-fills a
/// texture's storage when glTextureStorage2D allocates it: 85 MB for a 4096² RGBA8 chain, 113-279
/// ms on the 2-core VM, which was the worst frame of an asynchronous texture load (BENCHMARKS.md,
/// "Texture storage allocated off the drawing thread"). The drawing thread asks, keeps drawing,
/// and takes the texture once a fence the worker placed after the allocation has signalled
/// (checked without waiting: glClientWaitSync with a zero timeout).

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace velvet::render {

/// A context for a worker thread, in the drawing context's share group. Made on the drawing
/// thread; makeCurrent() is then called on the worker thread only (a Qt context, for one, must be
/// created on the thread that uses it), and the object is destroyed there.
class WorkerGlContext {
public:
    virtual ~WorkerGlContext() = default;
    /// Makes the context current on the calling thread; false + message when it cannot.
    virtual bool makeCurrent(std::string* error) = 0;
};

/// What one allocation asks for: glTextureStorage2D's arguments plus the sampling the slots use
/// (mipmapped trilinear, repeat).
struct TextureStorageRequest {
    int width = 0;
    int height = 0;
    int levels = 1;
    unsigned internalFormat = 0;
};

/// Creates a texture with @p request's storage and sampling in the current context (on the
/// worker, or on the drawing thread when there is no worker); returns its name.
unsigned createSlotTexture(const TextureStorageRequest& request);

/// One allocation in flight; the drawing thread polls it with TextureStorageThread::take().
class PendingTextureStorage {
public:
    const TextureStorageRequest& request() const { return m_request; }

private:
    friend class TextureStorageThread;
    TextureStorageRequest m_request;
    std::mutex mutex;
    unsigned texture = 0;
    void* fence = nullptr; // GLsync, kept out of this header
    bool done = false;
    bool abandoned = false; // the drawing thread no longer wants it: the worker frees it
    std::string error;
};

class TextureStorageThread {
public:
    explicit TextureStorageThread(std::unique_ptr<WorkerGlContext> context);
    /// Stops the worker; allocations not yet taken are freed by it, with its context current.
    ~TextureStorageThread();
    TextureStorageThread(const TextureStorageThread&) = delete;
    TextureStorageThread& operator=(const TextureStorageThread&) = delete;

    std::shared_ptr<PendingTextureStorage> allocate(const TextureStorageRequest& request);

    enum class State { Waiting, Ready, Failed };
    /// On the drawing thread, without waiting: Ready moves the texture into @p texture (the
    /// caller owns it from then on), Failed puts the reason in @p error (the worker's context
    /// could not be made current: the caller allocates on its own thread).
    static State take(PendingTextureStorage& pending, unsigned& texture, std::string* error);
    /// The drawing thread gives up on @p pending (its entry dropped): a texture already made is
    /// deleted here, one still to come by the worker.
    static void abandon(PendingTextureStorage& pending);
    /// take() until it is not Waiting (finish(): a headless frame needs every texture now).
    static State wait(PendingTextureStorage& pending, unsigned& texture, std::string* error);

private:
    void run();
    void allocateNow(PendingTextureStorage& pending);

    std::unique_ptr<WorkerGlContext> m_context;
    mutable std::mutex m_mutex;
    std::condition_variable m_wake;
    std::deque<std::shared_ptr<PendingTextureStorage>> m_queue;
    std::string m_contextError; // set once when makeCurrent fails: every request fails with it
    bool m_stop = false;
    bool m_current = false;
    std::thread m_thread;
};

} // namespace velvet::render
