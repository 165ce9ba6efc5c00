#include "core/mesh_tangents.h"

#include <cmath>
#include <glm/geometric.hpp>

namespace velvet {

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited".
glm::vec3 anyOrthogonal(glm::vec3 n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
}

void generateNormals(MeshData& mesh) {
    std::vector<glm::vec3> sum(mesh.vertices.size(), glm::vec3(0.0f));
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const std::uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
        const glm::vec3 n = glm::cross(mesh.vertices[b].position - mesh.vertices[a].position,
                                       mesh.vertices[c].position - mesh.vertices[a].position);
        sum[a] += n;
        sum[b] += n;
        sum[c] += n;
    }
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
        const float len = glm::length(sum[v]);
        mesh.vertices[v].normal = len > 0.0f ? sum[v] / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

void generateTangents(MeshData& mesh) {
    std::vector<glm::vec3> tan(mesh.vertices.size(), glm::vec3(0.0f));
    std::vector<glm::vec3> bitan(mesh.vertices.size(), glm::vec3(0.0f));
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const std::uint32_t idx[3] = {mesh.indices[i], mesh.indices[i + 1], mesh.indices[i + 2]};
        const Vertex& v0 = mesh.vertices[idx[0]];
        const Vertex& v1 = mesh.vertices[idx[1]];
        const Vertex& v2 = mesh.vertices[idx[2]];
        const glm::vec3 e1 = v1.position - v0.position, e2 = v2.position - v0.position;
        const glm::vec2 d1 = v1.uv - v0.uv, d2 = v2.uv - v0.uv;
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (std::abs(det) < 1e-20f || !std::isfinite(det))
            continue;
        // Lengyel's system [e1 e2] = [T B] [d1 d2]: T = dP/du, B = dP/dv. Unnormalised sums
        // weight each triangle by its area in position space over its area in UV space; that is
        // Lengyel's weighting too.
        const float r = 1.0f / det;
        const glm::vec3 t = (e1 * d2.y - e2 * d1.y) * r;
        const glm::vec3 b = (e2 * d1.x - e1 * d2.x) * r;
        for (std::uint32_t k : idx) {
            tan[k] += t;
            bitan[k] += b;
        }
    }
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
        Vertex& vert = mesh.vertices[v];
        const glm::vec3 n = vert.normal;
        glm::vec3 t = tan[v] - n * glm::dot(n, tan[v]); // Gram-Schmidt
        const float len = glm::length(t);
        t = len > 1e-12f && std::isfinite(len) ? t / len : anyOrthogonal(n);
        // B = dP/dv points to increasing v, i.e. down the image in glTF's UV space; the glTF
        // bitangent cross(n, t) * w points up the image, so w is minus the sign of their dot.
        const float w = glm::dot(glm::cross(n, t), bitan[v]) > 0.0f ? -1.0f : 1.0f;
        vert.tangent = glm::vec4(t, w);
    }
}

} // namespace velvet
