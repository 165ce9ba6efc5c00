#pragma once
/// @file mesh.h
/// Triangle meshes with tangents, and the procedural preview meshes.

#include <cstddef>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vector>

namespace velvet {

enum class PreviewMeshKind : int; // core/scene.h

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec4 tangent; ///< xyz tangent, w handedness (glTF convention: bitangent = cross(n, t) * w)
    glm::vec2 uv;
};

struct MeshData {
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> indices; ///< triangles, counter-clockwise front faces
    /// An open surface (plane, cloth) whose back is meant to be seen: drawn without culling.
    bool doubleSided = false;
    /// Per vertex, or empty: xyz the bent normal, w the share of the hemisphere the mesh does
    /// not hide from the vertex (render/mesh_visibility.h). Empty means nothing is hidden (a
    /// convex mesh), which the renderer draws as (0, 0, 0, 1): no cone, all open.
    std::vector<glm::vec4> visibility;
    size_t triangleCount() const { return indices.size() / 3; }
};

/// Axis-aligned bounds of a mesh's vertices (min > max when it has none).
struct MeshBounds {
    glm::vec3 min{1e30f};
    glm::vec3 max{-1e30f};
    bool empty() const { return min.x > max.x; }
    glm::vec3 center() const { return 0.5f * (min + max); }
    glm::vec3 size() const { return max - min; }
};
MeshBounds meshBounds(const MeshData& mesh);

/// Moves @p mesh so its bounding box is centred at the origin and scales it uniformly so the
/// largest side spans [-halfExtent, halfExtent]: every preview mesh lives in the box [-1, 1]^3,
/// the unit sphere's box, which the default camera frames. Normals and tangents are unchanged
/// (uniform scale). An empty or point-like mesh is left alone.
void fitToUnitBox(MeshData& mesh, float halfExtent = 1.0f);

/// @name Procedural preview meshes (core/mesh_procedural.cpp)
/// All centred at the origin, inside [-1, 1]^3, with unit normals, tangents with handedness
/// (bitangent = cross(n, t) * w points to decreasing v: glTF's UV space, v = 0 at the image's
/// top, OpenGL-style normal maps), UVs, counter-clockwise front faces.
/// @{
/// A UV sphere of radius @p radius centred at the origin.
MeshData makeSphere(float radius = 1.0f, int segments = 96, int rings = 48);
/// A cube of half-size @p halfSize with hard edges: 24 vertices, each face UV-mapped to [0, 1]^2.
MeshData makeCube(float halfSize = 0.8f);
/// A cube of half-size @p halfSize with edges rounded to @p radius: each face a @p steps^2 grid
/// projected onto the rounded box (closed; positions shared exactly across face seams).
MeshData makeRoundedCube(float halfSize = 0.8f, float radius = 0.2f, int steps = 24);
/// A square in the XZ plane (y = 0), normal +Y, side 2 * @p halfSize, @p steps^2 quads;
/// double-sided.
MeshData makePlane(float halfSize = 1.0f, int steps = 16);
/// A cloth draped over a sphere-like support: a grid whose height falls off from a domed top
/// and whose hanging border folds (radial sines), the look-dev "cloth" shape; double-sided.
MeshData makeClothDrape(int steps = 96);
/// A shader ball (the classic look-dev shape): a sphere on a lathed pedestal, ringed at its
/// equator by a band with a grooved cut-out; every part a closed lathe surface.
MeshData makeShaderBall(int segments = 96);
/// The procedural mesh of @p kind (PreviewMeshKind::Custom gives an empty mesh: import it).
MeshData makePreviewMesh(PreviewMeshKind kind);
/// Whether the preview mesh of @p kind is convex or flat (sphere, cube, rounded cube, plane), so
/// no part of it hides another from the environment: no visibility to bake.
bool previewMeshIsConvex(PreviewMeshKind kind);
/// @}

} // namespace velvet
