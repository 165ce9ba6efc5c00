#pragma once
/// @file mesh_visibility.h
/// How much of its hemisphere each vertex of a mesh sees past the mesh itself, ray traced once
/// per mesh (issue 15): the viewport's image-based light uses it to occlude the environment's
/// light where the mesh hides it from itself, diffusely and in its reflections (the shader
/// ball's ring over its pedestal), which screen-space occlusion reaches only partly.
/// Rays through Embree, threads through oneTBB (both only in the .cpp), as the reference path
/// tracer's; no GL: the mesh cache bakes it before the upload (render/mesh_cache.cpp).

#include "core/mesh.h"

#include <cstdint>
#include <glm/vec4.hpp>
#include <vector>

namespace velvet::render {

struct VisibilityBakeOptions {
    int raysPerVertex = 128;
    /// Rays for the whole mesh: a mesh with more vertices gets fewer rays each (at least 16), so
    /// a large import costs a bounded time (about 0.1 s per million rays on two cores).
    std::int64_t rayBudget = 4'000'000;
};

/// Per vertex of @p mesh, in its vertex order: xyz the bent normal (the normalised mean of the
/// unoccluded directions among rays spread uniformly over the hemisphere about the vertex normal;
/// the normal itself when every ray is blocked), w the unoccluded share of the hemisphere's solid
/// angle (1: the mesh hides nothing above the vertex). The viewport takes them as a cone of open
/// directions (gbuffer.frag, mesh_visibility.glsl). The share is by solid angle, not cosine
/// weighted, so a vertex that sees nearly all its sky gets a cone that reaches nearly to its
/// horizon: a cosine-weighted share (the ambient occlusion) puts the cone's rim well above it and
/// hid the grazing reflections of open vertices (BENCHMARKS.md). The same mesh gives the same
/// values on every run and thread count. Empty when the mesh has no triangle or Embree cannot
/// start.
std::vector<glm::vec4> bakeMeshVisibility(const MeshData& mesh,
                                          const VisibilityBakeOptions& options = {});

} // namespace velvet::render
