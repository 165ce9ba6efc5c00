#include "render/frame_targets.h"

#include "render/gbuffer_layout.h"
#include "render/gl_util.h"
#include "render/shadow_mask.h"

#include <epoxy/gl.h>
#include <vector>

namespace velvet::render {
namespace {

GLuint depthTextureOf(GLuint fbo) {
    GLint depthTexture = 0;
    glGetNamedFramebufferAttachmentParameteriv(
        fbo, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &depthTexture);
    return GLuint(depthTexture);
}

} // namespace

FrameTargets::~FrameTargets() {
    if (m_litFbo)
        glDeleteFramebuffers(1, &m_litFbo);
    for (DepthSharingTarget* t : {&m_display, &m_reflectionSource})
        if (t->fbo)
            glDeleteFramebuffers(1, &t->fbo);
    if (m_geometryFbo)
        glDeleteFramebuffers(1, &m_geometryFbo);
    if (m_maskFbo)
        glDeleteFramebuffers(1, &m_maskFbo);
    if (m_maskDepth)
        glDeleteRenderbuffers(1, &m_maskDepth);
}

bool FrameTargets::resize(int width, int height, bool compactGBuffer, std::string* error) {
    return m_gbuffer.resize(width, height, compactGBuffer, error) &&
           m_hdr.resize(width, height, GL_RGBA16F, error);
}

unsigned FrameTargets::geometryFramebuffer(bool emission, bool lobeTargets, std::string* error) {
    const GLuint depthTexture = depthTextureOf(m_gbuffer.framebuffer());
    if (!m_geometryFbo)
        glCreateFramebuffers(1, &m_geometryFbo);
    const int n = gbufferColorAttachmentCount();
    if (m_geometryHdrGeneration != m_hdr.generation() ||
        m_geometryGbufferGeneration != m_gbuffer.generation()) {
        std::vector<GLenum> drawBuffers;
        for (int i = 0; i < n; ++i) {
            GLint texture = 0;
            glGetNamedFramebufferAttachmentParameteriv(
                m_gbuffer.framebuffer(), GLenum(GL_COLOR_ATTACHMENT0 + i),
                GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &texture);
            glNamedFramebufferTexture(m_geometryFbo, GLenum(GL_COLOR_ATTACHMENT0 + i),
                                      GLuint(texture), 0);
            drawBuffers.push_back(m_gbuffer.texture(i) ? GLenum(GL_COLOR_ATTACHMENT0 + i)
                                                       : GLenum(GL_NONE));
        }
        glNamedFramebufferTexture(m_geometryFbo, GLenum(GL_COLOR_ATTACHMENT0 + n), m_hdr.texture(),
                                  0);
        drawBuffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + n));
        glNamedFramebufferTexture(m_geometryFbo, GL_DEPTH_ATTACHMENT, depthTexture, 0);
        glNamedFramebufferDrawBuffers(m_geometryFbo, GLsizei(drawBuffers.size()),
                                      drawBuffers.data());
        const GLenum status = glCheckNamedFramebufferStatus(m_geometryFbo, GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            fail(error, "geometry framebuffer incomplete: " + framebufferStatusName(status));
            return 0;
        }
        m_geometryHdrGeneration = m_hdr.generation();
        m_geometryGbufferGeneration = m_gbuffer.generation();
        m_geometryDrawBuffers = -1;
    }
    const int state = int(emission) | int(lobeTargets) << 1;
    if (m_geometryDrawBuffers != state) {
        std::vector<GLenum> drawBuffers;
        for (int i = 0; i < n; ++i) // the compact layout has no lobe channels (GL_NONE)
            drawBuffers.push_back(
                m_gbuffer.texture(i) &&
                        (lobeTargets || !gbufferAttachments()[size_t(i)].lobeChannels)
                    ? GLenum(GL_COLOR_ATTACHMENT0 + i)
                    : GLenum(GL_NONE));
        drawBuffers.push_back(emission ? GLenum(GL_COLOR_ATTACHMENT0 + n) : GLenum(GL_NONE));
        glNamedFramebufferDrawBuffers(m_geometryFbo, GLsizei(drawBuffers.size()),
                                      drawBuffers.data());
        m_geometryDrawBuffers = state;
    }
    return m_geometryFbo;
}

unsigned FrameTargets::litFramebuffer() {
    const GLuint depthTexture = depthTextureOf(m_gbuffer.framebuffer());
    if (!m_litFbo)
        glCreateFramebuffers(1, &m_litFbo);
    if (m_litHdrGeneration != m_hdr.generation() ||
        m_litGbufferGeneration != m_gbuffer.generation()) {
        glNamedFramebufferTexture(m_litFbo, GL_COLOR_ATTACHMENT0, m_hdr.texture(), 0);
        glNamedFramebufferTexture(m_litFbo, GL_DEPTH_ATTACHMENT, depthTexture, 0);
        m_litHdrGeneration = m_hdr.generation();
        m_litGbufferGeneration = m_gbuffer.generation();
    }
    return m_litFbo;
}

