#pragma once
/// @file material_table.h
/// Render-private: the GPU material table (an SSBO indexed by the material id in the G-buffer).
/// A value edit rewrites the table; it never touches a shader.

#include "core/material.h"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <vector>

namespace velvet::render {

/// One material as the shaders read it; generated into GLSL by render/render_interface.cpp (std430,
/// vec4 members only, so C++ and GLSL agree on every offset).
struct GpuMaterial {
    glm::vec4 baseColorMetallic;
    glm::vec4 specularColorWeight;
    glm::vec4 roughIorOcclusionNormal;
    glm::vec4 emissive;
    glm::vec4 sheenColorRoughness;
    glm::vec4 clearcoat;
    glm::ivec4 terms;
    glm::ivec4 terms2;
};
static_assert(sizeof(GpuMaterial) == 128, "GpuMaterial must match the std430 layout");

GpuMaterial packMaterial(const Material& m);

class MaterialTable {
public:
    MaterialTable() = default;
    ~MaterialTable();
    MaterialTable(const MaterialTable&) = delete;
    MaterialTable& operator=(const MaterialTable&) = delete;

    /// Uploads @p materials (id = index); grows the buffer when needed.
    void upload(const std::vector<GpuMaterial>& materials);
    /// Binds the table to BINDING_MATERIAL_SSBO.
    void bind() const;

private:
    unsigned m_buffer = 0;
    size_t m_capacity = 0;
};

} // namespace velvet::render
