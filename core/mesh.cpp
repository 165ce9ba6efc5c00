#include "core/mesh.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <numbers>

namespace velvet {

MeshData makeSphere(float radius, int segments, int rings) {
    segments = std::max(segments, 3);
    rings = std::max(rings, 2);
    MeshData mesh;
    mesh.vertices.reserve(size_t(segments + 1) * (rings + 1));
    const float pi = std::numbers::pi_v<float>;

    // theta: polar angle from +Y (v = theta / pi, v = 0 at the top as in glTF's UV space);
    // phi: azimuth, u = 0.5 faces +Z, chosen so that u grows to the right
    // when the sphere is seen from +Z (texture not mirrored).
    for (int i = 0; i <= rings; ++i) {
        const float v = float(i) / float(rings);
        const float theta = v * pi;
        const float st = std::sin(theta), ct = std::cos(theta);
        for (int j = 0; j <= segments; ++j) {
            const float u = float(j) / float(segments);
            const float phi = (u - 0.5f) * 2.0f * pi;
            const float sp = std::sin(phi), cp = std::cos(phi);
            Vertex vert;
            vert.normal = glm::vec3(st * sp, ct, st * cp);
            vert.position = radius * vert.normal;
            // d(position)/du, without the sin(theta) factor so it stays defined at the poles.
            // Bitangent cross(n, t) points to the north pole = decreasing v = "up" in the
            // texture, the glTF / MikkTSpace convention for OpenGL-style normal maps: w = +1.
            vert.tangent = glm::vec4(cp, 0.0f, -sp, 1.0f);
            vert.uv = glm::vec2(u, v);
            mesh.vertices.push_back(vert);
        }
    }
    const auto index = [&](int i, int j) { return std::uint32_t(i * (segments + 1) + j); };
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            // a top-left, b bottom-left, c bottom-right, d top-right as seen from outside:
            // (a, b, c) and (a, c, d) are counter-clockwise. Skip the degenerate pole triangles.
            const std::uint32_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1),
                                d = index(i, j + 1);
            if (i != rings - 1)
                mesh.indices.insert(mesh.indices.end(), {a, b, c});
            if (i != 0)
                mesh.indices.insert(mesh.indices.end(), {a, c, d});
        }
    }
    return mesh;
}

} // namespace velvet

namespace velvet {

MeshBounds meshBounds(const MeshData& mesh) {
    MeshBounds b;
    for (const Vertex& v : mesh.vertices) {
        b.min = glm::min(b.min, v.position);
        b.max = glm::max(b.max, v.position);
    }
    return b;
}

void fitToUnitBox(MeshData& mesh, float halfExtent) {
    const MeshBounds b = meshBounds(mesh);
    if (b.empty())
        return;
    const glm::vec3 size = b.size();
    const float largest = std::max({size.x, size.y, size.z});
    if (!(largest > 0.0f) || !std::isfinite(largest))
        return;
    const glm::vec3 center = b.center();
    const float scale = 2.0f * halfExtent / largest;
    for (Vertex& v : mesh.vertices)
        v.position = (v.position - center) * scale;
}

} // namespace velvet