unsigned FrameTargets::shadowMaskFramebuffer(int downsample, std::string* error) {
    // One byte per shadow slot (kMaxShadowLights = 4 channels): the lighting passes read every
    // slot's visibility in one fetch. At the stage's downsample D of the frame's size (rounded
    // up): texel t is the lookup at pixel D t, upsampled where it is read (shadow_mask.glsl) by
    // its key beside it, that pixel's view depth and material id.
    const int width = maskSize(m_hdr.width(), downsample);
    const int height = maskSize(m_hdr.height(), downsample);
    if (!m_shadowMask.resize(width, height, GL_RGBA8, error) ||
        !m_shadowKey.resize(width, height, GL_RG32F, error) ||
        !m_groundShadowMask.resize(width, height, GL_RGBA8, error))
        return 0;
    if (!m_maskFbo)
        glCreateFramebuffers(1, &m_maskFbo);
    if (m_maskGeneration != m_shadowMask.generation() ||
        m_keyGeneration != m_shadowKey.generation() ||
        m_groundMaskGeneration != m_groundShadowMask.generation()) {
        // The upsample gathers the key around a texel corner: the last row and column clamp.
        glTextureParameteri(m_shadowKey.texture(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(m_shadowKey.texture(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glNamedFramebufferTexture(m_maskFbo, GL_COLOR_ATTACHMENT0, m_shadowMask.texture(), 0);
        glNamedFramebufferTexture(m_maskFbo, GL_COLOR_ATTACHMENT1, m_shadowKey.texture(), 0);
        // The ground's mask is smooth across the mesh's silhouettes (the ground behind the mesh,
        // not the mesh): the catcher reads it with the hardware's bilinear filter.
        const GLuint ground = m_groundShadowMask.texture();
        glTextureParameteri(ground, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(ground, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(ground, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(ground, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glNamedFramebufferTexture(m_maskFbo, GL_COLOR_ATTACHMENT2, ground, 0);
        // Which texels the lookup pass shades: depth 0 where the settle pass settled them, 1
        // where it did not, tested against its triangle's 0.5 (render/shadow_mask.cpp).
        if (m_maskDepth)
            glDeleteRenderbuffers(1, &m_maskDepth);
        glCreateRenderbuffers(1, &m_maskDepth);
        glNamedRenderbufferStorage(m_maskDepth, GL_DEPTH_COMPONENT16, width, height);
        glNamedFramebufferRenderbuffer(m_maskFbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                       m_maskDepth);
        const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
                                   GL_COLOR_ATTACHMENT2};
        glNamedFramebufferDrawBuffers(m_maskFbo, 3, buffers);
        const GLenum status = glCheckNamedFramebufferStatus(m_maskFbo, GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            fail(error, "shadow mask framebuffer incomplete: " + framebufferStatusName(status));
            return 0;
        }
        m_maskGeneration = m_shadowMask.generation();
        m_keyGeneration = m_shadowKey.generation();
        m_groundMaskGeneration = m_groundShadowMask.generation();
    }
    return m_maskFbo;
}

unsigned FrameTargets::depthSharingFramebuffer(DepthSharingTarget& t, unsigned internalFormat,
                                               const char* what, std::string* error) {
    if (!t.color.resize(m_gbuffer.width(), m_gbuffer.height(), internalFormat, error))
        return 0;
    if (!t.fbo)
        glCreateFramebuffers(1, &t.fbo);
    if (t.colorGeneration != t.color.generation() ||
        t.gbufferGeneration != m_gbuffer.generation()) {
        glNamedFramebufferTexture(t.fbo, GL_COLOR_ATTACHMENT0, t.color.texture(), 0);
        glNamedFramebufferTexture(t.fbo, GL_DEPTH_ATTACHMENT,
                                  depthTextureOf(m_gbuffer.framebuffer()), 0);
        const GLenum status = glCheckNamedFramebufferStatus(t.fbo, GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            fail(error,
                 std::string(what) + " framebuffer incomplete: " + framebufferStatusName(status));
            return 0;
        }
        t.colorGeneration = t.color.generation();
        t.gbufferGeneration = m_gbuffer.generation();
    }
    return t.fbo;
}

unsigned FrameTargets::displayFramebuffer(unsigned internalFormat, std::string* error) {
    return depthSharingFramebuffer(m_display, internalFormat, "display", error);
}

unsigned FrameTargets::reflectionSourceFramebuffer(std::string* error) {
    return depthSharingFramebuffer(m_reflectionSource, GL_RGBA16F, "reflection source", error);
}

} // namespace velvet::render
