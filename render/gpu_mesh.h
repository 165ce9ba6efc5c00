#pragma once
/// @file gpu_mesh.h
/// Render-private: a MeshData in GL buffers with its vertex array.

#include "core/mesh.h"

namespace velvet::render {

class GpuMesh {
public:
    GpuMesh() = default;
    ~GpuMesh();
    GpuMesh(const GpuMesh&) = delete;
    GpuMesh& operator=(const GpuMesh&) = delete;

    /// gbuffer.vert's location of MeshData::visibility.
    static constexpr unsigned kVisibilityLocation = 4;

    void upload(const MeshData& mesh);
    /// Adds the mesh's visibility from itself (one per vertex; MeshData::visibility) to an
    /// uploaded mesh, replacing any; an empty or mis-sized one is ignored.
    void uploadVisibility(const std::vector<glm::vec4>& visibility);
    void draw() const;
    bool empty() const { return m_indexCount == 0; }
    /// Whether the mesh was uploaded with its visibility from itself (MeshData::visibility).
    bool hasVisibility() const { return m_visibilityVbo != 0; }

private:
    void release();
    unsigned m_vao = 0, m_vbo = 0, m_ibo = 0, m_visibilityVbo = 0;
    int m_indexCount = 0;
    size_t m_vertexCount = 0;
};

} // namespace velvet::render
