#pragma once
/// @file shadow_maps.h
/// Render-private: shadow maps for the lights that cast shadows (docs/shadows.md). At most
/// kMaxShadowLights lights, the strongest at the mesh, each get one layer of a depth-texture
/// array fitted to the preview mesh's bounding sphere: an orthographic box for a directional
/// light, a perspective frustum from a point, spot or area light's centre that just holds the
/// sphere. Receivers outside a map are outside every caster's shadow, so the ground needs no map
/// of its own. The maps are drawn again only when the lights or the mesh change (an orbit draws
/// none); the lighting passes filter them with PCSS (Fernando 2005) in shadow_sampling.glsl.

#include "core/diagnostics.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "render/shader_program.h"
#include "render/shadow_depth_bounds.h"
#include "render/stage_interface.h"

#include <glm/mat4x4.hpp>
#include <string>
#include <vector>

namespace velvet::render {

struct ShadowSlot {
    int light = -1; ///< index into the scene's lights
    bool perspective = false;
    glm::mat4 view{1.0f}, proj{1.0f};
    float nearPlane = 0.0f, farPlane = 1.0f;
    /// Perspective: the source's diameter (m); orthographic: 2 tan(angular diameter / 2).
    float sourceSize = 0.0f;
    /// Orthographic: metres per unit of uv; perspective: 2 tan(half fov) (x the depth).
    float metresPerUv = 1.0f;
    float contribution = 0.0f; ///< what the ranking compared (illuminance at the mesh centre)
};

/// The mesh's bounding sphere, from its axis-aligned bounds.
struct BoundingSphere {
    glm::vec3 center{0.0f};
    float radius = 1.0f;
};
BoundingSphere boundingSphere(const MeshBounds& bounds);

/// The shadow slots for @p lights around @p casters: every light with castShadows (not ambient)
/// whose source lies outside the sphere, ranked by illuminance at the sphere's centre, the first
/// kMaxShadowLights kept. Each light left out is a warning in @p problems naming "lights[i]".
std::vector<ShadowSlot> planShadows(const std::vector<Light>& lights, const BoundingSphere& casters,
                                    Problems* problems);

class ShadowMaps {
public:
    ShadowMaps() = default;
    /// Needs the renderer's context current.
    ~ShadowMaps();
    ShadowMaps(const ShadowMaps&) = delete;
    ShadowMaps& operator=(const ShadowMaps&) = delete;

    bool initialize(std::string* error);
    bool reload(std::string* error);
    int compileCount() const { return m_compileCount; }

    /// Plans the slots for @p lights around @p casters (planShadows) and marks the maps for
    /// drawing at the next draw() when a slot's view or projection changed.
    void plan(const std::vector<Light>& lights, const BoundingSphere& casters, Problems* problems);
    const std::vector<ShadowSlot>& slots() const { return m_slots; }
    /// Per scene light: its slot + 1, or 0 (no shadow); what the light buffers carry.
    std::vector<int> slotOfLight(size_t lightCount) const;

    /// Draws the depth maps of @p mesh when plan() or a new mesh asked for it; true when it drew.
    /// Leaves the framebuffer, viewport and depth state for the caller to set.
    bool draw(const class GpuMesh& mesh);
    /// How many times draw() has drawn the maps: what the shadow mask's reuse key sees of them.
    unsigned long long drawCount() const { return m_drawCount; }
    /// Fills the shadow members of @p block (the scene's lights for the catcher's radiance).
    void fill(StageBlock& block, const std::vector<Light>& lights) const;
    /// Binds the depth array at both shadow units with their samplers, and its depth bounds
    /// (render/shadow_depth_bounds.h) at theirs.
    void bind() const;
    void unbind() const;

private:
    void allocate(int layers, int size);

    ShaderProgram m_program;
    ShadowDepthBounds m_bounds; ///< the maps' min-max chain, rebuilt with them
    int m_compileCount = 0;
    std::vector<ShadowSlot> m_slots;
    bool m_dirty = true;
    unsigned long long m_drawCount = 0;
    const GpuMesh* m_drawnMesh = nullptr;
    unsigned m_texture = 0, m_fbo = 0, m_compareSampler = 0, m_depthSampler = 0;
    int m_layers = 0, m_size = 0;
};

} // namespace velvet::render
