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
/// Each slot's pass is scissored to the part of the frame where a receiver can lie inside the
/// slot's map (shadowReceiverRect()); the mask is cleared to 1 first, which is exactly what the
/// lookup returns for a receiver outside its map.

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

/// The texels of a half-resolution mask (@p maskWidth x @p maskHeight; texel t stands for pixel
/// 2t) that the pixels of @p frameRect read when they upsample it. Pure: test_render_shadow_mask.
PixelRect maskRect(const PixelRect& frameRect, int maskWidth, int maskHeight);

class ShadowMaskPass {
public:
    bool build(std::string* error);
    int compileCount() const { return m_compileCount; }

    /// Draws the mask of @p slots for a @p width x @p height frame into @p framebuffer (the
    /// mask's half-resolution RGBA8 colour, FrameTargets::shadowMaskFramebuffer()), cleared to 1
    /// first. Expects the frame and stage blocks, the G-buffer's textures and the shadow maps
    /// bound. Returns the slot passes drawn (one per slot whose receivers are on screen). Leaves
    /// the depth test, scissor and blending disabled and every colour channel writable; the
    /// viewport is the mask's.
    int run(unsigned framebuffer, const std::vector<ShadowSlot>& slots, const MeshBounds& bounds,
            bool ground, float groundHeight, const glm::mat4& viewProj, int width, int height,
            unsigned emptyVao);

private:
    ShaderProgram m_program;
    int m_compileCount = 0;
};

} // namespace velvet::render
