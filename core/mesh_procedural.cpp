// Procedural preview meshes other than the sphere (core/mesh.cpp): cube, rounded cube, plane,
// cloth drape, shader ball. Every builder follows makeSphere()'s conventions: glTF UV space
// (v = 0 at the image's top), tangent w = +1 (bitangent cross(n, t) points to decreasing v),
// counter-clockwise front faces.
#include "core/mesh.h"
#include "core/mesh_tangents.h"
#include "core/scene.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <numbers>

namespace velvet {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

/// A cube face seen from outside: normal, u axis (right in the image), v axis (down in the
/// image) = cross(u, n), so that (a, b, c), (a, c, d) below wind counter-clockwise about n.
struct Face {
    glm::vec3 n, u;
    glm::vec3 v() const { return glm::cross(u, n); }
};
constexpr Face kCubeFaces[6] = {
    {{0, 0, 1}, {1, 0, 0}},  {{0, 0, -1}, {-1, 0, 0}}, {{1, 0, 0}, {0, 0, -1}},
    {{-1, 0, 0}, {0, 0, 1}}, {{0, 1, 0}, {1, 0, 0}},   {{0, -1, 0}, {1, 0, 0}},
};

/// Appends the indices of a (rows + 1) x (cols + 1) vertex grid starting at @p base, row-major,
/// rows going down the image: a top-left, b bottom-left, c bottom-right, d top-right.
void addGridIndices(MeshData& mesh, std::uint32_t base, int rows, int cols) {
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            const std::uint32_t a = base + std::uint32_t(i * (cols + 1) + j);
            const std::uint32_t b = a + std::uint32_t(cols + 1), c = b + 1, d = a + 1;
            mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
        }
}

/// The point (s, t) in [-1, 1]^2 of a face of the cube [-1, 1]^3. Products with 0 and +-1 and
/// sums with 0 are exact, so a point on an edge comes out bit-identical from both faces.
glm::vec3 facePoint(const Face& f, float s, float t) {
    return f.n + s * f.u + t * f.v();
}

/// One point of a lathe profile: (radius, height).
using ProfilePoint = glm::vec2;

/// Sweeps the profile sections of one closed part about +Y (x = r sin(phi), z = r cos(phi), as
/// makeSphere()). Each section is a polyline with smooth normals; sections meet at hard edges.
/// A profile must run with the outside on its left in the (r, y) plane (normal (-dy, dr)), e.g.
/// top, outer side downwards, bottom: then the faces wind counter-clockwise seen from outside.
/// v runs along the whole profile by arc length.
void addLathe(MeshData& mesh, const std::vector<std::vector<ProfilePoint>>& sections,
              int segments) {
    float total = 0.0f;
    for (const auto& s : sections)
        for (size_t i = 1; i < s.size(); ++i)
            total += glm::length(s[i] - s[i - 1]);
    float travelled = 0.0f;
    for (const auto& s : sections) {
        const std::uint32_t base = std::uint32_t(mesh.vertices.size());
        const int rows = int(s.size()) - 1;
        for (size_t i = 0; i < s.size(); ++i) {
            if (i > 0)
                travelled += glm::length(s[i] - s[i - 1]);
            glm::vec2 n(0.0f);
            if (i > 0) {
                const glm::vec2 d = s[i] - s[i - 1];
                n += glm::normalize(glm::vec2(-d.y, d.x));
            }
            if (i + 1 < s.size()) {
                const glm::vec2 d = s[i + 1] - s[i];
                n += glm::normalize(glm::vec2(-d.y, d.x));
            }
            n = glm::normalize(n);
            if (s[i].x <= 0.0f) // on the axis the normal is the axis
                n = glm::vec2(0.0f, n.y >= 0.0f ? 1.0f : -1.0f);
            for (int j = 0; j <= segments; ++j) {
                const float u = float(j) / float(segments);
                // Both seam columns use phi = -pi exactly, so their positions are bit-identical.
                const float phi = j == segments ? -kPi : (u - 0.5f) * 2.0f * kPi;
                const float sp = std::sin(phi), cp = std::cos(phi);
                Vertex v;
                v.position = glm::vec3(s[i].x * sp, s[i].y, s[i].x * cp);
                v.normal = glm::vec3(n.x * sp, n.y, n.x * cp);
                v.tangent = glm::vec4(cp, 0.0f, -sp, 1.0f);
                v.uv = glm::vec2(u, total > 0.0f ? travelled / total : 0.0f);
                mesh.vertices.push_back(v);
            }
        }
        // As makeSphere(): skip the triangles that collapse on the axis.
        for (int i = 0; i < rows; ++i)
            for (int j = 0; j < segments; ++j) {
                const std::uint32_t a = base + std::uint32_t(i * (segments + 1) + j);
                const std::uint32_t b = a + std::uint32_t(segments + 1), c = b + 1, d = a + 1;
                if (s[size_t(i) + 1].x > 0.0f)
                    mesh.indices.insert(mesh.indices.end(), {a, b, c});
                if (s[size_t(i)].x > 0.0f)
                    mesh.indices.insert(mesh.indices.end(), {a, c, d});
            }
    }
}

} // namespace

