#include "render/shadow_mask.h"

#include "render/stage_interface.h"

#include <algorithm>
#include <cmath>
#include <epoxy/gl.h>
#include <glm/common.hpp>
#include <glm/matrix.hpp>

namespace velvet::render {
namespace {

/// Accumulates the screen-space bounds (NDC) of world points; false once one lies behind the
/// camera (its projection is then meaningless).
struct ScreenBounds {
    const glm::mat4& viewProj;
    glm::vec2 lo{1e30f}, hi{-1e30f};
    bool add(const glm::vec3& p) {
        const glm::vec4 clip = viewProj * glm::vec4(p, 1.0f);
        if (clip.w <= 1e-4f)
            return false;
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        lo = glm::min(lo, ndc);
        hi = glm::max(hi, ndc);
        return true;
    }
};

glm::vec3 unproject(const glm::mat4& inverseViewProj, float x, float y, float z) {
    const glm::vec4 p = inverseViewProj * glm::vec4(x, y, z, 1.0f);
    return glm::vec3(p) / p.w;
}

} // namespace

PixelRect shadowReceiverRect(const ShadowSlot& slot, const MeshBounds& bounds, bool ground,
                             float groundHeight, const glm::mat4& viewProj, int width, int height) {
    const PixelRect full{0, 0, width, height};
    if (bounds.empty())
        return full;
    ScreenBounds screen{viewProj};
    for (int i = 0; i < 8; ++i)
        if (!screen.add({(i & 1) ? bounds.max.x : bounds.min.x,
                         (i & 2) ? bounds.max.y : bounds.min.y,
                         (i & 4) ? bounds.max.z : bounds.min.z}))
            return full;
    if (ground) {
        // The map's four edges, each the line through a corner of its near and of its far plane:
        // for an orthographic map the edges of its prism (both ways: conservative), for a
        // perspective one rays from the light's centre. Where they meet the ground bounds the
        // part of the ground inside the map (a convex quadrilateral) when they all go down to it.
        const glm::mat4 toWorld = glm::inverse(slot.proj * slot.view);
        const glm::vec3 apex = glm::vec3(glm::inverse(slot.view)[3]);
        if (slot.perspective && apex.y <= groundHeight)
            return full;
        for (int k = 0; k < 4; ++k) {
            const float x = (k & 1) ? 1.0f : -1.0f, y = (k & 2) ? 1.0f : -1.0f;
            const glm::vec3 nearCorner = unproject(toWorld, x, y, -1.0f);
            const glm::vec3 farCorner = unproject(toWorld, x, y, 1.0f);
            const glm::vec3 origin = slot.perspective ? apex : nearCorner;
            const glm::vec3 dir = farCorner - nearCorner;
            // Down towards the ground, or the light does not light it from above: the lookup
            // there is not 1 (or the part is unbounded).
            if (!(dir.y < -1e-3f * glm::length(dir)))
                return full;
            const float t = (groundHeight - origin.y) / dir.y;
            if (!screen.add(origin + t * dir))
                return full;
        }
    }
    // To pixels, one pixel of margin each side (a receiver's pixel centre lies inside), clamped.
    const auto px = [](float ndc, int size) { return (ndc * 0.5f + 0.5f) * float(size); };
    const float big = 1e6f; // keeps the float-to-int conversion defined for far-off points
    const int x0 =
        std::clamp(int(std::floor(std::clamp(px(screen.lo.x, width), -big, big))) - 1, 0, width);
    const int y0 =
        std::clamp(int(std::floor(std::clamp(px(screen.lo.y, height), -big, big))) - 1, 0, height);
    const int x1 =
        std::clamp(int(std::ceil(std::clamp(px(screen.hi.x, width), -big, big))) + 1, 0, width);
    const int y1 =
        std::clamp(int(std::ceil(std::clamp(px(screen.hi.y, height), -big, big))) + 1, 0, height);
    return {x0, y0, std::max(x1 - x0, 0), std::max(y1 - y0, 0)};
}

PixelRect maskRect(const PixelRect& frameRect, int maskWidth, int maskHeight) {
    // Texel t stands for pixel 2t, and a pixel of the rectangle blends the texels either side of
    // it (shadow_mask.glsl): from the texel at or below its first pixel to the one above its last.
    if (frameRect.width <= 0 || frameRect.height <= 0)
        return {};
    const int x0 = std::clamp(frameRect.x / 2, 0, maskWidth);
    const int y0 = std::clamp(frameRect.y / 2, 0, maskHeight);
    const int x1 = std::clamp((frameRect.x + frameRect.width - 1) / 2 + 2, 0, maskWidth);
    const int y1 = std::clamp((frameRect.y + frameRect.height - 1) / 2 + 2, 0, maskHeight);
    return {x0, y0, std::max(x1 - x0, 0), std::max(y1 - y0, 0)};
}

bool ShadowMaskPass::build(std::string* error) {
    if (!m_program.build("fullscreen.vert", "shadow_mask.frag", {}, error))
        return false;
    ++m_compileCount;
    return true;
}

int ShadowMaskPass::run(unsigned framebuffer, const std::vector<ShadowSlot>& slots,
                        const MeshBounds& bounds, bool ground, float groundHeight,
                        const glm::mat4& viewProj, int width, int height, unsigned emptyVao) {
    // The mask is at half the frame's size: texel t looks up pixel 2t (shadow_mask.frag).
    const int maskWidth = (width + 1) / 2, maskHeight = (height + 1) / 2;
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, maskWidth, maskHeight);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    const float lit[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    glClearBufferfv(GL_COLOR, 0, lit);
    // A texel no slot draws keeps a key no pixel matches (depth 0, no material): the upsample
    // never weighs it, but then its mask value is 1 anyway.
    const float noKey[4] = {0.0f, -1.0f, 0.0f, 0.0f};
    glClearBufferfv(GL_COLOR, 1, noKey);
    glEnable(GL_SCISSOR_TEST);
    glUseProgram(m_program.id());
    glBindVertexArray(emptyVao);
    int drawn = 0;
    const int count = std::min(int(slots.size()), kMaxShadowLights);
    for (int s = 0; s < count; ++s) {
        const PixelRect r = maskRect(shadowReceiverRect(slots[size_t(s)], bounds, ground,
                                                        groundHeight, viewProj, width, height),
                                     maskWidth, maskHeight);
        if (r.width <= 0 || r.height <= 0)
            continue;
        glScissor(r.x, r.y, r.width, r.height);
        glColorMaski(0, s == 0, s == 1, s == 2, s == 3);       // slot s writes channel s alone
        glColorMaski(1, GL_TRUE, GL_TRUE, GL_FALSE, GL_FALSE); // every slot writes the key
        glProgramUniform1i(m_program.id(), 0, s);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        ++drawn;
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_SCISSOR_TEST);
    return drawn;
}

} // namespace velvet::render
