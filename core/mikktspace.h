#pragma once
/// @file mikktspace.h
/// MikkTSpace tangent frames (Morten S. Mikkelsen 2008, "Simulation of Wrinkled Surfaces
/// Revisited", and his reference mikktspace.c): the frames glTF 2.0 (§3.7.2.1, "Meshes") tells a
/// client to generate when a mesh with a normal map has no TANGENT attribute, and the frames
/// normal-map bakers (Blender, Substance, xNormal) encode with — so a baked map decodes exactly.
/// Velvet's own implementation of the reference algorithm; docs/architecture.md, "Tangents".

#include "core/mesh.h"

#include <cstdint>
#include <glm/vec4.hpp>
#include <vector>

namespace velvet {

/// One tangent per triangle corner, in mesh.indices order.
struct CornerTangents {
    /// xyz unit tangent in the plane of the corner's normal; w the handedness in the glTF
    /// convention with glTF's UV space (v = 0 at the image's top): cross(n, t) * w points to
    /// decreasing v. That is the reference's sign negated — the reference's bitangent points to
    /// increasing v — as three.js and the glTF sample assets apply it.
    std::vector<glm::vec4> tangents;
    /// 0 where the reference leaves its placeholder (tangent (1, 0, 0)): a corner whose
    /// triangles have no UV area, or a degenerate triangle's corner that touches no valid one.
    /// Such a corner gets any unit vector orthogonal to its normal (w = 1) instead, since a
    /// tangent along the normal would make a shader's frame singular.
    std::vector<std::uint8_t> defined;
};

/// The MikkTSpace tangent of every corner of @p mesh's triangles, with the reference's default
/// settings (no angular split of a vertex's fan). Normals are assumed unit.
CornerTangents mikkTSpaceCornerTangents(const MeshData& mesh);

/// Sets every vertex's tangent to its corners' MikkTSpace tangent. A vertex whose corners get
/// different tangents (a mirrored-UV seam on shared vertices, a fan split in two) is split:
/// the first tangent stays at the vertex's index, copies with the others are appended after the
/// existing vertices and the corners' indices updated. Vertices no triangle uses get any unit
/// vector orthogonal to their normal.
void generateMikkTSpaceTangents(MeshData& mesh);

/// The same for one part of @p mesh — one of a file's meshes, such as a glTF primitive, which
/// the glTF specification gives its own tangents: the triangles of indices[firstIndex,
/// firstIndex + indexCount), which use only vertices [firstVertex, firstVertex + vertexCount).
/// Split copies are appended at the end of the mesh's vertices.
void generateMikkTSpaceTangents(MeshData& mesh, size_t firstVertex, size_t vertexCount,
                                size_t firstIndex, size_t indexCount);

} // namespace velvet
