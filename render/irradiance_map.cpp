#include "render/irradiance_map.h"

#include <algorithm>
#include <epoxy/gl.h>

namespace velvet::render {

IrradianceMap::~IrradianceMap() {
    if (m_cube)
        glDeleteTextures(1, &m_cube);
}

bool IrradianceMap::build(std::string* error) {
    if (!m_program.build("irradiance_map.comp", {}, {}, error))
        return false;
    ++m_compileCount;
    m_texture = 0;
    return true;
}

void IrradianceMap::update(const GpuEnvironment& environment) {
    // Once a frame: compared, not concatenated.
    if ((environment.texture == m_texture && environment.key == m_key) ||
        environment.texture == 0 || environment.width <= 0)
        return;
    if (!m_cube) {
        glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &m_cube);
        glTextureStorage2D(m_cube, 1, GL_RGBA16F, kFaceSize, kFaceSize);
        glTextureParameteri(m_cube, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(m_cube, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    }
    // The smallest mip at least kSourceWidth wide, integrated texel by texel; a smaller source
    // (a uniform environment's 1 x 1) through a grid of kSourceWidth x kSourceWidth / 2 samples.
    int level = 0;
    while (level + 1 < environment.levels && (environment.width >> (level + 1)) >= kSourceWidth)
        ++level;
    const int gridWidth = std::max(environment.width >> level, kSourceWidth);
    const int gridHeight = std::max(environment.height >> level, kSourceWidth / 2);
    glUseProgram(m_program.id());
    glBindTextureUnit(0, environment.texture);
    glBindImageTexture(0, m_cube, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glProgramUniform1i(m_program.id(), 1, kFaceSize);
    glProgramUniform1i(m_program.id(), 2, level);
    glProgramUniform2i(m_program.id(), 3, gridWidth, gridHeight);
    const GLuint groups = GLuint((kFaceSize + 7) / 8);
    for (int face = 0; face < 6; ++face) {
        glProgramUniform1i(m_program.id(), 0, face);
        glDispatchCompute(groups, groups, 1);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindImageTexture(0, 0, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindTextureUnit(0, 0);
    m_key = environment.key;
    m_texture = environment.texture;
    ++m_integrations;
}

} // namespace velvet::render
