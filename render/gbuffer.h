#pragma once
/// @file gbuffer.h
/// Render-private: the G-buffer framebuffer, allocated from gbuffer_layout.h's table.

#include <string>

namespace velvet::render {

class GBuffer {
public:
    GBuffer() = default;
    ~GBuffer();
    GBuffer(const GBuffer&) = delete;
    GBuffer& operator=(const GBuffer&) = delete;

    /// (Re)allocates for @p width x @p height when the size or the layout changed; checks
    /// completeness. @p compact: the 16-byte layout without the lobe channels (for comparison).
    bool resize(int width, int height, bool compact, std::string* error);
    unsigned framebuffer() const { return m_fbo; }
    /// Binds every attachment as a texture at its layout unit (a compact layout's lobe units get
    /// texture 0: incomplete, reads as zero; no material maps a channel then).
    void bindTextures() const;
    /// The texture of attachment @p attachment (gbufferAttachments() order; 0 when absent).
    unsigned texture(int attachment) const;
    bool compact() const { return m_compact; }
    int width() const { return m_width; }
    int height() const { return m_height; }
    /// Changes whenever resize() reallocates, unique across targets: framebuffers built over
    /// these textures compare it, not the GL names, which a driver may hand out again.
    unsigned generation() const { return m_generation; }

private:
    void release();
    unsigned m_generation = 0;
    unsigned m_fbo = 0;
    unsigned m_textures[8] = {};
    int m_count = 0;
    int m_width = 0, m_height = 0;
    bool m_compact = false;
};

/// One colour texture + framebuffer (the HDR target, and the display target offscreen).
class ColorTarget {
public:
    ColorTarget() = default;
    ~ColorTarget();
    ColorTarget(const ColorTarget&) = delete;
    ColorTarget& operator=(const ColorTarget&) = delete;

    /// @p internalFormat is a GL enum (GL_RGBA16F, GL_RGBA8, ...).
    bool resize(int width, int height, unsigned internalFormat, std::string* error);
    unsigned framebuffer() const { return m_fbo; }
    unsigned texture() const { return m_texture; }
    int width() const { return m_width; }
    int height() const { return m_height; }
    /// As GBuffer::generation().
    unsigned generation() const { return m_generation; }

private:
    void release();
    unsigned m_generation = 0;
    unsigned m_fbo = 0, m_texture = 0, m_format = 0;
    int m_width = 0, m_height = 0;
};

/// "complete" or the name of the GL framebuffer status.
std::string framebufferStatusName(unsigned status);

} // namespace velvet::render
