#pragma once
/// @file frame_uniforms.h
/// Render-private: the per-frame uniform blocks every pass reads — FrameBlock (camera, viewport,
/// SH9 ambient, directional lights, modes) and IblBlock (the prefiltered environment's state),
/// both described in render/render_interface.h — filled from the scene and the frame settings,
/// and the uniform buffers they live in.

#include "core/scene.h"
#include "render/render_interface.h"
#include "render/renderer.h"

namespace velvet::render {

struct GpuEnvironment;
class IblBaker;

/// The frame block of @p scene seen from @p camera (FrameSettings::camera or the scene's) with
/// @p environment's SH9: the first kMaxDirectionalLights directional lights, the ambient lights
/// summed (point, spot and area lights are render/light_passes.h's).
FrameBlock makeFrameBlock(const Scene& scene, const Camera& camera,
                          const GpuEnvironment& environment, const FrameSettings& fs);
/// How many of @p lights the frame block carries as directional lights (FrameBlock::modes.x):
/// the directional ones, at most kMaxDirectionalLights.
int frameDirectionalLightCount(const std::vector<Light>& lights);
/// The clip-space offset that moves a @p width x @p height image by @p jitter pixels
/// (FrameSettings::jitter; identity for none): the frame block's projection is it times the
/// camera's. jitterMatrix(-jitter, ...) undoes it.
glm::mat4 jitterMatrix(glm::vec2 jitter, int width, int height);
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
