#include "render/material_table.h"

#include "render/shader_program.h"

#include <epoxy/gl.h>

namespace velvet::render {

GpuMaterial packMaterial(const Material& m) {
    GpuMaterial g{};
    g.baseColorMetallic = glm::vec4(m.color(ParamId::BaseColor), m.scalar(ParamId::Metallic));
    g.specularColorWeight =
        glm::vec4(m.color(ParamId::SpecularColor), m.scalar(ParamId::SpecularWeight));
    g.roughIorOcclusionNormal =
        glm::vec4(m.scalar(ParamId::Roughness), m.scalar(ParamId::Ior),
                  m.scalar(ParamId::OcclusionStrength), m.scalar(ParamId::NormalScale));
    g.emissive = glm::vec4(m.color(ParamId::EmissiveColor), m.scalar(ParamId::EmissiveStrength));
    g.sheenColorRoughness = glm::vec4(m.scalar(ParamId::SheenWeight) * m.color(ParamId::SheenColor),
                                      m.scalar(ParamId::SheenRoughness));
    g.clearcoat =
        glm::vec4(m.scalar(ParamId::ClearcoatWeight), m.scalar(ParamId::ClearcoatRoughness),
                  m.scalar(ParamId::ClearcoatNormalScale), 0.0f);
    g.terms = glm::ivec4(m.choice(ParamId::Distribution), m.choice(ParamId::Visibility),
                         m.choice(ParamId::Fresnel), m.choice(ParamId::Diffuse));
    g.terms2 = glm::ivec4(m.choice(ParamId::SheenModel), 0, 0, 0);
    return g;
}

MaterialTable::~MaterialTable() {
    if (m_buffer)
        glDeleteBuffers(1, &m_buffer);
}

void MaterialTable::upload(const std::vector<GpuMaterial>& materials) {
    const size_t bytes = std::max<size_t>(materials.size(), 1) * sizeof(GpuMaterial);
    if (!m_buffer || bytes > m_capacity) {
        if (m_buffer)
            glDeleteBuffers(1, &m_buffer);
        glCreateBuffers(1, &m_buffer);
        glNamedBufferStorage(m_buffer, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
        m_capacity = bytes;
    }
    if (!materials.empty())
        glNamedBufferSubData(m_buffer, 0, GLsizeiptr(materials.size() * sizeof(GpuMaterial)),
                             materials.data());
}

void MaterialTable::bind() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::kMaterialSsbo, m_buffer);
}

} // namespace velvet::render
