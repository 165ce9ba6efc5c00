#include "render/renderer.h"

#include "core/brdf.h"
#include "core/color_management.h"
#include "render/camera.h"
#include "render/display_transform.h"
#include "render/environment_map.h"
#include "render/gbuffer.h"
#include "render/gbuffer_layout.h"
#include "render/gpu_mesh.h"
#include "render/material_table.h"
#include "render/shader_program.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <epoxy/gl.h>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/trigonometric.hpp>
#include <map>

namespace velvet::render {
namespace {

constexpr int kMaxLights = 16;

/// Mirrors FrameBlock in common_frame.glsl (std140; vec4 / mat4 members only).
struct FrameBlock {
    glm::mat4 view, proj, invProj, invView, viewProj;
    glm::vec4 cameraPosition;
    glm::vec4 viewport;
    glm::vec4 envSh[9];
    glm::vec4 envParams;
    glm::vec4 ambientRadiance;
    glm::vec4 backgroundColor;
    glm::ivec4 modes;
    glm::vec4 post;
    glm::vec4 lightDirection[kMaxLights];
    glm::vec4 lightRadiance[kMaxLights];
};

std::string glErrorName(GLenum e) {
    switch (e) {
    case GL_INVALID_ENUM:
        return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
        return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
        return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
        return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
        return "GL_OUT_OF_MEMORY";
    default:
        return "GL error " + std::to_string(e);
    }
}

/// Drains the GL error queue; returns the first error's name or "".
std::string takeGlErrors() {
    std::string first;
    for (int i = 0; i < 32; ++i) {
        const GLenum e = glGetError();
        if (e == GL_NO_ERROR)
            break;
        if (first.empty())
            first = glErrorName(e);
    }
    return first;
}

bool fail(std::string* error, const std::string& message) {
    if (error)
        *error = message;
    return false;
}

/// Reads RGBA float pixels of a framebuffer's colour attachment 0 (or the default back buffer),
/// top row first.
Image readFramebuffer(GLuint fbo, int width, int height) {
    Image img(width, height, 4);
    if (width <= 0 || height <= 0)
        return {};
    GLint previous = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glReadBuffer(fbo ? GL_COLOR_ATTACHMENT0 : GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    std::vector<float> rows(size_t(width) * height * 4);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rows.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(previous));
    const size_t rowFloats = size_t(width) * 4;
    for (int y = 0; y < height; ++y)
        std::copy_n(rows.data() + size_t(height - 1 - y) * rowFloats, rowFloats,
                    img.pixels.data() + size_t(y) * rowFloats);
    return img;
}

} // namespace

struct Renderer::Impl {
    bool initialized = false;
    int compileCount = 0;

    ShaderProgram gbufferProgram, lightingProgram, tonemapProgram;
    GBuffer gbuffer;
    ColorTarget hdr;
    GpuMesh mesh;
    MaterialTable materials;
    EnvironmentCache environments;
    GLuint frameUbo = 0;
    GLuint emptyVao = 0;
    GLuint sheenLut = 0;
    GLuint queries[4] = {};
    bool queriesIssued = false;

    // The OCIO display transform: the config, the programs (cached by OCIO cache id inside
    // DisplayTransform) and which (display, view, look) maps to which cache id, so that switching
    // back to a view asks OCIO for nothing.
    std::shared_ptr<const ColorManagement> colorManagement;
    DisplayTransform displayTransform;
    std::map<std::string, std::string> displayCacheIds;
    std::string displayKey;

    Scene scene;
    bool haveScene = false;
    const GpuEnvironment* environment = nullptr;

    unsigned lastTarget = 0;
    int lastWidth = 0, lastHeight = 0;
    mutable FrameTimings timings;
    double cpuMs = 0;

    ~Impl() {
        if (frameUbo)
            glDeleteBuffers(1, &frameUbo);
        if (emptyVao)
            glDeleteVertexArrays(1, &emptyVao);
        if (sheenLut)
            glDeleteTextures(1, &sheenLut);
        if (queries[0])
            glDeleteQueries(4, queries);
    }

