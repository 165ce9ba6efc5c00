#include "render/background_downsample.h"

#include <algorithm>
#include <epoxy/gl.h>

namespace velvet::render {

int backgroundDownsampleFactor(BackgroundMode mode, bool prefilteredReady, const PostChain* chain,
                               float pixelsPerTexel) {
    // Display steps that are smooth functions of the colour and the pixel's position; grain,
    // static, posterising (toon) and the rest change from one pixel to the next.
    if (chain &&
        !std::all_of(chain->effects.begin(), chain->effects.end(), [](const EffectInstance& e) {
            return !e.enabled || e.type == "tonemap" || e.type == "color_grading" ||
                   e.type == "vignette";
        }))
        return 1;
    if ((mode == BackgroundMode::Blurred && prefilteredReady) || mode == BackgroundMode::SolidColor)
        return 4;
    if (mode == BackgroundMode::Sharp || mode == BackgroundMode::Blurred) // Blurred not yet baked
        return pixelsPerTexel >= 12.0f ? 4 : pixelsPerTexel >= 6.0f ? 2 : 1;
    return 1;
}

bool BackgroundDownsample::build(std::string* error) {
    if (!m_upsample.build("fullscreen.vert", "background_upsample.frag", {}, error))
        return false;
    ++m_compileCount;
    return true;
}

bool BackgroundDownsample::draw(const ShaderProgram& smallProgram, int factor,
                                unsigned displayFramebuffer, int width, int height,
                                std::string* error) {
    const int smallWidth = (width + factor - 1) / factor;
    const int smallHeight = (height + factor - 1) / factor;
    // 8 bits, as the display target: llvmpipe filters unorm8 texels on its fixed-point path, so
    // the upsample costs about half what half floats cost (BENCHMARKS.md, "The inline background's
    // upsample"). The display values are rounded twice then, once here and once after filtering:
    // at most one 255th more than half floats gave.
    if (!m_small.resize(smallWidth, smallHeight, GL_RGBA8, error))
        return false;
    if (m_smallGeneration != m_small.generation()) {
        glTextureParameteri(m_small.texture(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(m_small.texture(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(m_small.texture(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(m_small.texture(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        m_smallGeneration = m_small.generation();
    }
    // Every texel: the background behind the mesh too (the upsample blends across its edge).
    glBindFramebuffer(GL_FRAMEBUFFER, m_small.framebuffer());
    glViewport(0, 0, smallWidth, smallHeight);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(smallProgram.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    // Every pixel, without a depth test: the surfaces' pass draws every pixel of the mesh over it
    // next (as it does over a kept background), so the picture is the same to the bit, and a
    // plain texture-to-target pass is one llvmpipe draws about 1 ms cheaper at 1280x720 than
    // one that tests each pixel's depth against the far plane (the test is still off from the
    // small pass above).
    glBindFramebuffer(GL_FRAMEBUFFER, displayFramebuffer);
    glViewport(0, 0, width, height);
    glBindTextureUnit(binding::kHdrTex, m_small.texture());
    glUseProgram(m_upsample.id());
    glProgramUniform1f(m_upsample.id(), 0, float(factor));
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindTextureUnit(binding::kHdrTex, 0);
    return true;
}

} // namespace velvet::render