MeshData makeCube(float halfSize) {
    MeshData mesh;
    for (const Face& f : kCubeFaces) {
        const std::uint32_t base = std::uint32_t(mesh.vertices.size());
        for (int i = 0; i <= 1; ++i)
            for (int j = 0; j <= 1; ++j) {
                Vertex v;
                v.position = halfSize * facePoint(f, 2.0f * j - 1.0f, 2.0f * i - 1.0f);
                v.normal = f.n;
                v.tangent = glm::vec4(f.u, 1.0f);
                v.uv = glm::vec2(float(j), float(i));
                mesh.vertices.push_back(v);
            }
        addGridIndices(mesh, base, 1, 1);
    }
    return mesh;
}

MeshData makeRoundedCube(float halfSize, float radius, int steps) {
    steps = std::max(steps, 2);
    const float r = std::clamp(radius / halfSize, 0.0f, 1.0f);
    MeshData mesh;
    for (const Face& f : kCubeFaces) {
        const std::uint32_t base = std::uint32_t(mesh.vertices.size());
        for (int i = 0; i <= steps; ++i)
            for (int j = 0; j <= steps; ++j) {
                const float s = 2.0f * float(j) / float(steps) - 1.0f;
                const float t = 2.0f * float(i) / float(steps) - 1.0f;
                // The point on the cube, pulled onto the rounded box: the inner box shrunk by r
                // plus r along the direction from its nearest point (a Minkowski sum with a ball).
                const glm::vec3 p = facePoint(f, s, t);
                const glm::vec3 inner = glm::clamp(p, glm::vec3(r - 1.0f), glm::vec3(1.0f - r));
                const glm::vec3 d = p - inner;
                const float len = glm::length(d);
                const glm::vec3 n = len > 0.0f ? d / len : f.n;
                Vertex v;
                v.position = halfSize * (inner + r * n);
                v.normal = n;
                v.tangent = glm::vec4(glm::normalize(f.u - n * glm::dot(n, f.u)), 1.0f);
                v.uv = glm::vec2(float(j), float(i)) / float(steps);
                mesh.vertices.push_back(v);
            }
        addGridIndices(mesh, base, steps, steps);
    }
    return mesh;
}

MeshData makePlane(float halfSize, int steps) {
    steps = std::max(steps, 1);
    MeshData mesh;
    mesh.doubleSided = true;
    const Face& top = kCubeFaces[4]; // +Y: u = +X, v = +Z
    for (int i = 0; i <= steps; ++i)
        for (int j = 0; j <= steps; ++j) {
            const float s = 2.0f * float(j) / float(steps) - 1.0f;
            const float t = 2.0f * float(i) / float(steps) - 1.0f;
            Vertex v;
            v.position = halfSize * (s * top.u + t * top.v());
            v.normal = top.n;
            v.tangent = glm::vec4(top.u, 1.0f);
            v.uv = glm::vec2(float(j), float(i)) / float(steps);
            mesh.vertices.push_back(v);
        }
    addGridIndices(mesh, 0, steps, steps);
    return mesh;
}