    bool buildPrograms(std::string* error) {
        struct {
            ShaderProgram& program;
            const char* vs;
            const char* fs;
        } programs[] = {{gbufferProgram, "gbuffer.vert", "gbuffer.frag"},
                        {lightingProgram, "fullscreen.vert", "lighting.frag"},
                        {tonemapProgram, "fullscreen.vert", "post_tonemap.frag"}};
        for (auto& p : programs) {
            if (!p.program.build(p.vs, p.fs, {}, error))
                return false;
            ++compileCount;
        }
        return true;
    }

    void uploadSheenLut() {
        const auto& table = brdf::sheenAlbedoLut();
        glCreateTextures(GL_TEXTURE_2D, 1, &sheenLut);
        glTextureStorage2D(sheenLut, 1, GL_R32F, brdf::kSheenLutSize, brdf::kSheenLutSize);
        glTextureSubImage2D(sheenLut, 0, 0, 0, brdf::kSheenLutSize, brdf::kSheenLutSize, GL_RED,
                            GL_FLOAT, table.data());
        glTextureParameteri(sheenLut, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(sheenLut, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(sheenLut, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(sheenLut, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }

    /// Selects the display transform @p fs names, building it the first time. Exposure is left
    /// out of the key and extracted as 0: it is a dynamic uniform set at every draw.
    bool selectDisplayTransform(const FrameSettings& fs, std::string* error) {
        const std::string key = fs.display + '\n' + fs.displayView + '\n' + fs.look;
        if (key == displayKey && displayTransform.hasSelection())
            return true;
        if (const auto it = displayCacheIds.find(key);
            it != displayCacheIds.end() && displayTransform.selectCached(it->second)) {
            displayKey = key;
            return true;
        }
        if (!colorManagement) {
            auto loaded = std::make_shared<ColorManagement>();
            if (!loaded->loadDefault(error))
                return false;
            colorManagement = std::move(loaded);
        }
        const DisplaySettings settings{fs.display, fs.displayView, fs.look, 0.0f};
        const std::optional<GpuDisplayTransform> transform =
            colorManagement->gpuDisplayTransform(settings, error);
        if (!transform || !displayTransform.select(*transform, error))
            return false;
        displayCacheIds[key] = transform->cacheId;
        displayKey = key;
        return true;
    }

    FrameBlock frameBlock(const FrameSettings& fs) const {
        FrameBlock b{};
        const Camera& cam = scene.camera;
        const float aspect = float(fs.width) / float(std::max(fs.height, 1));
        b.view = viewMatrix(cam);
        b.proj = projectionMatrix(cam, aspect);
        b.invProj = glm::inverse(b.proj);
        b.invView = glm::inverse(b.view);
        b.viewProj = b.proj * b.view;
        b.cameraPosition = glm::vec4(cameraEye(cam), cam.orthographic ? 1.0f : 0.0f);
        b.viewport = glm::vec4(float(fs.width), float(fs.height), 1.0f / float(fs.width),
                               1.0f / float(fs.height));
        const Environment& env = scene.environment;
        for (int i = 0; i < 9; ++i)
            b.envSh[i] = glm::vec4(environment->sh[i] * env.intensity, 0.0f);
        const float rot = glm::radians(env.rotationDeg);
        b.envParams =
            glm::vec4(std::cos(rot), std::sin(rot), env.intensity, float(environment->levels - 1));
        glm::vec3 ambient(0.0f);
        int count = 0;
        for (const Light& l : scene.lights) {
            if (l.type == LightType::Ambient) {
                ambient += l.color * l.intensity;
            } else if (l.type == LightType::Directional && count < kMaxLights) {
                const float len = glm::length(l.direction);
                const glm::vec3 toLight = len > 0.0f ? -l.direction / len : glm::vec3(0, 1, 0);
                b.lightDirection[count] = glm::vec4(toLight, 0.0f);
                b.lightRadiance[count] = glm::vec4(l.color * l.intensity, 0.0f);
                ++count;
            }
            // Point, spot and area lights arrive with the renderer issue.
        }
        b.ambientRadiance = glm::vec4(ambient, 0.0f);
        const float backgroundLod = env.background == BackgroundMode::Blurred
                                        ? std::min(4.0f, float(environment->levels - 1))
                                        : 0.0f;
        b.backgroundColor = glm::vec4(env.backgroundColor, backgroundLod);
        b.modes = glm::ivec4(count, int(fs.view), int(fs.toneMapper), int(env.background));
        b.post = glm::vec4(std::exp2(fs.exposureEv), 2.0f * std::max(cam.distance, 0.1f),
                           float(environment->width), 0.0f);
        return b;
    }
};

Renderer::Renderer() : m_impl(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

bool Renderer::initialize(std::string* error) {
    Impl& d = *m_impl;
    if (d.initialized)
        return true;
    if (epoxy_gl_version() < 45)
        return fail(error, "OpenGL 4.5 core is needed; the current context is " +
                               std::string(reinterpret_cast<const char*>(glGetString(GL_VERSION))));
    takeGlErrors();
    if (!d.buildPrograms(error))
        return false;
    glCreateBuffers(1, &d.frameUbo);
    glNamedBufferStorage(d.frameUbo, sizeof(FrameBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glCreateVertexArrays(1, &d.emptyVao);
    glCreateQueries(GL_TIMESTAMP, 4, d.queries);
    d.uploadSheenLut();
    d.mesh.upload(makeSphere());
    d.materials.upload({packMaterial(Material())});
    if (const std::string e = takeGlErrors(); !e.empty())
        return fail(error, "OpenGL error while creating renderer resources: " + e);
    d.initialized = true;
    if (!d.haveScene)
        setScene(Scene{});
    return true;
}

void Renderer::setColorManagement(std::shared_ptr<const ColorManagement> colorManagement) {
    Impl& d = *m_impl;
    d.colorManagement = std::move(colorManagement);
    // Names may mean other transforms in another config; compiled programs stay valid (same
    // cache id, same shader).
    d.displayCacheIds.clear();
    d.displayKey.clear();
}

void Renderer::setScene(const Scene& scene, Problems* problems) {
    Impl& d = *m_impl;
    d.scene = scene;
    d.haveScene = true;
    if (!d.initialized)
        return; // uploaded by initialize()
    if (scene.mesh.kind != PreviewMeshKind::Sphere && problems)
        problems->warning(scene.mesh.file, "mesh",
                          "only the sphere preview mesh is drawn so far; showing a sphere");
    // Numbers only: rewrite the material table (never a shader).
    d.materials.upload({packMaterial(scene.material)});
    d.environment = &d.environments.get(scene.environment, problems);
}

bool Renderer::render(const FrameSettings& fs, unsigned targetFbo, std::string* error) {
    Impl& d = *m_impl;
    if (!d.initialized)
        return fail(error, "Renderer::render called before initialize()");
    if (fs.width <= 0 || fs.height <= 0 || fs.width > 16384 || fs.height > 16384)
        return fail(error, "invalid frame size " + std::to_string(fs.width) + "x" +
                               std::to_string(fs.height));
    const auto cpuStart = std::chrono::steady_clock::now();
    takeGlErrors(); // errors left by whoever owns the context are not ours
    // An unknown display, view or look fails here, before anything is drawn.
    const bool ocioDisplay = fs.usesColorManagement() && fs.view == DebugView::Final;
    if (ocioDisplay && !d.selectDisplayTransform(fs, error))
        return false;
    if (!d.environment)
        d.environment = &d.environments.get(d.scene.environment, nullptr);
    if (!d.gbuffer.resize(fs.width, fs.height, error) ||
        !d.hdr.resize(fs.width, fs.height, GL_RGBA16F, error))
        return false;
    if (targetFbo != 0) {
        const GLenum status = glCheckNamedFramebufferStatus(targetFbo, GL_DRAW_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            return fail(error, "target framebuffer " + std::to_string(targetFbo) +
                                   " is incomplete: " + framebufferStatusName(status));
    }

    const FrameBlock block = d.frameBlock(fs);
    glNamedBufferSubData(d.frameUbo, 0, sizeof(FrameBlock), &block);
    glBindBufferBase(GL_UNIFORM_BUFFER, binding::kFrameUbo, d.frameUbo);
    d.materials.bind();

    // Known state: a host (Qt) may leave anything bound or enabled.
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_MULTISAMPLE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glViewport(0, 0, fs.width, fs.height);
    glQueryCounter(d.queries[0], GL_TIMESTAMP);

    // 1. G-buffer.
    glBindFramebuffer(GL_FRAMEBUFFER, d.gbuffer.framebuffer());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    const float zeros[4] = {0, 0, 0, 0};
    for (int i = 0; i < gbufferColorAttachmentCount(); ++i)
        glClearBufferfv(GL_COLOR, i, zeros);
    const float farDepth = 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &farDepth);
    glUseProgram(d.gbufferProgram.id());
    glProgramUniform1i(d.gbufferProgram.id(), 0, 0); // uMaterialId: one material for now
    d.mesh.draw();
    glQueryCounter(d.queries[1], GL_TIMESTAMP);

    // 2. Lighting + background into the HDR target.
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glBindFramebuffer(GL_FRAMEBUFFER, d.hdr.framebuffer());
    d.gbuffer.bindTextures();
    glBindTextureUnit(binding::kEnvironmentTex, d.environment->texture);
    glBindTextureUnit(binding::kSheenLutTex, d.sheenLut);
    glBindVertexArray(d.emptyVao);
    glUseProgram(d.lightingProgram.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glQueryCounter(d.queries[2], GL_TIMESTAMP);

    // 3. Into the target: OCIO's display transform (exposure, look, display/view in one generated
    // function), or the built-in exposure, tone mapper and sRGB OETF.
    glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);
    if (ocioDisplay) {
        d.displayTransform.draw(d.hdr.texture(), fs.exposureEv);
    } else {
        glBindTextureUnit(binding::kHdrTex, d.hdr.texture());
        glUseProgram(d.tonemapProgram.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glQueryCounter(d.queries[3], GL_TIMESTAMP);
    d.queriesIssued = true;

    // Leave sane defaults for the host.
    glUseProgram(0);
    glBindVertexArray(0);
    glDepthMask(GL_TRUE);
    for (GLuint unit : {0u, 1u, 2u, 3u, GLuint(binding::kEnvironmentTex),
                        GLuint(binding::kSheenLutTex), GLuint(binding::kHdrTex)})
        glBindTextureUnit(unit, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);

    d.lastTarget = targetFbo;
    d.lastWidth = fs.width;
    d.lastHeight = fs.height;
    d.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpuStart)
                  .count();
    if (const std::string e = takeGlErrors(); !e.empty())
        return fail(error, "OpenGL error while rendering: " + e);
    return true;
}

Image Renderer::readLinear() const {
    const Impl& d = *m_impl;
    if (!d.initialized || !d.hdr.framebuffer())
        return {};
    return readFramebuffer(d.hdr.framebuffer(), d.hdr.width(), d.hdr.height());
}

Image Renderer::readDisplay() const {
    const Impl& d = *m_impl;
    if (!d.initialized || d.lastWidth == 0)
        return {};
    return readFramebuffer(d.lastTarget, d.lastWidth, d.lastHeight);
}

int Renderer::shaderCompileCount() const {
    return m_impl->compileCount + m_impl->displayTransform.compileCount();
}

FrameTimings Renderer::lastTimings() const {
    const Impl& d = *m_impl;
    if (d.queriesIssued) {
        GLuint64 t[4] = {};
        for (int i = 0; i < 4; ++i)
            glGetQueryObjectui64v(d.queries[i], GL_QUERY_RESULT, &t[i]);
        d.timings.gbufferMs = double(t[1] - t[0]) * 1e-6;
        d.timings.lightingMs = double(t[2] - t[1]) * 1e-6;
        d.timings.postMs = double(t[3] - t[2]) * 1e-6;
        d.timings.totalMs = double(t[3] - t[0]) * 1e-6;
    }
    return d.timings;
}

} // namespace velvet::render
