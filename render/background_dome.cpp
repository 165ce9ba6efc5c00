#include "render/background_dome.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <epoxy/gl.h>
#include <vector>

namespace velvet::render {
namespace {

// Facets of 360/64 = 5.6 degrees: the interpolated coordinates stay within 0.003 of a texel of
// the 1024-wide HDRIs' true equirect mapping (background_dome.h).
constexpr int kLongitudes = 64, kLatitudes = 32;

/// The latitude-longitude sphere in the environment's frame (MeshData::position: a direction
/// before the environment's rotation), with the equirect coordinates of common_environment.glsl's
/// equirectUv in MeshData::uv (u = 0.5 at -Z, v = 0 at +Y). The seam's column is doubled (u 0 and
/// 1) and each pole's vertex repeated per column at that column's middle, so that no triangle
/// interpolates across the wrap.
MeshData domeMesh() {
    MeshData mesh;
    const float pi = 3.14159265358979f;
    for (int row = 0; row <= kLatitudes; ++row) {
        const float v = float(row) / float(kLatitudes);
        for (int column = 0; column <= kLongitudes; ++column) {
            const bool pole = row == 0 || row == kLatitudes;
            const float u = (float(column) + (pole ? 0.5f : 0.0f)) / float(kLongitudes);
            const float theta = pi * v, phi = 2.0f * pi * (u - 0.5f);
            Vertex vertex{};
            vertex.position = glm::vec3(std::sin(phi) * std::sin(theta), std::cos(theta),
                                        -std::cos(phi) * std::sin(theta));
            vertex.uv = glm::vec2(u, v);
            mesh.vertices.push_back(vertex);
        }
    }
    std::vector<std::uint32_t>& indices = mesh.indices;
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
    return mesh;
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

bool BackgroundDome::build(std::string* error) {
    if (!m_program.build("background_dome.vert", "background_dome.frag", {}, error))
        return false;
    ++m_compileCount;
    m_cacheValid = false;
    if (m_mesh.empty())
        m_mesh.upload(domeMesh());
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
    m_mesh.draw();
    glBindTextureUnit(binding::kHdrTex, 0);
    return true;
}

} // namespace velvet::render
