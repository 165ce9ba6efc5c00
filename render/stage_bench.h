#pragma once
/// @file stage_bench.h
/// `velvet bench`'s look-dev stage figures (docs/shadows.md, BENCHMARKS.md): the shader ball on a
/// shadow-catching ground under the key light at the bench's size, frames with the stage off,
/// with one shadowed light, and with shadows and ambient occlusion, interleaved in one process.

#include <string>

namespace velvet::render {

struct StageBenchReport {
    double frameOffMs = 0;    ///< wall clock: no shadow, no occlusion (the ground drawn)
    double frameShadowMs = 0; ///< one shadowed directional light (maps cached, as an orbit)
    double frameStageMs = 0;  ///< shadows and ambient occlusion (every timed frame an orbit step)
    /// (The three orbit frames are drawn as the editor draws them while the camera moves.)
    /// Shadows and occlusion in a frame after a material value edit (the base colour), which
    /// keeps the last frame's occlusion (render/ao_pass.h); and the frames that kept it.
    double frameStageValueEditMs = 0;
    int occlusionKeptFrames = 0;
    /// The shadows-and-occlusion frame with the occlusion upsampled on its own
    /// (FrameSettings::packOcclusion off: the "before" of its ride in the shadow masks), and
    /// its overhead over frameOffMs.
    double frameStageOwnUpsampleMs = 0, stageOwnUpsampleOverhead = 0;
    double shadowOverhead = 0; ///< frameShadowMs / frameOffMs - 1
    double stageOverhead = 0;  ///< frameStageMs / frameOffMs - 1
    double shadowMapMs = 0;    ///< GPU time of drawing the shadow map (a light or mesh edit)
    double occlusionMs = 0;    ///< GPU time of the occlusion passes
    double shadowMaskMs = 0;   ///< GPU time of the screen-space shadow mask (render/shadow_mask.h)
    /// The same three frames by the process's CPU time (getrusage: every llvmpipe thread), which
    /// other processes' load does not inflate the way it does wall-clock time (BENCHMARKS.md).
    double cpuOffMs = 0, cpuShadowMs = 0, cpuStageMs = 0;
    double cpuShadowOverhead = 0; ///< cpuShadowMs / cpuOffMs - 1
    double cpuStageOverhead = 0;  ///< cpuStageMs / cpuOffMs - 1
    /// The shadowed frame with every shadow-mask texel filtered (FrameSettings::settleShadows
    /// off: what the maps' depth bounds save), CPU time, and its overhead over cpuOffMs.
    double cpuShadowUnsettledMs = 0, cpuShadowUnsettledOverhead = 0;
    /// The shadowed frame's shadow-mask texels and the share of them the lookup filtered.
    double shadowMaskTexels = 0, shadowMaskFilteredShare = 0;
    /// The orbit frames above are the editor's while the camera moves (FrameSettings::navigating:
    /// the masks and the occlusion at a quarter); these are the same frames with the stage at
    /// its resolution at rest (half), their overheads over frameOffMs and their passes' GPU time.
    double frameShadowRestMs = 0, frameStageRestMs = 0;
    double shadowRestOverhead = 0, stageRestOverhead = 0;
    double shadowMaskRestMs = 0, occlusionRestMs = 0;
    /// The editor's refinement at rest of the shadowed, occluded stage (frames 1..15 of a
    /// progressive mean, wall clock): with the mesh's light traced in screen space
    /// (FrameSettings::screenSpaceReflections; each frame reading the frame before's light) and
    /// without, alternated; and the overhead.
    double refineTracedMs = 0, refineUntracedMs = 0, refineTracedOverhead = 0;
};

/// Median of @p frames frames each; needs a current context. False + message on failure.
bool measureStage(int width, int height, int frames, StageBenchReport& report, std::string* error);

} // namespace velvet::render
