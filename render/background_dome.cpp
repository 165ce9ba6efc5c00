#include "render/background_dome.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <epoxy/gl.h>
#include <glm/vec3.hpp>
#include <vector>

namespace velvet::render {
namespace {

// Facets of 360/64 = 5.6 degrees: the interpolated coordinates stay within 0.003 of a texel of
// the 1024-wide HDRIs' true equirect mapping (background_dome.h).
constexpr int kLongitudes = 64, kLatitudes = 32;

struct DomeVertex {
    glm::vec3 environmentDirection; ///< in the environment's frame (before its rotation)
    float u, v;                     ///< the equirect coordinates of that direction
};

/// The latitude-longitude sphere in the environment's frame, with the equirect coordinates of
/// common_environment.glsl's equirectUv (u = 0.5 at -Z, v = 0 at +Y). The seam's column is
/// doubled (u 0 and 1) and each pole's vertex repeated per column at that column's middle, so
/// that no triangle interpolates across the wrap.
void domeMesh(std::vector<DomeVertex>& vertices, std::vector<unsigned>& indices) {
    const float pi = 3.14159265358979f;
    for (int row = 0; row <= kLatitudes; ++row) {
        const float v = float(row) / float(kLatitudes);
        for (int column = 0; column <= kLongitudes; ++column) {
            const bool pole = row == 0 || row == kLatitudes;
            const float u = (float(column) + (pole ? 0.5f : 0.0f)) / float(kLongitudes);
            const float theta = pi * v, phi = 2.0f * pi * (u - 0.5f);
            vertices.push_back({glm::vec3(std::sin(phi) * std::sin(theta), std::cos(theta),
                                          -std::cos(phi) * std::sin(theta)),
                                u, v});
        }
    }
    const unsigned stride = kLongitudes + 1;
    for (unsigned row = 0; row < unsigned(kLatitudes); ++row)
        for (unsigned column = 0; column < unsigned(kLongitudes); ++column) {
            const unsigned a = row * stride + column, b = a + 1, c = a + stride, d = c + 1;
            // The poles' rows are triangles: a (the top's pole at this column's middle) with c
            // and d; a and b with c (the bottom's pole).
            if (row == 0)
                indices.insert(indices.end(), {a, c, d});
            else if (row == unsigned(kLatitudes) - 1)
                indices.insert(indices.end(), {a, c, b});
            else
                indices.insert(indices.end(), {a, c, b, b, c, d});
        }
}

} // namespace

bool backgroundDomeApplies(BackgroundMode mode, const PostChain* chain) {
    if (mode != BackgroundMode::Sharp && mode != BackgroundMode::Blurred)
        return false;
    // The vignette is smooth but reads the pixel's position, grain and the rest also vary by it.
    return !chain ||
           std::all_of(chain->effects.begin(), chain->effects.end(), [](const EffectInstance& e) {
               return !e.enabled || e.type == "tonemap" || e.type == "color_grading";
           });
}

BackgroundDome::~BackgroundDome() {
    if (m_vao)
        glDeleteVertexArrays(1, &m_vao);
    if (m_vbo)
        glDeleteBuffers(1, &m_vbo);
    if (m_ibo)
        glDeleteBuffers(1, &m_ibo);
}

bool BackgroundDome::build(std::string* error) {
    if (!m_program.build("background_dome.vert", "background_dome.frag", {}, error))
        return false;
    ++m_compileCount;
    m_cacheValid = false;
    if (m_vao)
        return true;
    std::vector<DomeVertex> vertices;
    std::vector<unsigned> indices;
    domeMesh(vertices, indices);
    glCreateBuffers(1, &m_vbo);
    glNamedBufferStorage(m_vbo, GLsizeiptr(vertices.size() * sizeof(DomeVertex)), vertices.data(),
                         0);
    glCreateBuffers(1, &m_ibo);
    glNamedBufferStorage(m_ibo, GLsizeiptr(indices.size() * sizeof(unsigned)), indices.data(), 0);
    glCreateVertexArrays(1, &m_vao);
    glVertexArrayVertexBuffer(m_vao, 0, m_vbo, 0, sizeof(DomeVertex));
    glVertexArrayElementBuffer(m_vao, m_ibo);
    glEnableVertexArrayAttrib(m_vao, 0);
    glVertexArrayAttribFormat(m_vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(m_vao, 0, 0);
    glEnableVertexArrayAttrib(m_vao, 1);
    glVertexArrayAttribFormat(m_vao, 1, 2, GL_FLOAT, GL_FALSE, GLuint(offsetof(DomeVertex, u)));
    glVertexArrayAttribBinding(m_vao, 1, 0);
    m_indexCount = int(indices.size());
    return true;
}

bool BackgroundDome::draw(const ShaderProgram& cacheProgram, int cacheWidth, int cacheHeight,
                          const FrameKey& key, unsigned displayFramebuffer, int width, int height,
                          bool* cacheDrawn, std::string* error) {
    *cacheDrawn = false;
    glDisable(GL_DEPTH_TEST);
    if (!m_cacheValid || !(key == m_cacheKey) || m_cache.width() != cacheWidth ||
        m_cache.height() != cacheHeight) {
        // 8 bits, as the display target and the smaller background's target (llvmpipe filters
        // unorm8 on its fixed-point path).
        if (!m_cache.resize(cacheWidth, cacheHeight, GL_RGBA8, error))
            return false;
        if (m_cacheGeneration != m_cache.generation()) {
            glTextureParameteri(m_cache.texture(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            glTextureParameteri(m_cache.texture(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            glTextureParameteri(m_cache.texture(), GL_TEXTURE_WRAP_S, GL_REPEAT); // the seam
            glTextureParameteri(m_cache.texture(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
            m_cacheGeneration = m_cache.generation();
        }
        glBindFramebuffer(GL_FRAMEBUFFER, m_cache.framebuffer());
        glViewport(0, 0, cacheWidth, cacheHeight);
        glUseProgram(cacheProgram.id());
        glDrawArrays(GL_TRIANGLES, 0, 3); // the caller's empty VAO is bound
        m_cacheKey = key;
        m_cacheValid = true;
        *cacheDrawn = true;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, displayFramebuffer);
    glViewport(0, 0, width, height);
    glBindTextureUnit(binding::kHdrTex, m_cache.texture());
    glUseProgram(m_program.id());
    GLint vao = 0;
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
    glBindVertexArray(m_vao);
    glDrawElements(GL_TRIANGLES, m_indexCount, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(GLuint(vao));
    glBindTextureUnit(binding::kHdrTex, 0);
    return true;
}

} // namespace velvet::render
