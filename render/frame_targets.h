#pragma once
/// @file frame_targets.h
/// Render-private: the frame's render targets — the G-buffer, the HDR colour — and the two
/// framebuffers assembled over their textures: the geometry pass's (the G-buffer's attachments
/// plus the HDR colour after them, which receives each pixel's emission, gbuffer.frag's
/// gEmission) and the lighting pass's (the HDR colour with the G-buffer's depth, read-only: its
/// full-screen triangles at the far plane are depth-tested so surfaces shade only geometry pixels
/// and the background only the others).
///
/// The assembled framebuffers are rebuilt when either target's allocation generation changes,
/// never by comparing GL names: a driver may hand a freed name out again (ctest runs Mesa with
/// force_gl_names_reuse to prove it).

#include "render/gbuffer.h"

#include <string>

namespace velvet::render {

class FrameTargets {
public:
    FrameTargets() = default;
    /// Needs the renderer's context current (frees the assembled framebuffers).
    ~FrameTargets();
    FrameTargets(const FrameTargets&) = delete;
    FrameTargets& operator=(const FrameTargets&) = delete;

    /// (Re)allocates the G-buffer and the HDR colour (RGBA16F) for @p width x @p height.
    /// @p compactGBuffer: the 16-byte G-buffer without lobe channels (GBuffer::resize).
    bool resize(int width, int height, bool compactGBuffer, std::string* error);

    /// The geometry pass's framebuffer, its HDR draw buffer on only when the frame can emit
    /// (writing emission costs a 16-bit RGBA store per pixel and a blend in the lighting pass:
    /// about 5 ms of a 58 ms 1280x720 frame on llvmpipe), its lobe-channel draw buffers on only
    /// when @p lobeTargets (a drawn material has a lobe map; otherwise nothing reads them).
    /// 0 + message when incomplete.
    unsigned geometryFramebuffer(bool emission, bool lobeTargets, std::string* error);
    /// The lighting pass's framebuffer (HDR colour + the G-buffer's depth).
    unsigned litFramebuffer();
    /// The framebuffer of a lighting pass that writes display values (issue 16: the display
    /// step compiled into it): a colour target in @p internalFormat (the caller's target's, so
    /// the copy into it changes no value) with the G-buffer's depth, read-only as in
    /// litFramebuffer(). Allocated on first use. 0 + message when incomplete.
    unsigned displayFramebuffer(unsigned internalFormat, std::string* error);
    const ColorTarget& display() const { return m_display.color; }
    /// The framebuffer of the first surfaces pass of a frame with screen-space reflections
    /// (FrameSettings::screenSpaceReflections): a copy of the HDR colour (RGBA16F) with the
    /// G-buffer's depth, read-only as in litFramebuffer(); the second pass reads its colour.
    /// Allocated on first use. 0 + message when incomplete.
    unsigned reflectionSourceFramebuffer(std::string* error);
    const ColorTarget& reflectionSource() const { return m_reflectionSource.color; }

    /// The screen-space shadow mask's framebuffer (render/shadow_mask.h): at the stage's
    /// @p downsample of the frame's size (maskSize()), the mask (RGBA8, attachment 0) and its key
    /// (RG32F: each texel's pixel's view depth and material id, attachment 1) and the ground's mask
    /// (RGBA8, attachment 2: each texel's visibility where its pixel's view ray meets the ground,
    /// read with bilinear filtering by the shadow catcher), with a 16-bit depth buffer that marks
    /// the texels the mask's settle pass left for the lookup (render/shadow_mask.h), allocated the
    /// first time a frame has a shadowed light. 0 + message when incomplete.
    unsigned shadowMaskFramebuffer(int downsample, std::string* error);

    const GBuffer& gbuffer() const { return m_gbuffer; }
    const ColorTarget& hdr() const { return m_hdr; }
    const ColorTarget& shadowMask() const { return m_shadowMask; }
    const ColorTarget& shadowKey() const { return m_shadowKey; }
    const ColorTarget& groundShadowMask() const { return m_groundShadowMask; }

private:
    GBuffer m_gbuffer;
    ColorTarget m_hdr;
    unsigned m_geometryFbo = 0;
    unsigned m_geometryHdrGeneration = 0, m_geometryGbufferGeneration = 0;
    /// The draw buffers set: emission (bit 0) and lobe targets (bit 1); -1: not set yet.
    int m_geometryDrawBuffers = -1;
    unsigned m_litFbo = 0;
    unsigned m_litHdrGeneration = 0, m_litGbufferGeneration = 0;
    ColorTarget m_shadowMask, m_shadowKey, m_groundShadowMask;
    unsigned m_maskFbo = 0, m_maskDepth = 0; ///< the depth: a renderbuffer of the mask's size
    unsigned m_maskGeneration = 0, m_keyGeneration = 0, m_groundMaskGeneration = 0;
    /// A colour target drawn with the G-buffer's depth (the display target, the reflection
    /// source), its framebuffer and the generations it was last attached at.
    struct DepthSharingTarget {
        ColorTarget color;
        unsigned fbo = 0;
        unsigned colorGeneration = 0, gbufferGeneration = 0;
    };
    /// @p t's framebuffer at the G-buffer's size in @p internalFormat, attached again when the
    /// colour target or the G-buffer was remade; 0 + message naming @p what on failure.
    unsigned depthSharingFramebuffer(DepthSharingTarget& t, unsigned internalFormat,
                                     const char* what, std::string* error);
    DepthSharingTarget m_display, m_reflectionSource;
};

} // namespace velvet::render
