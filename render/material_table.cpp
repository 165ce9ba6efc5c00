#include "render/material_table.h"

#include "core/color_management.h"
#include "render/lobe_channels.h"
#include "render/shader_program.h"
#include "render/texture_set.h"

#include <algorithm>
#include <cmath>
#include <epoxy/gl.h>
#include <glm/trigonometric.hpp>
#include <string_view>

namespace velvet::render {

glm::vec3 storedBaseColor(glm::vec3 linear) {
    glm::vec3 stored;
    for (int c = 0; c < 3; ++c) {
        const float encoded = std::clamp(linearToSrgb(std::max(linear[c], 0.0f)), 0.0f, 1.0f);
        stored[c] = srgbToLinear(std::floor(encoded * 255.0f + 0.5f) / 255.0f);
    }
    return stored;
}

GpuMaterial packMaterial(const Material& m) {
    GpuMaterial g{};
    g.baseColorMetallic = glm::vec4(m.color(ParamId::BaseColor), m.scalar(ParamId::Metallic));
    g.storedBaseColor = glm::vec4(storedBaseColor(m.color(ParamId::BaseColor)), 0.0f);
    g.specularColorWeight =
        glm::vec4(m.color(ParamId::SpecularColor), m.scalar(ParamId::SpecularWeight));
    g.roughIorOcclusionNormal =
        glm::vec4(m.scalar(ParamId::Roughness), m.scalar(ParamId::Ior),
                  m.scalar(ParamId::OcclusionStrength), m.scalar(ParamId::NormalScale));
    g.emissive = glm::vec4(m.color(ParamId::EmissiveColor), m.scalar(ParamId::EmissiveStrength));
    // The sheen colour without its weight: the geometry pass multiplies them per pixel (a graph
    // may drive either), the lighting passes when they stay per material.
    g.sheenColorRoughness =
        glm::vec4(m.color(ParamId::SheenColor), m.scalar(ParamId::SheenRoughness));
    g.sheenWeightAnisotropy =
        glm::vec4(m.scalar(ParamId::SheenWeight), m.scalar(ParamId::AnisotropyStrength),
                  glm::radians(m.scalar(ParamId::AnisotropyRotation)), 0.0f);
    g.clearcoat =
        glm::vec4(m.scalar(ParamId::ClearcoatWeight), m.scalar(ParamId::ClearcoatRoughness),
                  m.scalar(ParamId::ClearcoatNormalScale), float(assignLobeChannels(0).iorEntry()));
    g.terms = glm::ivec4(m.choice(ParamId::Distribution), m.choice(ParamId::Visibility),
                         m.choice(ParamId::Fresnel), m.choice(ParamId::Diffuse));
    // No texture yet, every lobe value per material (packMaterialRecord() maps the varying ones).
    g.terms2 = glm::ivec4(m.choice(ParamId::SheenModel), 0, 0, assignLobeChannels(0).packed());
    return g;
}

GpuMaterial packMaterialRecord(const Material& m, const TextureSet& textures,
                               const std::vector<std::string>& graphFields, bool compactGBuffer,
                               std::uint32_t* overflow) {
    GpuMaterial g = packMaterial(m);
    const LobeChannelMap map =
        assignLobeChannels(varyingLobeValues(m, textures.presentSlots(), graphFields),
                           compactGBuffer ? 0 : kLobeChannelCount);
    g.terms2.w = map.packed();
    g.clearcoat.w = float(map.iorEntry());
    g.sheenWeightAnisotropy.w = perturbsNormal(textures.presentSlots(), graphFields) ? 1.0f : 0.0f;
    textures.applyTo(g, map);
    const auto writes = [&](std::string_view field) {
        return std::find(graphFields.begin(), graphFields.end(), field) != graphFields.end();
    };
    if (g.terms2.y == 0 && !writes("baseColor") && !writes("metallic") && !writes("roughness"))
        g.terms2.y = kRecordValuesPerMaterial;
    if (overflow)
        *overflow = compactGBuffer ? 0u : map.overflow;
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
