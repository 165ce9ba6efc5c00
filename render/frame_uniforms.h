#pragma once
/// @file frame_uniforms.h
/// Render-private: the per-frame uniform blocks every pass reads — FrameBlock (camera, viewport,
/// SH9 ambient, directional lights, modes; common_frame.glsl) and IblBlock (the prefiltered
/// environment's state; common_environment.glsl) — filled from the scene and the frame settings,
/// and the uniform buffers they live in.

#include "core/scene.h"
#include "render/renderer.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

namespace velvet::render {

struct GpuEnvironment;
class IblBaker;

/// Mirrors FrameBlock in common_frame.glsl (std140; vec4 / mat4 members only).
struct FrameBlock {
    glm::mat4 view, proj, invProj, invView, viewProj;
    glm::vec4 cameraPosition;
    glm::vec4 viewport;
    glm::vec4 envSh[9];
    glm::vec4 envParams;
    glm::vec4 ambientRadiance;
    glm::vec4 backgroundColor;
    glm::ivec4 modes;
    glm::vec4 post;
    glm::vec4 lightDirection[kMaxDirectionalLights];
    glm::vec4 lightRadiance[kMaxDirectionalLights];
};

/// Mirrors IblBlock in common_environment.glsl (std140, vec4 only).
struct IblBlock {
    glm::vec4 state;      ///< cube ready, its last level, DFG LUT ready, multiple scattering on
    glm::vec4 background; ///< blurred background level, time (s), unused, unused
};

/// The frame block of @p scene seen from @p camera (FrameSettings::camera or the scene's) with
/// @p environment's SH9: the first kMaxDirectionalLights directional lights, the ambient lights
/// summed (point, spot and area lights are render/light_passes.h's).
FrameBlock makeFrameBlock(const Scene& scene, const Camera& camera,
                          const GpuEnvironment& environment, const FrameSettings& fs);
/// The IBL block for the bake's current state.
IblBlock makeIblBlock(const IblBaker& ibl, const FrameSettings& fs);

/// The two uniform buffers (binding::kFrameUbo, binding::kIblUbo).
class FrameUniforms {
public:
    FrameUniforms() = default;
    /// Needs the renderer's context current.
    ~FrameUniforms();
    FrameUniforms(const FrameUniforms&) = delete;
    FrameUniforms& operator=(const FrameUniforms&) = delete;

    /// Creates the buffers; needs a current context.
    void initialize();
    /// Uploads @p b and binds it at binding::kFrameUbo.
    void bindFrame(const FrameBlock& b);
    /// Uploads @p b and binds it at binding::kIblUbo.
    void bindIbl(const IblBlock& b);

private:
    unsigned m_frameUbo = 0, m_iblUbo = 0;
};

} // namespace velvet::render
