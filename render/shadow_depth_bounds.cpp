#include "render/shadow_depth_bounds.h"

#include <algorithm>
#include <epoxy/gl.h>
#include <string>

namespace velvet::render {

ShadowDepthBounds::~ShadowDepthBounds() {
    if (m_texture)
        glDeleteTextures(1, &m_texture);
}

bool ShadowDepthBounds::build(std::string* error) {
    if (!m_program.build("shadow_depth_bounds.comp",
                         {"BOUNDS_BLOCK " + std::to_string(kShadowBoundsBlock)}, {}, error))
        return false;
    ++m_compileCount;
    return true;
}

void ShadowDepthBounds::allocate(int layers, int size) {
    if (layers == m_layers && size == m_size)
        return;
    if (m_texture)
        glDeleteTextures(1, &m_texture);
    m_levels = shadowBoundsLevels(size);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &m_texture);
    glTextureStorage3D(m_texture, m_levels, GL_RG32F, size, size, layers);
    glTextureParameteri(m_texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glTextureParameteri(m_texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    m_layers = layers;
    m_size = size;
}

void ShadowDepthBounds::update(unsigned depthArray, int layers, int size) {
    const int base = std::max(size / kShadowBoundsBlock, 1);
    allocate(layers, base);
    if (!m_program.id())
        return;
    const unsigned program = m_program.id();
    glUseProgram(program);
    // The depth maps through their own parameters (no comparison: ShadowMaps compares through
    // a sampler object), read by texelFetch.
    glBindTextureUnit(0, depthArray);
    glBindSampler(0, 0);
    for (int level = 0; level < m_levels; ++level) {
        const int levelSize = std::max(base >> level, 1);
        if (level > 0)
            glBindImageTexture(0, m_texture, level - 1, GL_TRUE, 0, GL_READ_ONLY, GL_RG32F);
        glBindImageTexture(1, m_texture, level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RG32F);
        glProgramUniform1i(program, 0, level);
        glProgramUniform1i(program, 2, levelSize);
        for (int layer = 0; layer < layers; ++layer) {
            glProgramUniform1i(program, 1, layer);
            glDispatchCompute(GLuint((levelSize + 7) / 8), GLuint((levelSize + 7) / 8), 1);
        }
        // The next level reads this one through image loads; the lookups through textures.
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RG32F);
    glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
    glBindTextureUnit(0, 0);
}

} // namespace velvet::render
