#pragma once
/// @file ao_pass.h
/// Render-private: screen-space ambient occlusion (GTAO, ao_gtao.frag) at half resolution (a
/// quarter while the camera moves: the stage's downsample, render/stage_interface.h) after the
/// geometry pass, then a depth-aware 4x4 blur (ao_blur.frag); the lighting pass reads the
/// result at stage_binding::kOcclusionTex with a depth-aware upsample (stage_shading.glsl) and
/// multiplies the environment's light by it and the material's occlusion map.
/// The search integrates the visible share of the hemisphere about the surface's geometric
/// normal (the depth's) where a material bends its shading normal (a weave, a knit, a normal
/// map), so the micro-relief's own horizon is not counted twice (the lighting's geometric horizon
/// and the material's occlusion have it); the program with that reconstruction runs only in a
/// frame that draws such a material (LightingFeatures::geometricHorizon).
/// Only the texels that can differ from 1 run: a point farther than the search radius from the
/// mesh sees nothing but the flat ground, so both passes are scissored to the mesh's bounds grown
/// by the radius (occlusionRect()) and the rest is cleared to 1. And only in frames whose result
/// can differ from the last one's: the passes read the G-buffer's depth and normals and the
/// camera, which a material's colour or a light does not change, so a frame whose key
/// (render/frame_reuse.h) matches the last one's keeps the targets as they are.

#include "core/mesh.h"
#include "render/frame_reuse.h"
#include "render/gbuffer.h"
#include "render/shader_program.h"
#include "render/shadow_mask.h"

#include <string>

namespace velvet::render {

/// The pixels of a @p width x @p height frame seen through @p viewProj whose occlusion can differ
/// from 1: the screen rectangle of @p bounds grown by @p radius on every side (the whole frame
/// when they reach behind the camera, none without a mesh). Pure: test_render_shadow_mask checks
/// it.
PixelRect occlusionRect(const MeshBounds& bounds, float radius, const glm::mat4& viewProj,
                        int width, int height);

class OcclusionPass {
public:
    bool build(std::string* error);
    int compileCount() const { return m_compileCount; }
    /// The blurred texels the upsample of @p frameRect's pixels (occlusionRect()) reads in a
    /// @p width x @p height frame at @p downsample: those run() draws, every other one is
    /// exactly 1.
    static PixelRect texelRect(const PixelRect& frameRect, int width, int height, int downsample) {
        return maskRect(frameRect, maskSize(width, downsample), maskSize(height, downsample),
                        downsample);
    }
    /// Runs both passes for a @p width x @p height frame at @p downsample (its targets
    /// maskSize() texels each way) over @p texels (texelRect()), with the
    /// geometric normal for the materials that bend theirs when @p geometricNormals, unless
    /// @p key (every byte the result depends on that can change without invalidate()) is the last
    /// run's: then the targets already hold the result and @p kept is set. Expects the frame and
    /// stage blocks and the G-buffer's textures bound. Leaves the viewport at the targets' size
    /// and the scissor test off.
    bool run(int width, int height, int downsample, const PixelRect& texels, bool geometricNormals,
             FrameKey key, unsigned emptyVao, bool* kept, std::string* error);
    /// Something the key cannot see changed (the mesh, a texture, the shaders): the next run draws.
    void invalidate() { m_reuse.invalidate(); }
    /// The blurred occlusion at stage_binding::kOcclusionTex.
    void bind() const;
    /// The blurred occlusion into the alpha of the shadow masks of @p maskFramebuffer
    /// (FrameTargets::shadowMaskFramebuffer(), the same texel grid), when no shadow slot takes
    /// their fourth channel: the lighting passes then read it with the shadows' upsample, not
    /// their own (stage_shading.glsl's stageOcclusion, StageBlock::counts.z; ao_pack.frag). Over
    /// @p texels (run()'s), alpha 1 elsewhere. Expects the frame and stage blocks and the
    /// G-buffer's textures bound, after run() and the masks' passes of this frame.
    void packInto(unsigned maskFramebuffer, const PixelRect& texels, unsigned emptyVao);

private:
    ShaderProgram m_gtao[2]; // [1]: the geometric normal for materials that bend theirs
    ShaderProgram m_blur, m_pack;
    ColorTarget m_raw, m_blurred;
    FrameReuse m_reuse;
    int m_compileCount = 0;
};

} // namespace velvet::render
