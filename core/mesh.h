#pragma once
/// @file mesh.h
/// Triangle meshes with tangents, and the procedural preview meshes.

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vector>

namespace velvet {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec4 tangent; ///< xyz tangent, w handedness (glTF convention: bitangent = cross(n, t) * w)
    glm::vec2 uv;
};

struct MeshData {
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> indices; ///< triangles, counter-clockwise front faces
};

/// A UV sphere of radius @p radius centred at the origin.
MeshData makeSphere(float radius = 1.0f, int segments = 96, int rings = 48);

} // namespace velvet
