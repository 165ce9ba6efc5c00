#include "render/display_transform.h"

#include "render/ocio_gpu.h"
#include "render/shader_program.h"

#include <algorithm>
#include <epoxy/gl.h>
#include <map>

namespace velvet::render {
namespace {

/// The generated include display_transform.frag pulls OCIO's GLSL from.
constexpr const char* kGeneratedInclude = "ocio_display.glsl";

GLenum textureTarget(int dimensions) {
    return dimensions == 1 ? GL_TEXTURE_1D : dimensions == 2 ? GL_TEXTURE_2D : GL_TEXTURE_3D;
}

} // namespace

/// One LUT as OCIO's own OpenGL helper (OpenColorIO/src/libutils/oglapphelpers/oglapp.cpp,
/// AllocateTexture2D / AllocateTexture3D) makes it: 32-bit float, R or RGB, clamp to edge,
/// GL_NEAREST for nearest LUTs and GL_LINEAR otherwise (tetrahedral blending happens in the GLSL).
unsigned uploadOcioLut(const GpuLutTexture& lut) {
    const GLenum target = textureTarget(lut.dimensions);
    const GLenum internalFormat = lut.channels == 1 ? GL_R32F : GL_RGB32F;
    const GLenum format = lut.channels == 1 ? GL_RED : GL_RGB;
    GLuint tex = 0;
    glCreateTextures(target, 1, &tex);
    if (lut.dimensions == 1) {
        glTextureStorage1D(tex, 1, internalFormat, lut.width);
        glTextureSubImage1D(tex, 0, 0, lut.width, format, GL_FLOAT, lut.values.data());
    } else if (lut.dimensions == 2) {
        glTextureStorage2D(tex, 1, internalFormat, lut.width, lut.height);
        glTextureSubImage2D(tex, 0, 0, 0, lut.width, lut.height, format, GL_FLOAT,
                            lut.values.data());
    } else {
        glTextureStorage3D(tex, 1, internalFormat, lut.width, lut.height, lut.depth);
        glTextureSubImage3D(tex, 0, 0, 0, 0, lut.width, lut.height, lut.depth, format, GL_FLOAT,
                            lut.values.data());
    }
    const GLint filter =
        lut.interpolation == GpuLutTexture::Interpolation::Nearest ? GL_NEAREST : GL_LINEAR;
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, filter);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    return tex;
}

/// Sets a uniform's extraction-time value (all but the exposure keep it for the program's life:
/// Velvet makes only the exposure dynamic).
void setOcioUniform(unsigned program, const GpuUniform& u) {
    const GLint loc = glGetUniformLocation(program, u.name.c_str());
    if (loc < 0)
        return; // declared but unused: the GLSL compiler removed it
    switch (u.type) {
    case GpuUniform::Type::Float:
        if (!u.floats.empty())
            glProgramUniform1f(program, loc, u.floats[0]);
        break;
    case GpuUniform::Type::Bool:
        if (!u.floats.empty())
            glProgramUniform1i(program, loc, u.floats[0] != 0.0f ? 1 : 0);
        break;
    case GpuUniform::Type::Float3:
        if (u.floats.size() >= 3)
            glProgramUniform3fv(program, loc, 1, u.floats.data());
        break;
    case GpuUniform::Type::FloatArray:
        if (!u.floats.empty())
            glProgramUniform1fv(program, loc, GLsizei(u.floats.size()), u.floats.data());
        break;
    case GpuUniform::Type::IntArray:
        if (!u.ints.empty())
            glProgramUniform1iv(program, loc, GLsizei(u.ints.size()), u.ints.data());
        break;
    }
}

namespace {

bool fail(std::string* error, const std::string& message) {
    if (error)
        *error = message;
    return false;
}

} // namespace

struct DisplayTransform::Impl {
    /// One compiled transform: program, LUT textures (at units kDisplayLutTexFirst + i) and the
    /// location of the dynamic exposure uniform (-1: none).
    struct Program {
        ShaderProgram program;
        std::vector<GLuint> luts;
        GLint exposureLocation = -1;
        GpuDisplayTransform source; ///< kept for reload() (shader text from disk, OCIO's GLSL)
        ~Program() {
            if (!luts.empty())
                glDeleteTextures(GLsizei(luts.size()), luts.data());
        }
    };

    std::map<std::string, std::unique_ptr<Program>> cache; ///< keyed by OCIO's cache id
    Program* selected = nullptr;
    int compiles = 0;
    GLuint emptyVao = 0;

    ~Impl() {
        cache.clear();
        if (emptyVao)
            glDeleteVertexArrays(1, &emptyVao);
    }

    bool build(const GpuDisplayTransform& t, Program& p, std::string* error) {
        GLint maxUnits = 0;
        glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &maxUnits);
        if (binding::kDisplayLutTexFirst + int(t.textures.size()) > maxUnits)
            return fail(error, "the display transform needs " + std::to_string(t.textures.size()) +
                                   " LUT textures from unit " +
                                   std::to_string(binding::kDisplayLutTexFirst) +
                                   " but the GL context has " + std::to_string(maxUnits) +
                                   " texture units");
        if (!compile(t, p, error))
            return false;
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 0);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
        for (const GpuLutTexture& lut : t.textures)
            p.luts.push_back(uploadOcioLut(lut));
        setUniforms(t, p);
        p.source = t;
        for (GpuLutTexture& lut : p.source.textures)
            lut.values = {}; // uploaded; reload() needs only the names
        return true;
    }

    /// Compiles display_transform.frag with @p t's GLSL into @p p (the last good program stays on
    /// failure).
    bool compile(const GpuDisplayTransform& t, Program& p, std::string* error) {
        if (!p.program.build("fullscreen.vert", "display_transform.frag",
                             {"OCIO_DISPLAY " + t.functionName}, {{kGeneratedInclude, t.glsl}},
                             error))
            return false;
        ++compiles;
        return true;
    }

    /// Sampler units and extraction-time uniform values of a freshly linked program.
    void setUniforms(const GpuDisplayTransform& t, Program& p) {
        const GLuint program = p.program.id();
        for (size_t i = 0; i < t.textures.size(); ++i) {
            const GLint loc = glGetUniformLocation(program, t.textures[i].samplerName.c_str());
            if (loc >= 0)
                glProgramUniform1i(program, loc, binding::kDisplayLutTexFirst + int(i));
        }
        p.exposureLocation = -1;
        for (const GpuUniform& u : t.uniforms) {
            setOcioUniform(program, u);
            if (u.isExposure)
                p.exposureLocation = glGetUniformLocation(program, u.name.c_str());
        }
    }
};

