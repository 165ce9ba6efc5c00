#include "render/gpu_mesh.h"

#include <cstddef>
#include <epoxy/gl.h>

namespace velvet::render {

GpuMesh::~GpuMesh() {
    release();
}

void GpuMesh::release() {
    if (m_vao)
        glDeleteVertexArrays(1, &m_vao);
    if (m_vbo)
        glDeleteBuffers(1, &m_vbo);
    if (m_ibo)
        glDeleteBuffers(1, &m_ibo);
    if (m_visibilityVbo)
        glDeleteBuffers(1, &m_visibilityVbo);
    m_vao = m_vbo = m_ibo = m_visibilityVbo = 0;
    m_indexCount = 0;
}

void GpuMesh::upload(const MeshData& mesh) {
    release();
    glCreateBuffers(1, &m_vbo);
    glNamedBufferStorage(m_vbo, GLsizeiptr(mesh.vertices.size() * sizeof(Vertex)),
                         mesh.vertices.data(), 0);
    glCreateBuffers(1, &m_ibo);
    glNamedBufferStorage(m_ibo, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                         mesh.indices.data(), 0);
    glCreateVertexArrays(1, &m_vao);
    glVertexArrayVertexBuffer(m_vao, 0, m_vbo, 0, sizeof(Vertex));
    glVertexArrayElementBuffer(m_vao, m_ibo);
    const struct {
        GLuint location;
        GLint size;
        size_t offset;
    } attributes[] = {{0, 3, offsetof(Vertex, position)},
                      {1, 3, offsetof(Vertex, normal)},
                      {2, 4, offsetof(Vertex, tangent)},
                      {3, 2, offsetof(Vertex, uv)}};
    for (const auto& a : attributes) {
        glEnableVertexArrayAttrib(m_vao, a.location);
        glVertexArrayAttribFormat(m_vao, a.location, a.size, GL_FLOAT, GL_FALSE, GLuint(a.offset));
        glVertexArrayAttribBinding(m_vao, a.location, 0);
    }
    m_vertexCount = mesh.vertices.size();
    uploadVisibility(mesh.visibility);
    m_indexCount = int(mesh.indices.size());
}

void GpuMesh::uploadVisibility(const std::vector<glm::vec4>& visibility) {
    // The mesh's visibility from itself from a second buffer; without it the attribute stays
    // disabled and draw() sets its generic value.
    if (!m_vao || visibility.empty() || visibility.size() != m_vertexCount)
        return;
    if (m_visibilityVbo)
        glDeleteBuffers(1, &m_visibilityVbo);
    glCreateBuffers(1, &m_visibilityVbo);
    glNamedBufferStorage(m_visibilityVbo, GLsizeiptr(visibility.size() * sizeof(glm::vec4)),
                         visibility.data(), 0);
    glVertexArrayVertexBuffer(m_vao, 1, m_visibilityVbo, 0, sizeof(glm::vec4));
    glEnableVertexArrayAttrib(m_vao, kVisibilityLocation);
    glVertexArrayAttribFormat(m_vao, kVisibilityLocation, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(m_vao, kVisibilityLocation, 1);
}

void GpuMesh::draw() const {
    glBindVertexArray(m_vao);
    // A disabled attribute reads the context's current generic value, which is not part of the
    // vertex array and which others (Qt's paint engine in the editor) leave as they please: set
    // it to (0, 0, 0, 1), no bent normal and nothing hidden, for a mesh without visibility.
    if (!m_visibilityVbo)
        glVertexAttrib4f(kVisibilityLocation, 0.0f, 0.0f, 0.0f, 1.0f);
    glDrawElements(GL_TRIANGLES, m_indexCount, GL_UNSIGNED_INT, nullptr);
}

} // namespace velvet::render