MeshData makeClothDrape(int steps) {
    steps = std::max(steps, 8);
    MeshData mesh;
    mesh.doubleSided = true;
    // A square cloth of side 2 laid over a ball of radius R: a point at distance d from the
    // cloth's centre wraps the ball along a great circle (arc length d) up to the contact angle,
    // then hangs, flaring a little and folding with radial sines whose amplitude grows with the
    // hanging length (a cheap stand-in for a simulated drape).
    const float R = 0.55f, contact = 1.1f, contactArc = R * contact;
    for (int i = 0; i <= steps; ++i)
        for (int j = 0; j <= steps; ++j) {
            const float x = 2.0f * float(j) / float(steps) - 1.0f;
            const float z = 2.0f * float(i) / float(steps) - 1.0f;
            const float d = std::sqrt(x * x + z * z);
            const float phi = std::atan2(x, z);
            float rho, y;
            if (d <= contactArc) {
                const float a = d / R;
                rho = R * std::sin(a);
                y = R * std::cos(a);
            } else {
                const float hang = d - contactArc;
                const float fold = 0.12f * hang * std::sin(7.0f * phi + 1.3f) +
                                   0.05f * hang * std::sin(13.0f * phi);
                rho = R * std::sin(contact) + 0.3f * hang + fold;
                y = R * std::cos(contact) - 0.95f * hang + 0.04f * std::sin(9.0f * phi) * hang;
            }
            // A few soft gaussian wrinkles on top.
            y += 0.015f * std::exp(-((x - 0.2f) * (x - 0.2f) + (z + 0.1f) * (z + 0.1f)) / 0.02f);
            Vertex v;
            v.position = glm::vec3(rho * std::sin(phi), y, rho * std::cos(phi));
            if (d == 0.0f)
                v.position = glm::vec3(0.0f, y, 0.0f);
            v.uv = glm::vec2(float(j), float(i)) / float(steps);
            mesh.vertices.push_back(v);
        }
    addGridIndices(mesh, 0, steps, steps);
    generateNormals(mesh);
    generateTangents(mesh);
    fitToUnitBox(mesh, 0.95f);
    return mesh;
}

MeshData makeShaderBall(int segments) {
    segments = std::max(segments, 8);
    MeshData mesh;
    // Ball: radius 0.5 about (0, 0.2, 0), pole to pole.
    std::vector<ProfilePoint> arc;
    const int arcSteps = std::max(segments / 2, 8);
    for (int i = 0; i <= arcSteps; ++i) {
        const float theta = kPi * float(i) / float(arcSteps);
        arc.emplace_back(i == 0 || i == arcSteps ? 0.0f : 0.5f * std::sin(theta),
                         0.2f + 0.5f * std::cos(theta));
    }
    addLathe(mesh, {arc}, segments);
    // Ring about the equator with a grooved cut-out in its outer face; a closed profile that
    // does not touch the axis (a torus-like shell). Outside on the left of the travel direction.
    addLathe(mesh,
             {{{0.47f, 0.27f}, {0.58f, 0.27f}},
              {{0.58f, 0.27f}, {0.58f, 0.23f}},
              {{0.58f, 0.23f}, {0.53f, 0.23f}},
              {{0.53f, 0.23f}, {0.53f, 0.17f}},
              {{0.53f, 0.17f}, {0.58f, 0.17f}},
              {{0.58f, 0.17f}, {0.58f, 0.13f}},
              {{0.58f, 0.13f}, {0.47f, 0.13f}},
              {{0.47f, 0.13f}, {0.47f, 0.27f}}},
             segments);
    // Pedestal: top disc, bevel, neck, flare, foot, bottom disc.
    addLathe(mesh,
             {{{0.0f, -0.25f}, {0.3f, -0.25f}},
              {{0.3f, -0.25f}, {0.33f, -0.28f}},
              {{0.33f, -0.28f}, {0.33f, -0.42f}},
              {{0.33f, -0.42f}, {0.5f, -0.5f}},
              {{0.5f, -0.5f}, {0.5f, -0.58f}},
              {{0.5f, -0.58f}, {0.0f, -0.58f}}},
             segments);
    // Lathe tangents are analytic (d/dphi); they are already orthogonal to the normals.
    fitToUnitBox(mesh, 1.0f);
    return mesh;
}

MeshData makePreviewMesh(PreviewMeshKind kind) {
    switch (kind) {
    case PreviewMeshKind::Sphere:
        return makeSphere();
    case PreviewMeshKind::Cube:
        return makeCube();
    case PreviewMeshKind::RoundedCube:
        return makeRoundedCube();
    case PreviewMeshKind::Plane:
        return makePlane();
    case PreviewMeshKind::ClothDrape:
        return makeClothDrape();
    case PreviewMeshKind::ShaderBall:
        return makeShaderBall();
    case PreviewMeshKind::Custom:
        break;
    }
    return {};
}

bool previewMeshIsConvex(PreviewMeshKind kind) {
    return kind == PreviewMeshKind::Sphere || kind == PreviewMeshKind::Cube ||
           kind == PreviewMeshKind::RoundedCube || kind == PreviewMeshKind::Plane;
}

} // namespace velvet
