#pragma once
/// @file background_downsample.h
/// Render-private: the inline frame's background at a half or a quarter of the resolution
/// (issue 16).
///
/// In the inline display path (FrameSettings::displayOnly) the background pass computes, for
/// ~75 % of a preview's pixels, the view direction, the environment lookup and the whole display
/// step (tone curve, OCIO encoding, the fused post chain): 9–10 ms of a 31 ms orbit frame at
/// 1280×720 on llvmpipe (BENCHMARKS.md), all but 1.5 ms of it the per-pixel display step. When the
/// background is the prefiltered environment's blurred level or a flat colour, and every display
/// step in the chain is a smooth function of colour and position (the tone curve, colour
/// grading, vignette: no grain, no posterising), the picture it draws has no detail finer than
/// many pixels, so it is drawn into a target of a quarter of the width and height — the same
/// program, each texel standing for the full-resolution point at its centre — and the background
/// pass reads it with one bilinear fetch per pixel. A sharp HDRI is drawn at the size its own
/// texels allow (backgroundDownsampleFactor); the procedural background and grain keep the
/// full-resolution pass.

#include "core/post_chain.h"
#include "core/scene.h"
#include "render/gbuffer.h"
#include "render/shader_program.h"

#include <string>

namespace velvet::render {

/// How many times smaller each way the background of @p mode may be drawn (1: full size, 2 or 4)
/// under the display step of @p chain (null: the built-in tone curve alone). The blurred level
/// (@p prefilteredReady) and a flat colour have no fine detail: 4. The sharp HDRI has the detail
/// of its texels, @p pixelsPerTexel screen pixels each at the frame's centre (the shipped 1024-wide
/// HDRIs under a 35° camera: 7 at 720 pixels high): sampled every third of a texel or closer,
/// the bilinear upsample of the bilinearly filtered texels differs from them only next to a
/// texel's edge, by a twelfth of the slope's change there at most, so 4 from 12 pixels a texel, 2
/// from 6, else 1. The procedural background, and a chain with grain or posterising, 1.
int backgroundDownsampleFactor(BackgroundMode mode, bool prefilteredReady, const PostChain* chain,
                               float pixelsPerTexel);

class BackgroundDownsample {
public:
    bool build(std::string* error);
    int compileCount() const { return m_compileCount; }

    /// Draws @p smallProgram (lighting.frag's background with BACKGROUND_DOWNSAMPLE @p factor:
    /// the display step's inputs already bound) into a target @p factor times smaller each way,
    /// then the upsampled picture into every pixel of @p displayFramebuffer (@p width x
    /// @p height): the surfaces' pass must draw the mesh's pixels after it. Leaves the depth test
    /// disabled. False + message when the target cannot be made.
    bool draw(const ShaderProgram& smallProgram, int factor, unsigned displayFramebuffer, int width,
              int height, std::string* error);

private:
    ShaderProgram m_upsample;
    ColorTarget m_small;
    unsigned m_smallGeneration = 0;
    int m_compileCount = 0;
};

} // namespace velvet::render
