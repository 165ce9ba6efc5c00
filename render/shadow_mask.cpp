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

PixelRect intersection(const PixelRect& a, const PixelRect& b) {
    const int x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
    const int x1 = std::min(a.x + a.width, b.x + b.width);
    const int y1 = std::min(a.y + a.height, b.y + b.height);
    return {x0, y0, std::max(x1 - x0, 0), std::max(y1 - y0, 0)};
}

PixelRect maskRect(const PixelRect& frameRect, int maskWidth, int maskHeight, int downsample) {
    // Texel t stands for pixel D t, and a pixel of the rectangle blends the texels either side of
    // it (shadow_mask.glsl): from the texel at or below its first pixel to the one above its last.
    if (frameRect.width <= 0 || frameRect.height <= 0)
        return {};
    const int d = std::max(downsample, 1);
    const int x0 = std::clamp(frameRect.x / d, 0, maskWidth);
    const int y0 = std::clamp(frameRect.y / d, 0, maskHeight);
    const int x1 = std::clamp((frameRect.x + frameRect.width - 1) / d + 2, 0, maskWidth);
    const int y1 = std::clamp((frameRect.y + frameRect.height - 1) / d + 2, 0, maskHeight);
    return {x0, y0, std::max(x1 - x0, 0), std::max(y1 - y0, 0)};
}

bool ShadowMaskPass::build(std::string* error) {
    const std::vector<std::string> defines[kPassCount] = {
        {"SHADOW_MASK_GROUND", "SHADOW_MASK_SETTLE"},
        {"SHADOW_MASK_GROUND"},
        {"SHADOW_MASK_SETTLE", "WITH_GEOMETRIC_HORIZON 0"},
        {"WITH_GEOMETRIC_HORIZON 0"},
        {"SHADOW_MASK_SETTLE"},
        {}};
    for (int p = 0; p < kPassCount; ++p)
        if (!m_programs[p].build("fullscreen.vert", "shadow_mask.frag", defines[p], error))
            return false;
    m_compileCount += kPassCount;
    return true;
}

ShadowMaskPass::~ShadowMaskPass() {
    if (m_queries[0])
        glDeleteQueries(kMaxQueries, m_queries);
}

void ShadowMaskPass::draw(Pass pass, int slot, bool settle) {
    const unsigned program = m_programs[pass].id();
    // A settle pass writes every texel's depth (0 settled, 1 left for the lookup; without
    // settling, 1 wherever there is a receiver); its lookup pass, drawn at depth 0.5, shades
    // only where the test LESS passes. llvmpipe tests depth before shading, so blocks of settled
    // texels skip the lookup.
    const bool settlePass = pass == kGroundSettle || pass == kMeshSettle || pass == kMeshSettleBent;
    glDepthFunc(settlePass ? GL_ALWAYS : GL_LESS);
    glUseProgram(program);
    glProgramUniform1i(program, 0, slot);
    glProgramUniform1i(program, 1, settle ? 1 : 0);
    const bool counted = !settlePass && m_queriesUsed < kMaxQueries;
    if (counted)
        glBeginQuery(GL_SAMPLES_PASSED, m_queries[m_queriesUsed]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    if (counted) {
        glEndQuery(GL_SAMPLES_PASSED);
        ++m_queriesUsed;
    }
}

void ShadowMaskPass::lastTexels(long long* texels, long long* filtered) const {
    *texels = m_texels;
    *filtered = 0;
    for (int i = 0; i < m_queriesUsed; ++i) {
        GLuint64 n = 0;
        glGetQueryObjectui64v(m_queries[i], GL_QUERY_RESULT, &n);
        *filtered += (long long)n;
    }
}

int ShadowMaskPass::run(unsigned framebuffer, const std::vector<ShadowSlot>& slots,
                        const MeshBounds& bounds, bool ground, float groundHeight,
                        const glm::mat4& viewProj, int width, int height, int downsample,
                        unsigned emptyVao, bool settle, bool bentNormals) {
    if (!m_queries[0])
        glCreateQueries(GL_SAMPLES_PASSED, kMaxQueries, m_queries);
    m_queriesUsed = 0;
    m_texels = 0;
    // Texel t looks up pixel D t (shadow_mask.frag), D the downsample.
    const int maskWidth = maskSize(width, downsample), maskHeight = maskSize(height, downsample);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, maskWidth, maskHeight);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    const float lit[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    glClearBufferfv(GL_COLOR, 0, lit);
    glClearBufferfv(GL_COLOR, 2, lit);
    // A texel no slot draws keeps a key no pixel matches (depth 0, no material): the upsample
    // never weighs it, but then its mask value is 1 anyway.
    const float noKey[4] = {0.0f, -1.0f, 0.0f, 0.0f};
    glClearBufferfv(GL_COLOR, 1, noKey);
    glEnable(GL_SCISSOR_TEST);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glBindVertexArray(emptyVao);
    // Where the mesh's own texels can be: its bounds on screen.
    const PixelRect meshRect =
        maskRect(shadowReceiverRect({}, bounds, false, 0.0f, viewProj, width, height), maskWidth,
                 maskHeight, downsample);
    int drawn = 0;
    const int count = std::min(int(slots.size()), kMaxShadowLights);
    for (int s = 0; s < count; ++s) {
        const PixelRect r = maskRect(shadowReceiverRect(slots[size_t(s)], bounds, ground,
                                                        groundHeight, viewProj, width, height),
                                     maskWidth, maskHeight, downsample);
        if (r.width <= 0 || r.height <= 0)
            continue;
        glScissor(r.x, r.y, r.width, r.height);
        const GLboolean c[4] = {s == 0, s == 1, s == 2, s == 3}; // slot s: channel s alone
        glColorMaski(0, c[0], c[1], c[2], c[3]);
        if (ground) {
            // The ground where each texel's view ray meets it, into the ground's mask and (the
            // mesh's texels overwritten below) the mask; the settle pass writes every key.
            glColorMaski(1, GL_TRUE, GL_TRUE, GL_FALSE, GL_FALSE);
            glColorMaski(2, c[0], c[1], c[2], c[3]);
            draw(kGroundSettle, s, settle);
            m_texels += (long long)r.width * r.height;
            glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            draw(kGroundLookup, s, settle);
        }
        // The mesh's own texels: its settle pass discards the others (the background's keep the
        // clear values, which are what they would write), so they keep depth 0, settled.
        const PixelRect m = intersection(r, meshRect);
        ++drawn;
        if (m.width <= 0 || m.height <= 0)
            continue;
        glScissor(m.x, m.y, m.width, m.height);
        const float settled = 0.0f;
        glClearBufferfv(GL_DEPTH, 0, &settled);
        const GLboolean key = ground ? GL_FALSE : GL_TRUE; // else the ground's pass wrote it
        glColorMaski(1, key, key, GL_FALSE, GL_FALSE);
        glColorMaski(2, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        draw(bentNormals ? kMeshSettleBent : kMeshSettle, s, settle);
        if (!ground)
            m_texels += (long long)m.width * m.height;
        glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        draw(bentNormals ? kMeshLookupBent : kMeshLookup, s, settle);
    }
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_SCISSOR_TEST);
    return drawn;
}

} // namespace velvet::render
