#include "render/ao_pass.h"

#include "render/stage_interface.h"

#include <epoxy/gl.h>

namespace velvet::render {

bool OcclusionPass::build(std::string* error) {
    if (!m_gtao.build("fullscreen.vert", "ao_gtao.frag", {}, error) ||
        !m_blur.build("fullscreen.vert", "ao_blur.frag", {}, error))
        return false;
    m_compileCount += 2;
    return true;
}

bool OcclusionPass::run(int width, int height, unsigned emptyVao, std::string* error) {
    const int w = halfSize(width), h = halfSize(height);
    if (!m_raw.resize(w, h, GL_RG16F, error) || !m_blurred.resize(w, h, GL_RG16F, error))
        return false;
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glViewport(0, 0, w, h);
    glBindVertexArray(emptyVao);
    glBindFramebuffer(GL_FRAMEBUFFER, m_raw.framebuffer());
    glUseProgram(m_gtao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_FRAMEBUFFER, m_blurred.framebuffer());
    glBindTextureUnit(stage_binding::kOcclusionRawTex, m_raw.texture());
    glUseProgram(m_blur.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindTextureUnit(stage_binding::kOcclusionRawTex, 0);
    return true;
}

void OcclusionPass::bind() const {
    glBindTextureUnit(stage_binding::kOcclusionTex, m_blurred.texture());
}

} // namespace velvet::render