DisplayTransform::DisplayTransform() : m_impl(std::make_unique<Impl>()) {}
DisplayTransform::~DisplayTransform() = default;

bool DisplayTransform::select(const GpuDisplayTransform& transform, std::string* error) {
    Impl& d = *m_impl;
    if (selectCached(transform.cacheId))
        return true;
    auto program = std::make_unique<Impl::Program>();
    if (!d.build(transform, *program, error))
        return false;
    d.selected = program.get();
    d.cache[transform.cacheId] = std::move(program);
    return true;
}

bool DisplayTransform::reload(std::string* error) {
    Impl& d = *m_impl;
    std::string errors;
    for (auto& [id, program] : d.cache) {
        std::string message;
        if (d.compile(program->source, *program, &message))
            d.setUniforms(program->source, *program);
        else
            errors += (errors.empty() ? "" : "\n") + message;
    }
    if (!errors.empty() && error)
        *error = errors;
    return errors.empty();
}

bool DisplayTransform::selectCached(const std::string& cacheId) {
    Impl& d = *m_impl;
    const auto it = d.cache.find(cacheId);
    if (it == d.cache.end())
        return false;
    d.selected = it->second.get();
    return true;
}

bool DisplayTransform::hasSelection() const {
    return m_impl->selected != nullptr;
}

void DisplayTransform::draw(unsigned hdrTexture, float exposureEv) {
    Impl& d = *m_impl;
    if (!d.selected)
        return;
    if (!d.emptyVao)
        glCreateVertexArrays(1, &d.emptyVao);
    const GLuint program = d.selected->program.id();
    if (d.selected->exposureLocation >= 0)
        glProgramUniform1f(program, d.selected->exposureLocation, exposureEv);
    glBindTextureUnit(binding::kHdrTex, hdrTexture);
    const auto& luts = d.selected->luts;
    for (size_t i = 0; i < luts.size(); ++i)
        glBindTextureUnit(GLuint(binding::kDisplayLutTexFirst + int(i)), luts[i]);
    glUseProgram(program);
    glBindVertexArray(d.emptyVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glUseProgram(0);
    for (size_t i = 0; i < luts.size(); ++i)
        glBindTextureUnit(GLuint(binding::kDisplayLutTexFirst + int(i)), 0);
    glBindTextureUnit(binding::kHdrTex, 0);
}

bool DisplayTransform::apply(const Image& linear, float exposureEv, Image& display,
                             std::string* error) {
    if (!m_impl->selected)
        return fail(error, "DisplayTransform::apply: no display transform is selected");
    if (linear.empty() || linear.channels < 1 || linear.channels > 4)
        return fail(error, "DisplayTransform::apply: empty image or unsupported channel count");
    const int w = linear.width, h = linear.height;
    // GL's row 0 is the bottom row: upload flipped so texel (x, y) of the pass is Image (x, h-1-y).
    std::vector<float> rgba(size_t(w) * h * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::vec4 p = linear.rgba(x, y);
            float* o = &rgba[(size_t(h - 1 - y) * w + x) * 4];
            o[0] = p.r, o[1] = p.g, o[2] = p.b, o[3] = p.a;
        }
    while (glGetError() != GL_NO_ERROR) {
    }
    GLuint textures[2] = {};
    glCreateTextures(GL_TEXTURE_2D, 2, textures);
    for (GLuint t : textures) {
        glTextureStorage2D(t, 1, GL_RGBA32F, w, h);
        glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glTextureSubImage2D(textures[0], 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, rgba.data());
    GLuint fbo = 0;
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, textures[1], 0);
    glNamedFramebufferDrawBuffer(fbo, GL_COLOR_ATTACHMENT0);

    GLint previousFbo = 0, previousViewport[4] = {};
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previousFbo);
    glGetIntegerv(GL_VIEWPORT, previousViewport);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    draw(textures[0], exposureEv);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(previousFbo));
    glViewport(previousViewport[0], previousViewport[1], previousViewport[2], previousViewport[3]);

    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glGetTextureImage(textures[1], 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)),
                      rgba.data());
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(2, textures);
    if (const GLenum e = glGetError(); e != GL_NO_ERROR)
        return fail(error, "DisplayTransform::apply: OpenGL error " + std::to_string(e));

    display = Image(w, h, 4);
    for (int y = 0; y < h; ++y)
        std::copy_n(&rgba[size_t(h - 1 - y) * w * 4], size_t(w) * 4, display.at(0, y));
    return true;
}

int DisplayTransform::compileCount() const {
    return m_impl->compiles;
}

int DisplayTransform::cachedProgramCount() const {
    return int(m_impl->cache.size());
}

} // namespace velvet::render
