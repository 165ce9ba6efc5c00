#pragma once
/// @file mesh_tangents.h
/// Vertex normals and tangent frames generated from a mesh's triangles, for meshes that come
/// without them (imported files, height-field surfaces).

#include "core/mesh.h"

namespace velvet {

/// A unit vector orthogonal to unit @p n (Duff et al. 2017, "Building an Orthonormal Basis,
/// Revisited"): the tangent of a vertex whose UVs define none.
glm::vec3 anyOrthogonal(glm::vec3 n);

/// Sets every vertex normal to the area-weighted average of the normals of the triangles that
/// use it (the cross product's length is twice the area, so summing unnormalised cross products
/// weights by area). Vertices no triangle uses get +Y.
void generateNormals(MeshData& mesh);

/// Generates tangents with handedness from positions, normals and UVs: per-triangle tangent and
/// bitangent from the UV derivatives, summed per vertex, then Gram-Schmidt-orthonormalised
/// against the normal (Lengyel 2001, "Computing Tangent Space Basis Vectors for an Arbitrary
/// Mesh"). w follows the glTF convention with glTF's UV space (v = 0 at the image's top):
/// cross(n, t) * w points to decreasing v, as makeSphere() does. Triangles with degenerate UVs
/// add nothing; a vertex left without a tangent gets any unit vector orthogonal to its normal.
/// Used for the procedural meshes; imported ones get MikkTSpace (core/mikktspace.h).
void generateTangents(MeshData& mesh);

} // namespace velvet
