#pragma once
/// @file post_bench.h
/// Post-chain measurements for `velvet bench` (app/command_bench.cpp calls this; DESIGN.md,
/// "Measuring": medians and ratios in one process). Needs a current OpenGL 4.5 core context.

#include <string>
#include <utility>
#include <vector>

namespace velvet::render {

/// Medians of @p frames frames each, wall clock with glFinish (llvmpipe's timer queries measure
/// submission, not execution).
struct PostBenchReport {
    double frameMs = 0;       ///< the default scene with the default chain, at `lights` lights
    double frameNoPostMs = 0; ///< the same frame with an empty chain
    /// (frameMs − frameNoPostMs) / frameMs; the target is ≤ 0.35.
    double postChainShare = 0;
    double bloomMs = 0;       ///< the bloom effect alone on a width × height HDR image
    double gauss9Ms = 0;      ///< one full-resolution separable 9-tap gaussian on the same image
    double bloomVsGauss9 = 0; ///< bloomMs / gauss9Ms; target ≤ 0.75
    /// Each catalogue effect alone (defaults), per chain step ("tonemap+vignette" when fused).
    std::vector<std::pair<std::string, double>> effectMs;
};

/// Measures at @p width × @p height with @p lights point lights added to the default scene.
/// False + message on a GL or shader failure.
bool measurePostChain(int width, int height, int lights, int frames, PostBenchReport& report,
                      std::string* error);

} // namespace velvet::render
