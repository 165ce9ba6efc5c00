#pragma once
/// @file reference_renderer.h
/// The offline ground truth (issue 15): a CPU Monte Carlo path tracer of the scene `velvet render`
/// draws: the same preview mesh, orbit camera, lights, environment and material, shaded through
/// the BRDF's C++ twins (core/brdf.h). Rays through Embree, threads through oneTBB (both only in
/// the .cpp). Progressive: one sample per pixel per pass; cancellable between rows. Deterministic
/// for a seed: every (pixel, sample) has its own random stream, whatever the thread count.

#include "core/diagnostics.h"
#include "core/image.h"
#include "core/scene.h"

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

namespace velvet::reference {

struct Options {
    int width = 256;
    int height = 256;
    int samplesPerPixel = 64;
    int maxBounces = 4;          ///< path vertices after the camera hit; Russian roulette from 3
    std::uint64_t seed = 1;      ///< same seed, same image
    double timeLimitSeconds = 0; ///< > 0: stop after the pass running when this much time passed
    int threads = 0;             ///< 0: oneTBB's default
    /// Called (on the calling thread) with the image so far and its coverage (Result::coverage)
    /// after passes 1, 2, 4, 8, 16, 32 and then every 32nd: the editor's Reference view shows the
    /// render as it converges.
    std::function<void(const Image& soFar, const Image& coverage, int passes)> onPassImage;
};

/// Called after each pass (on the calling thread): passes done, passes asked for.
using ProgressFn = std::function<void(int done, int total)>;

struct Result {
    Image image; ///< scene-linear RGB, row 0 at the top (as render::readLinear)
    /// One channel: the fraction of each pixel's samples whose camera ray hit the mesh (1 inside
    /// it, 0 on the background, between on its silhouette). Comparisons with the viewport weigh
    /// the material with it, not the background (which the viewport may blur).
    Image coverage;
    int passesDone = 0; ///< complete samples per pixel
    bool cancelled = false;
};

/// Renders @p scene. @p cancel (may be null) is polled between rows: when it becomes true the
/// image so far (each pixel divided by its own sample count) is returned with cancelled set.
/// False + message when the mesh cannot be built or Embree fails. Problems get warnings (a missing
/// HDRI or texture, a material graph, which the CPU does not evaluate).
bool render(const Scene& scene, const Options& options, Result& out, std::string* error,
            Problems* problems = nullptr, const ProgressFn& progress = {},
            const std::atomic<bool>* cancel = nullptr);

} // namespace velvet::reference
