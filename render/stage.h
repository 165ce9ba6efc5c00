#pragma once
/// @file stage.h
/// Render-private: the look-dev stage around the preview mesh (docs/shadows.md) — the shadow maps
/// (render/shadow_maps.h), the ground drawn into the G-buffer after the mesh (ground.vert/.frag:
/// a square at the mesh's lowest point, material id kGroundPlainMaterialId or
/// kGroundCatcherMaterialId), screen-space ambient occlusion (render/ao_pass.h), the screen-space
/// shadow mask the lighting passes read the shadows from (render/shadow_mask.h) — and the
/// StageBlock every lighting pass reads them through. Renderer::render() calls it at five
/// points: shadows before the geometry pass, the ground after it, occlusion and the shadow mask
/// after that, and bind() before lighting.

#include "core/diagnostics.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "render/ao_pass.h"
#include "render/material_table.h"
#include "render/render_interface.h"
#include "render/shadow_maps.h"
#include "render/shadow_mask.h"

#include <string>
#include <vector>

namespace velvet::render {

class GpuMesh;

/// The plain ground's record of the material table (also the catcher's): its colour and
/// roughness, a dielectric.
GpuMaterial groundMaterial(const Environment& environment);

class Stage {
public:
    Stage() = default;
    /// Needs the renderer's context current.
    ~Stage();
    Stage(const Stage&) = delete;
    Stage& operator=(const Stage&) = delete;

    bool initialize(std::string* error);
    bool reload(std::string* error);
    int compileCount() const;

    /// The lights or the mesh changed: plans the shadow slots around @p bounds (warnings for
    /// the lights left out go to @p problems).
    void plan(const std::vector<Light>& lights, const MeshBounds& bounds, Problems* problems);
    /// Per scene light: its shadow slot + 1, or 0 (LightPasses::upload).
    std::vector<int> slotOfLight(size_t lightCount) const {
        return m_shadows.slotOfLight(lightCount);
    }
    /// Marks each shadowed directional light of @p block (lightDirection[i].w = slot + 1).
    void annotate(FrameBlock& block, const std::vector<Light>& lights) const;
    /// Whether a directional light the frame block carries has a shadow map (annotate()).
    bool shadowsDirectionalLight(const std::vector<Light>& lights) const;

