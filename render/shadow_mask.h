#pragma once
/// @file shadow_mask.h
/// Render-private: the screen-space shadow mask (docs/shadows.md). After the G-buffer, one small
/// full-screen pass per shadow slot (at most kMaxShadowLights: the cap) filters the slot's map with
/// PCSS at every other pixel of each row and column (shadow_mask.frag) and writes the visibility
/// into channel s of a half-resolution RGBA8 texture; the lighting passes then read it, upsampled
/// by depth (shadow_mask.glsl), instead of running the lookup inside their own shaders. This is how
/// deferred engines shade shadows (Unity's screen-space shadows, Unreal's shadow projection into a
/// light attenuation buffer). On llvmpipe, which runs every side of every branch, the lighting
/// shaders without the lookup are cheaper for every frame, and the lookup is cheaper in a pass of
/// its own, four times cheaper at half resolution (BENCHMARKS.md, the look-dev stage's shadow
/// mask).
///
/// Two masks: the mask proper, each texel's own surface (the mesh's texels read it with a depth-
/// and material-aware upsample), and the ground's mask, where each texel's view ray meets the
/// ground (behind the mesh too), which is smooth across the mesh's silhouettes, so the shadow
/// catcher reads it with one bilinear fetch. Each is drawn in two passes per slot: a settle pass
/// (the key; the visibility wherever the maps' depth bounds settle it without filtering,
/// render/shadow_depth_bounds.h; a depth of 1 where they do not) and the lookup, drawn with a
/// depth test that passes only there (llvmpipe then skips whole blocks of settled texels). The
/// ground's passes also write the mask (the ground's own texels), the mesh's overwrite it on the
/// mesh's texels. Each slot's passes are scissored to the part of the frame where a receiver can
/// lie inside the slot's map (shadowReceiverRect()), the mesh's to its bounds; the masks are
/// cleared to 1 first, which is exactly what the lookup returns for a receiver outside its map.

#include "core/mesh.h"
#include "render/shader_program.h"
#include "render/shadow_maps.h"

#include <glm/mat4x4.hpp>
#include <string>
#include <vector>

namespace velvet::render {

/// A pixel rectangle of the frame.
struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
    bool operator==(const PixelRect&) const = default;
};

/// The pixels of a @p width x @p height frame seen through @p viewProj where shadow slot
/// @p slot's visibility can differ from 1: the stage's receivers are the mesh (inside @p bounds)
/// and, when @p ground, the ground plane y = @p groundHeight, of which only the part inside the
/// slot's map (its orthographic prism or perspective pyramid, unbounded along the light) can be
/// shadowed. The whole frame when that part is unbounded on screen or reaches behind the camera,
/// and when the light is not above the ground (the lookup returns 0 there, not 1, for a ground
/// facing away from it). Pure (no GL): test_render_shadow_mask checks it.
PixelRect shadowReceiverRect(const ShadowSlot& slot, const MeshBounds& bounds, bool ground,
                             float groundHeight, const glm::mat4& viewProj, int width, int height);

/// The pixels both @p a and @p b hold (empty: width or height 0).
PixelRect intersection(const PixelRect& a, const PixelRect& b);

/// The texels of a mask at @p downsample (@p maskWidth x @p maskHeight; texel t stands for pixel
/// downsample x t: render/stage_interface.h's kStageDownsample, kNavigatingStageDownsample) that
/// the pixels of @p frameRect read when they upsample it. Pure: test_render_shadow_mask.
PixelRect maskRect(const PixelRect& frameRect, int maskWidth, int maskHeight,
                   int downsample = kStageDownsample);

/// The size of a mask at @p downsample for a frame @p fullSize pixels wide (or high), rounded up.
constexpr int maskSize(int fullSize, int downsample) {
    return (fullSize + downsample - 1) / downsample;
}

class ShadowMaskPass {
public:
    ShadowMaskPass() = default;
    /// Needs the renderer's context current.
    ~ShadowMaskPass();
    ShadowMaskPass(const ShadowMaskPass&) = delete;
    ShadowMaskPass& operator=(const ShadowMaskPass&) = delete;

    bool build(std::string* error);
    int compileCount() const { return m_compileCount; }

    /// Draws the masks of @p slots for a @p width x @p height frame into @p framebuffer
    /// (FrameTargets::shadowMaskFramebuffer(): the mask, its key, the ground's mask and the
    /// depth that marks unsettled texels), cleared to 1 first; the ground's passes only with
    /// @p ground. Expects the frame and stage blocks, the G-buffer's textures and the shadow maps
    /// bound. Returns the slot passes drawn (one per slot whose receivers are on screen). Leaves
    /// the depth test, scissor and blending disabled and every colour channel writable; the
    /// viewport is the mask's.
    /// Without @p settle every texel is filtered (the same masks: the reference of the tests).
    /// @p bentNormals: some drawn material bends its shading normal; the mesh's passes then
    /// offset those receivers along the face's normal (from the depth), not the bent one.
    /// @p downsample: the masks' (maskSize()), the StageBlock's counts.y.
    int run(unsigned framebuffer, const std::vector<ShadowSlot>& slots, const MeshBounds& bounds,
            bool ground, float groundHeight, const glm::mat4& viewProj, int width, int height,
            int downsample, unsigned emptyVao, bool settle = true, bool bentNormals = true);
    /// The last run's texels drawn (the settle passes' scissors) and, of those, the ones its
    /// lookup passes filtered (GL_SAMPLES_PASSED; waits for the GPU).
    void lastTexels(long long* texels, long long* filtered) const;

private:
    /// shadow_mask.frag's programs: for the ground where each texel's view ray meets it, and
    /// for the mesh's own texels, a settle pass (the texels the depth bounds settle) and the
    /// lookup where they do not.
    /// The mesh's passes twice: without and with the face normal for bent materials.
    enum Pass {
        kGroundSettle,
        kGroundLookup,
        kMeshSettle,
        kMeshLookup,
        kMeshSettleBent,
        kMeshLookupBent,
        kPassCount
    };
    void draw(Pass pass, int slot, bool settle);

    ShaderProgram m_programs[kPassCount];
    int m_compileCount = 0;
    /// One occlusion query per lookup pass drawn (two per slot at most).
    static constexpr int kMaxQueries = 2 * kMaxShadowLights;
    unsigned m_queries[kMaxQueries] = {};
    int m_queriesUsed = 0;
    long long m_texels = 0;
};

} // namespace velvet::render
