#include "render/headless_context.h"

#include "render/texture_storage_thread.h"

#include <cstring>
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <map>
#include <mutex>
#include <vector>

namespace velvet::render {
namespace {

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

bool hasExtension(const char* list, const char* name) {
    if (!list)
        return false;
    const size_t len = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)); p += len)
        if ((p == list || p[-1] == ' ') && (p[len] == ' ' || p[len] == '\0'))
            return true;
    return false;
}

std::string eglErrorName(EGLint e) {
    switch (e) {
    case EGL_SUCCESS:
        return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
        return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
        return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
        return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
        return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
        return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
        return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
        return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
        return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
        return "EGL_BAD_PARAMETER";
    default:
        return "EGL error 0x" + [&] {
            char b[16];
            std::snprintf(b, sizeof b, "%x", unsigned(e));
            return std::string(b);
        }();
    }
}

// eglGetPlatformDisplayEXT returns one EGLDisplay per platform for the whole process, and
// eglTerminate on it ends every context on it, in every thread. Contexts on several threads (the
// editor's thumbnail worker beside renderSceneOffscreen elsewhere) count their display's users,
// and the last one terminates it.
std::mutex& displayMutex() {
    static std::mutex mutex;
    return mutex;
}
std::map<EGLDisplay, int>& displayUsers() {
    static std::map<EGLDisplay, int> users;
    return users;
}

// Counts one more user of @p display (a context on it).
void retainDisplay(EGLDisplay display) {
    const std::lock_guard<std::mutex> lock(displayMutex());
    ++displayUsers()[display];
}
// One user fewer; the last terminates the display.
void releaseDisplay(EGLDisplay display) {
    const std::lock_guard<std::mutex> lock(displayMutex());
    if (--displayUsers()[display] <= 0) {
        displayUsers().erase(display);
        eglTerminate(display);
    }
}

// Desktop OpenGL 4.5, core profile: the drawing context and its workers alike.
const EGLint kContextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                  4,
                                  EGL_CONTEXT_MINOR_VERSION,
                                  5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                  EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_NONE};

std::string glString(GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return s ? s : "";
}

} // namespace

struct HeadlessContext::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    std::string platform;
    std::string vendor, renderer, version;
};

HeadlessContext::HeadlessContext() : m_impl(std::make_unique<Impl>()) {}

HeadlessContext::~HeadlessContext() {
    if (m_impl->display != EGL_NO_DISPLAY) {
        if (eglGetCurrentContext() == m_impl->context)
            eglMakeCurrent(m_impl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (m_impl->context != EGL_NO_CONTEXT)
            eglDestroyContext(m_impl->display, m_impl->context);
        releaseDisplay(m_impl->display);
    }
}

bool HeadlessContext::isAnyContextCurrent() {
    return eglGetCurrentContext() != EGL_NO_CONTEXT;
}

std::unique_ptr<HeadlessContext> HeadlessContext::create(std::string* error) {
    auto fail = [&](const std::string& what) -> std::unique_ptr<HeadlessContext> {
        if (error)
            *error = "headless OpenGL: " + what;
        return nullptr;
    };
    std::unique_ptr<HeadlessContext> ctx(new HeadlessContext());
    Impl& d = *ctx->m_impl;

    // 1. Pick a display that needs no window system: Mesa's surfaceless platform, else the EGL
    //    device platform (what NVIDIA's driver offers), else the default display.
    const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    std::string tried;
    const bool platformBase = hasExtension(clientExts, "EGL_EXT_platform_base");
    auto tryInit = [&](EGLDisplay dpy, const char* name) {
        if (dpy == EGL_NO_DISPLAY) {
            tried += std::string(tried.empty() ? "" : "; ") + name + ": no display";
            return false;
        }
        EGLint major = 0, minor = 0;
        const std::lock_guard<std::mutex> lock(displayMutex());
        if (!eglInitialize(dpy, &major, &minor)) {
            tried += std::string(tried.empty() ? "" : "; ") + name + ": eglInitialize failed (" +
                     eglErrorName(eglGetError()) + ")";
            return false;
        }
        d.display = dpy;
        d.platform = name;
        ++displayUsers()[dpy];
        return true;
    };
    if (platformBase && hasExtension(clientExts, "EGL_MESA_platform_surfaceless"))
        tryInit(
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
            "surfaceless (EGL_MESA_platform_surfaceless)");
    if (d.display == EGL_NO_DISPLAY && platformBase &&
        hasExtension(clientExts, "EGL_EXT_platform_device") &&
        hasExtension(clientExts, "EGL_EXT_device_enumeration")) {
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (eglQueryDevicesEXT(16, devices, &count) && count > 0)
            tryInit(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr),
                    "device (EGL_EXT_platform_device)");
        else
            tried += std::string(tried.empty() ? "" : "; ") + "device: no EGL devices";
    }
    if (d.display == EGL_NO_DISPLAY)
        tryInit(eglGetDisplay(EGL_DEFAULT_DISPLAY), "default display");
    if (d.display == EGL_NO_DISPLAY)
        return fail("no EGL display could be initialised (" + tried + ")");

    // 2. Desktop OpenGL, 4.5 core, no surface.
    if (!eglBindAPI(EGL_OPENGL_API))
        return fail("eglBindAPI(EGL_OPENGL_API) failed on the " + d.platform + " platform (" +
                    eglErrorName(eglGetError()) + ")");
    const char* displayExts = eglQueryString(d.display, EGL_EXTENSIONS);
    if (!hasExtension(displayExts, "EGL_KHR_surfaceless_context"))
        return fail("EGL_KHR_surfaceless_context is missing on the " + d.platform + " platform");

    EGLConfig config = nullptr;
    const EGLint configAttribs[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                    EGL_NONE};
    EGLint numConfigs = 0;
    if (!eglChooseConfig(d.display, configAttribs, &config, 1, &numConfigs) || numConfigs < 1) {
        if (!hasExtension(displayExts, "EGL_KHR_no_config_context"))
            return fail("no EGL config supports desktop OpenGL on the " + d.platform + " platform");
        config = nullptr; // EGL_NO_CONFIG_KHR
    }
    d.context = eglCreateContext(d.display, config, EGL_NO_CONTEXT, kContextAttribs);
    if (d.context == EGL_NO_CONTEXT)
        return fail("cannot create an OpenGL 4.5 core context on the " + d.platform +
                    " platform (" + eglErrorName(eglGetError()) + ")");
    if (!ctx->makeCurrent())
        return fail("eglMakeCurrent failed on the " + d.platform + " platform (" +
                    eglErrorName(eglGetError()) + ")");

    d.vendor = glString(GL_VENDOR);
    d.renderer = glString(GL_RENDERER);
    d.version = glString(GL_VERSION);
    if (epoxy_gl_version() < 45)
        return fail("OpenGL 4.5 is needed, the context is " + d.version + " (" + d.renderer + ")");
    return ctx;
}

