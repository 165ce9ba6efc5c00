#include "render/gbuffer.h"

#include "render/gbuffer_layout.h"

#include <algorithm>
#include <epoxy/gl.h>

namespace velvet::render {
namespace {

GLenum toGl(GBufferFormat f) {
    switch (f) {
    case GBufferFormat::Depth32F:
        return GL_DEPTH_COMPONENT32F;
    case GBufferFormat::RGBA8:
        return GL_RGBA8;
    case GBufferFormat::RG16:
        return GL_RG16;
    }
    return GL_RGBA8;
}

void setNearest(GLuint tex) {
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

} // namespace

std::string framebufferStatusName(unsigned status) {
    switch (status) {
    case GL_FRAMEBUFFER_COMPLETE:
        return "complete";
    case GL_FRAMEBUFFER_UNDEFINED:
        return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
        return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
        return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER:
        return "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER";
    case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER:
        return "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER";
    case GL_FRAMEBUFFER_UNSUPPORTED:
        return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
        return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS:
        return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
    default:
        return "framebuffer status " + std::to_string(status);
    }
}

GBuffer::~GBuffer() {
    release();
}

void GBuffer::release() {
    for (int i = 0; i < m_count; ++i)
        if (m_textures[i])
            glDeleteTextures(1, &m_textures[i]);
    std::fill(std::begin(m_textures), std::end(m_textures), 0u);
    if (m_fbo)
        glDeleteFramebuffers(1, &m_fbo);
    m_fbo = 0;
    m_count = 0;
    m_width = m_height = 0;
}

namespace {
unsigned nextTargetGeneration() {
    static unsigned generation = 0;
    return ++generation;
}
} // namespace

bool GBuffer::resize(int width, int height, bool compact, std::string* error) {
    if (m_fbo && width == m_width && height == m_height && compact == m_compact)
        return true;
    release();
    m_generation = nextTargetGeneration();
    const auto attachments = gbufferAttachments();
    m_count = int(attachments.size());
    glCreateFramebuffers(1, &m_fbo);
    GLenum drawBuffers[8];
    const int colorCount = gbufferColorAttachmentCount();
    for (int i = 0; i < m_count; ++i) {
        // The compact layout (velvet bench's 16-byte comparison) leaves the lobe channels out:
        // their draw buffers are GL_NONE, so the geometry pass's writes to them cost nothing.
        const bool present = !(compact && attachments[i].lobeChannels);
        if (i < colorCount)
            drawBuffers[i] = present ? GLenum(GL_COLOR_ATTACHMENT0 + i) : GLenum(GL_NONE);
        if (!present)
            continue;
        glCreateTextures(GL_TEXTURE_2D, 1, &m_textures[i]);
        glTextureStorage2D(m_textures[i], 1, toGl(attachments[i].format), width, height);
        setNearest(m_textures[i]);
        glNamedFramebufferTexture(
            m_fbo, i < colorCount ? GLenum(GL_COLOR_ATTACHMENT0 + i) : GLenum(GL_DEPTH_ATTACHMENT),
            m_textures[i], 0);
    }
    glNamedFramebufferDrawBuffers(m_fbo, colorCount, drawBuffers);
    const GLenum status = glCheckNamedFramebufferStatus(m_fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        if (error)
            *error = "G-buffer framebuffer (" + std::to_string(width) + "x" +
                     std::to_string(height) + ") is incomplete: " + framebufferStatusName(status);
        release();
        return false;
    }
    m_width = width;
    m_height = height;
    m_compact = compact;
    return true;
}

void GBuffer::bindTextures() const {
    const auto attachments = gbufferAttachments();
    for (int i = 0; i < m_count; ++i)
        glBindTextureUnit(GLuint(attachments[i].unit), m_textures[i]);
}

unsigned GBuffer::texture(int attachment) const {
    return attachment >= 0 && attachment < m_count ? m_textures[attachment] : 0u;
}

ColorTarget::~ColorTarget() {
    release();
}

void ColorTarget::release() {
    if (m_texture)
        glDeleteTextures(1, &m_texture);
    if (m_fbo)
        glDeleteFramebuffers(1, &m_fbo);
    m_texture = m_fbo = 0;
    m_width = m_height = 0;
}

bool ColorTarget::resize(int width, int height, unsigned internalFormat, std::string* error) {
    if (m_fbo && width == m_width && height == m_height && internalFormat == m_format)
        return true;
    release();
    m_generation = nextTargetGeneration();
    glCreateTextures(GL_TEXTURE_2D, 1, &m_texture);
    glTextureStorage2D(m_texture, 1, internalFormat, width, height);
    setNearest(m_texture);
    glCreateFramebuffers(1, &m_fbo);
    glNamedFramebufferTexture(m_fbo, GL_COLOR_ATTACHMENT0, m_texture, 0);
    glNamedFramebufferDrawBuffer(m_fbo, GL_COLOR_ATTACHMENT0);
    const GLenum status = glCheckNamedFramebufferStatus(m_fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        if (error)
            *error = "colour target (" + std::to_string(width) + "x" + std::to_string(height) +
                     ") is incomplete: " + framebufferStatusName(status);
        release();
        return false;
    }
    m_format = internalFormat;
    m_width = width;
    m_height = height;
    return true;
}

} // namespace velvet::render
