#pragma once
/// @file graph_material.h
/// The material graph at a path-tracer hit: the graph's outputs, evaluated on the CPU by the
/// graph compiler's twin (core/graph/graph_eval.h), overwrite the surface's parameters as
/// velvetGraph() overwrites MaterialInputs in the viewport's geometry pass (gbuffer.frag):
/// parameters times their slot textures go in, the graph's fed outputs replace them.

#include "core/brdf.h"
#include "core/diagnostics.h"
#include "core/material.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <memory>

namespace velvet {
class TextureCache;
}

namespace velvet::reference {

/// KHR_materials_anisotropy's inputs at a hit before they become a world direction: the
/// tangent-space direction (the texture's RG remapped, or the graph's anisotropyDirection) and the
/// rotation in degrees.
struct AnisotropyInputs {
    glm::vec2 direction{1.0f, 0.0f};
    float rotationDeg = 0.0f;
};

/// The world-space unit anisotropy direction at a hit (brdf::Surface::anisotropyDirection):
/// @p a's direction (normalised; (1, 0) when zero) rotated by its rotation, on the frame of the
/// interpolated mesh @p tangent (w: handedness, bitangent = cross(n, t) w) made orthogonal to the
/// shading normal @p n; any tangent orthogonal to n when the mesh's is unusable.
glm::vec3 anisotropyWorldDirection(glm::vec3 n, glm::vec4 tangent, const AnisotropyInputs& a);

class GraphMaterial {
public:
    /// Plans @p material's graph (none: inactive); texture nodes' images come from @p cache
    /// (problems reported into @p problems, missing files sample white as in the viewport).
    GraphMaterial(const Material& material, TextureCache& cache, Problems* problems);
    ~GraphMaterial();
    GraphMaterial(const GraphMaterial&) = delete;
    GraphMaterial& operator=(const GraphMaterial&) = delete;

    /// Whether the graph feeds any of the material's inputs.
    bool active() const;

    /// Overwrites what the graph feeds at @p uv: the parameters in @p s (sheen as weight x
    /// colour, emission as colour x strength, from the material's values where the graph feeds
    /// only one of the two) and the tangent-space normal @p tangentNormal (@p normalFed set true
    /// when the graph feeds it; it is then scaled by the normal scale like a normal map), and the
    /// anisotropy direction and rotation in @p anisotropy and the ambient occlusion in
    /// @p occlusion (before the strength) when given.
    void apply(glm::vec2 uv, brdf::Surface& s, glm::vec3& tangentNormal, bool& normalFed,
               AnisotropyInputs* anisotropy = nullptr, float* occlusion = nullptr) const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace velvet::reference