    /// Whether the occlusion of a frame of @p scene rides in the shadow masks' free fourth
    /// channel (OcclusionPass::packInto, StageBlock::counts.z): @p allowed
    /// (FrameSettings::packOcclusion), occlusion on, one to three shadow slots, one of them a
    /// directional light's.
    bool packsOcclusion(const Scene& scene, bool allowed) const;
    /// Whether this frame's occlusion rides in the shadow masks (beginFrame()'s packsOcclusion).
    bool occlusionInMask() const { return m_block.counts.z != 0; }
    /// Before the geometry pass: the shadow maps, when the lights or the mesh changed (timed).
    void drawShadows(const GpuMesh& mesh);
    /// The frame's StageBlock, uploaded and bound at stage_binding::kStageUbo; @p downsample is
    /// the masks' and the occlusion's (kStageDownsample, or kNavigatingStageDownsample in a frame
    /// drawn while the camera moves). @p packOcclusion lets the occlusion ride in the shadow
    /// masks where a channel is free (FrameSettings::packOcclusion).
    void beginFrame(const Scene& scene, int width, int height, int downsample,
                    bool packOcclusion = true);
    /// The downsample beginFrame() took.
    int downsample() const { return m_block.counts.y; }
    /// After the geometry pass, into its (still bound) framebuffer: the ground, if any.
    void drawGround(const Environment& environment);
    /// After the ground: the occlusion term, if on, over the pixels near the mesh seen through
    /// @p viewProj, the frame's camera (occlusionRect()), or the last frame's kept when
    /// @p frameKey (the camera, the material's normals where it bends them) and the stage's own
    /// inputs are as they were (render/ao_pass.h); expects the G-buffer textures bound.
    /// @p bentNormals: some drawn material bends its shading normal (about the geometric normal
    /// there). Leaves the viewport for the caller to reset.
    bool drawOcclusion(const Environment& environment, const glm::mat4& viewProj, int width,
                       int height, bool bentNormals, FrameKey frameKey, unsigned emptyVao,
                       std::string* error);
    /// The depth or the normals changed in a way no key sees (the mesh, a texture, a graph, the
    /// shaders, a split frame): the next frame's occlusion and shadow mask are drawn again.
    void invalidateScreenPasses() {
        m_occlusion.invalidate();
        m_maskReuse.invalidate();
    }
    /// Whether the last frame kept the frame before's occlusion.
    bool lastOcclusionKept() const { return m_occlusionKept; }
    /// Whether a point, spot or area light has a shadow slot (the catcher's slot loop).
    bool shadowsLocalLight(const std::vector<Light>& lights) const;
    /// Whether a light casts a shadow this frame (the frame then needs a shadow mask).
    bool hasShadows() const { return !m_shadows.slots().empty(); }
    /// After the occlusion: the screen-space shadow mask of every shadow slot into
    /// @p framebuffer (FrameTargets::shadowMaskFramebuffer(), whose colours are @p maskTexture
    /// and @p keyTexture), timed; nothing when no light casts a shadow. Expects the G-buffer's
    /// textures bound and @p viewProj the frame's camera. Leaves the viewport and depth state for
    /// the caller to set. The last frame's masks are kept, as the occlusion is, when
    /// @p frameKey (the camera, the material's normals where it bends them, the targets) and the
    /// stage's own inputs (the lights' slots and the StageBlock, the maps as drawn, the ground,
    /// the bounds) are as they were: after a material value edit, a slider dragged on a shadowed
    /// stage, the masks are the same texels. @p bentNormals: some drawn material bends its
    /// shading normal (its receivers offset along the face's normal, ShadowMaskPass::run).
    void drawShadowMask(unsigned framebuffer, unsigned maskTexture, unsigned keyTexture,
                        unsigned groundMaskTexture, const Environment& environment,
                        const glm::mat4& viewProj, int width, int height, FrameKey frameKey,
                        unsigned emptyVao, bool settle = true, bool bentNormals = true);
    /// Whether the last frame kept the frame before's shadow masks.
    bool lastShadowMaskKept() const { return m_maskKept; }
    /// The pixel rectangle (x, y, width, height) that holds the mesh's bounds seen through
    /// @p viewProj in a @p width x @p height frame (the whole frame when they reach behind the
    /// camera); false when there is no mesh.
    /// With a shadow catcher the surface pass is scissored to it, so the ground's pixels outside
    /// pay nothing for the mesh's shading (llvmpipe shades a discarded pixel to the end).
    bool meshRectangle(const glm::mat4& viewProj, int width, int height, int rect[4]) const;
    /// Before lighting: the shadow mask and the occlusion at their units.
    void bind() const;
    void unbind() const;

    /// GPU milliseconds of the last frame's shadow-map and occlusion passes (0 when not run).
    double lastShadowMs() const;
    double lastOcclusionMs() const;
    /// GPU milliseconds of the last frame's shadow-mask passes, and how many it drew (one per
    /// shadow slot with receivers on screen; at most kMaxShadowLights).
    double lastShadowMaskMs() const;
    /// (The passes of the masks the frame reads: a kept mask's are the frame's that drew it.)
    int lastShadowMaskPasses() const { return m_maskPasses; }
    /// The last frame's shadow-mask texels drawn and filtered (ShadowMaskPass::lastTexels).
    void lastShadowMaskTexels(long long* texels, long long* filtered) const {
        m_mask.lastTexels(texels, filtered);
    }

private:
    ShadowMaps m_shadows;
    ShadowMaskPass m_mask;
    OcclusionPass m_occlusion;
    ShaderProgram m_groundProgram;
    int m_groundCompiles = 0;
    MeshBounds m_bounds;
    unsigned m_ubo = 0;
    unsigned m_queries[6] = {};
    mutable bool m_shadowTimed = false, m_occlusionTimed = false;
    unsigned m_maskTexture = 0;       ///< this frame's shadow mask (0: no light casts a shadow)
    unsigned m_keyTexture = 0;        ///< its key (view depth, material id per texel)
    unsigned m_groundMaskTexture = 0; ///< the ground's mask, read by the shadow catcher
    int m_maskPasses = 0;
    PixelRect m_occlusionTexels; ///< the occlusion's drawn texels this frame (packInto's)
    FrameReuse m_maskReuse;
    bool m_maskKept = false;
    StageBlock m_block{}; ///< the frame's, as beginFrame() uploaded it (the mask's key)
    bool m_occlusionOn = false;
    bool m_occlusionKept = false;
};

} // namespace velvet::render