namespace {

// A worker's context on the drawing context's display, counted among the display's users so
// that the drawing context's end does not terminate it under the worker.
class EglWorkerContext final : public WorkerGlContext {
public:
    EglWorkerContext(EGLDisplay display, EGLContext context)
        : m_display(display), m_context(context) {
        retainDisplay(m_display);
    }
    ~EglWorkerContext() override {
        if (eglGetCurrentContext() == m_context)
            eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(m_display, m_context);
        releaseDisplay(m_display);
    }
    bool makeCurrent(std::string* error) override {
        // The bound API is per thread (EGL 1.5, 3.7).
        if (eglBindAPI(EGL_OPENGL_API) &&
            eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, m_context))
            return true;
        if (error)
            *error = "eglMakeCurrent failed for the worker context (" +
                     eglErrorName(eglGetError()) + ")";
        return false;
    }

private:
    EGLDisplay m_display;
    EGLContext m_context;
};

} // namespace

std::unique_ptr<WorkerGlContext> HeadlessContext::workerSharingCurrent(std::string* error) {
    const EGLDisplay display = eglGetCurrentDisplay();
    const EGLContext shared = eglGetCurrentContext();
    if (display == EGL_NO_DISPLAY || shared == EGL_NO_CONTEXT) {
        if (error)
            *error = "headless OpenGL: no EGL context is current to share with";
        return nullptr;
    }
    // The same config as the shared context's (EGL 1.5, 3.7.1: a share group needs compatible
    // contexts); none when it was made without one (EGL_KHR_no_config_context).
    EGLint configId = 0;
    eglQueryContext(display, shared, EGL_CONFIG_ID, &configId);
    EGLConfig config = nullptr;
    if (configId > 0) {
        const EGLint attribs[] = {EGL_CONFIG_ID, configId, EGL_NONE};
        EGLint count = 0;
        if (!eglChooseConfig(display, attribs, &config, 1, &count) || count < 1)
            config = nullptr;
    }
    const EGLContext context = eglCreateContext(display, config, shared, kContextAttribs);
    if (context == EGL_NO_CONTEXT) {
        if (error)
            *error = "headless OpenGL: cannot create a worker context sharing the current one (" +
                     eglErrorName(eglGetError()) + ")";
        return nullptr;
    }
    return std::make_unique<EglWorkerContext>(display, context);
}

bool HeadlessContext::makeCurrent() {
    return eglMakeCurrent(m_impl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, m_impl->context);
}

std::string HeadlessContext::vendor() const {
    return m_impl->vendor;
}
std::string HeadlessContext::renderer() const {
    return m_impl->renderer;
}
std::string HeadlessContext::version() const {
    return m_impl->version;
}
std::string HeadlessContext::platform() const {
    return m_impl->platform;
}

} // namespace velvet::render
