#pragma once
/// @file headless_context.h
/// An OpenGL 4.5 core context without a window system: EGL on Mesa's surfaceless platform (no X
/// server), or the EGL device platform on NVIDIA. EGL headers stay in the .cpp.

#include <memory>
#include <string>

namespace velvet::render {

class WorkerGlContext;

class HeadlessContext {
public:
    /// Creates and makes current a GL 4.5 core context; nullptr + message when none can be made.
    static std::unique_ptr<HeadlessContext> create(std::string* error);
    ~HeadlessContext();
    bool makeCurrent();
    /// Whether any EGL context is current on this thread (renderSceneOffscreen reuses it).
    static bool isAnyContextCurrent();
    /// A context in the share group of the EGL context current on this thread, for a worker
    /// thread to make current (TextureStorageThread); nullptr + message when none is current or
    /// none can be made.
    static std::unique_ptr<WorkerGlContext> workerSharingCurrent(std::string* error);

    /// GL_VENDOR, GL_RENDERER, GL_VERSION of the context, and the EGL platform used.
    std::string vendor() const;
    std::string renderer() const;
    std::string version() const;
    std::string platform() const;

private:
    HeadlessContext();
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace velvet::render
