#include "render/ao_pass.h"

#include "render/stage_interface.h"

#include <algorithm>
#include <epoxy/gl.h>

namespace velvet::render {
namespace {

/// @p r grown by @p margin texels each side, clamped to a @p width x @p height target.
PixelRect grown(const PixelRect& r, int margin, int width, int height) {
    if (r.width <= 0 || r.height <= 0)
        return r;
    const int x0 = std::max(r.x - margin, 0), y0 = std::max(r.y - margin, 0);
    const int x1 = std::min(r.x + r.width + margin, width);
    const int y1 = std::min(r.y + r.height + margin, height);
    return {x0, y0, x1 - x0, y1 - y0};
}

/// Draws the bound program's full-screen triangle into @p target over @p rect (texels), the rest
/// of the target cleared to the open value: visibility 1 at the background's depth.
void drawInto(const ColorTarget& target, const PixelRect& rect) {
    const bool whole = rect.x == 0 && rect.y == 0 && rect.width == target.width() &&
                       rect.height == target.height();
    if (!whole) {
        const float open[4] = {1.0f, 1e6f, 0.0f, 0.0f};
        glClearNamedFramebufferfv(target.framebuffer(), GL_COLOR, 0, open);
    }
    if (rect.width <= 0 || rect.height <= 0)
        return;
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer());
    glEnable(GL_SCISSOR_TEST);
    glScissor(rect.x, rect.y, rect.width, rect.height);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_SCISSOR_TEST);
}

} // namespace

PixelRect occlusionRect(const MeshBounds& bounds, float radius, const glm::mat4& viewProj,
                        int width, int height) {
    if (bounds.empty())
        return {};
    MeshBounds reach = bounds;
    reach.min -= glm::vec3(radius);
    reach.max += glm::vec3(radius);
    // The mesh alone (no shadow slot, no ground): the rectangle of the grown box's corners.
    return shadowReceiverRect({}, reach, false, 0.0f, viewProj, width, height);
}

bool OcclusionPass::build(std::string* error) {
    if (!m_gtao[0].build("fullscreen.vert", "ao_gtao.frag", {"WITH_GEOMETRIC_HORIZON 0"}, error) ||
        !m_gtao[1].build("fullscreen.vert", "ao_gtao.frag", {}, error) ||
        !m_blur.build("fullscreen.vert", "ao_blur.frag", {}, error) ||
        !m_pack.build("fullscreen.vert", "ao_pack.frag", {}, error))
        return false;
    m_compileCount += 4;
    return true;
}

bool OcclusionPass::run(int width, int height, int downsample, const PixelRect& texels,
                        bool geometricNormals, FrameKey key, unsigned emptyVao, bool* kept,
                        std::string* error) {
    const int w = maskSize(width, downsample), h = maskSize(height, downsample);
    key.add(w).add(h).add(texels).add(geometricNormals);
    *kept = m_reuse.reuse(std::move(key)) && m_blurred.width() == w && m_blurred.height() == h;
    if (*kept)
        return true;
    if (!m_raw.resize(w, h, GL_RG16F, error) || !m_blurred.resize(w, h, GL_RG16F, error)) {
        m_reuse.invalidate();
        return false;
    }
    // The blurred texels, and the raw ones their 4x4 windows (p - 2 .. p + 1) read.
    const PixelRect& blurRect = texels;
    const PixelRect gtaoRect = grown(blurRect, 2, w, h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glViewport(0, 0, w, h);
    glBindVertexArray(emptyVao);
    glUseProgram(m_gtao[geometricNormals ? 1 : 0].id());
    drawInto(m_raw, gtaoRect);
    glBindTextureUnit(stage_binding::kOcclusionRawTex, m_raw.texture());
    glUseProgram(m_blur.id());
    drawInto(m_blurred, blurRect);
    glBindTextureUnit(stage_binding::kOcclusionRawTex, 0);
    return true;
}

void OcclusionPass::packInto(unsigned maskFramebuffer, const PixelRect& texels, unsigned emptyVao) {
    glBindFramebuffer(GL_FRAMEBUFFER, maskFramebuffer);
    glViewport(0, 0, m_blurred.width(), m_blurred.height());
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    // Alpha alone, of the mask and the ground's mask (not the key between them).
    glColorMaski(0, GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
    glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glColorMaski(2, GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
    const float open[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    glClearBufferfv(GL_COLOR, 0, open); // the clears honour the colour masks
    glClearBufferfv(GL_COLOR, 2, open);
    if (texels.width > 0 && texels.height > 0) {
        bind();
        glBindVertexArray(emptyVao);
        glUseProgram(m_pack.id());
        glEnable(GL_SCISSOR_TEST);
        glScissor(texels.x, texels.y, texels.width, texels.height);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glDisable(GL_SCISSOR_TEST);
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void OcclusionPass::bind() const {
    glBindTextureUnit(stage_binding::kOcclusionTex, m_blurred.texture());
}

} // namespace velvet::render
