#include "render/progressive_accumulation.h"

#include <epoxy/gl.h>

namespace velvet::render {
namespace {

/// The radical inverse of @p i in @p base: the Halton sequence's i-th coordinate in [0, 1).
float radicalInverse(int i, int base) {
    float result = 0.0f;
    float digitWeight = 1.0f / float(base);
    for (; i > 0; i /= base, digitWeight /= float(base))
        result += float(i % base) * digitWeight;
    return result;
}

} // namespace

glm::vec2 progressiveJitter(int index) {
    if (index <= 0)
        return glm::vec2(0.0f);
    return glm::vec2(radicalInverse(index, 2), radicalInverse(index, 3)) - 0.5f;
}

bool ProgressiveAccumulation::build(std::string* error) {
    if (!m_copy.build("fullscreen.vert", "accumulate.frag", {}, error))
        return false;
    ++m_compileCount;
    return true;
}

bool ProgressiveAccumulation::add(const ColorTarget& frame, bool restart, unsigned emptyVao,
                                  std::string* error) {
    const int width = frame.width(), height = frame.height();
    if (width != m_history.width() || height != m_history.height())
        restart = true;
    if (!m_history.resize(width, height, GL_RGBA16F, error))
        return false;
    glBindFramebuffer(GL_FRAMEBUFFER, m_history.framebuffer());
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_SCISSOR_TEST);
    if (restart) {
        m_samples = 0;
        glDisable(GL_BLEND);
    } else {
        // mean' = mean + (frame - mean) / (n + 1): the blend's constant alpha weighs the new frame.
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA);
        glBlendColor(0.0f, 0.0f, 0.0f, 1.0f / float(m_samples + 1));
    }
    glBindTextureUnit(binding::kHdrTex, frame.texture());
    glUseProgram(m_copy.id());
    glBindVertexArray(emptyVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    // The defaults Renderer::render() leaves for the host.
    glBindTextureUnit(binding::kHdrTex, 0);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glBlendColor(0.0f, 0.0f, 0.0f, 0.0f);
    glUseProgram(0);
    glBindVertexArray(0);
    ++m_samples;
    return true;
}

void ProgressiveAccumulation::present(unsigned targetFbo) const {
    // Half floats to the target's format: the blit converts and rounds once. A host (Qt) may
    // leave a scissor or sRGB encoding on, which a blit would honour.
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glBlitNamedFramebuffer(m_history.framebuffer(), targetFbo, 0, 0, m_history.width(),
                           m_history.height(), 0, 0, m_history.width(), m_history.height(),
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);
}

} // namespace velvet::render
