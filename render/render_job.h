#pragma once
/// @file render_job.h
/// Stills and turntables written to files: the one code path `velvet render` (--turntable,
/// --video) and the editor's File > Render… share (docs/turntable.md). One renderer and one
/// environment bake serve every frame; each frame is checked for non-finite values, written
/// atomically (core/image.h) and reported to a progress callback that may cancel the rest.

#include "core/diagnostics.h"
#include "core/scene.h"
#include "core/turntable.h"
#include "render/renderer.h"

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace velvet {
class ColorManagement;
}

namespace velvet::render {

struct RenderJob {
    /// Size (1 to 8192 a side), exposure, tone mapper, view, time, … of every frame.
    /// FrameSettings::camera, when set, replaces the scene's camera (the editor's orbit).
    FrameSettings settings;
    std::shared_ptr<const ColorManagement> colorManagement; ///< null: the default config
    /// 0: a still written to `output`. 1 or more: a turntable of that many frames, frame i turned
    /// by 360 i / frames degrees (core/turntable.h) and written to framePath(output, i).
    int frames = 0;
    TurntableMode mode = TurntableMode::Mesh;
    /// A still: a .png (8-bit, display encoded) or .exr (linear half) file. A turntable: a
    /// pattern such as "out/%03d.png" (core/frame_pattern.h), or empty when `video` is set (the
    /// frames then go to a temporary folder removed afterwards).
    std::string output;
    /// A turntable's video (.mp4, .mov, .mkv) through ffmpeg (core/video_encoder.h); empty: none.
    /// Needs .png frames.
    std::string video;
    int fps = 30;
    /// Samples per pixel side, 1 to kMaxSupersample: each frame drawn this many times larger
    /// each way and box-filtered down (core/image_ops.h boxDownsample), so edges are
    /// anti-aliased; it costs about its square in time. The drawn frame may hold at most
    /// kMaxSupersampledPixels.
    int supersample = 1;
};

inline constexpr int kMaxSupersample = 4;
/// The largest frame a supersampled job draws: as many pixels as the largest still (8192^2).
inline constexpr long long kMaxSupersampledPixels = 8192LL * 8192LL;

/// What checkRenderJob found: a usage error (a still's extension), bad input (a bad pattern, a
/// missing folder, no ffmpeg for --video) or nothing.
enum class RenderJobCheck { Ok, Usage, BadInput };

/// Checks @p job before anything is rendered, so bad input fails fast and writes nothing:
/// the size, the frame count (at most kMaxTurntableFrames), the still's extension, the pattern
/// (one frame number in the file name, .png or .exr), the folders of the frames and the video
/// (they must exist), the video's container and ffmpeg on PATH. @p message names the value and
/// the problem.
RenderJobCheck checkRenderJob(const RenderJob& job, std::string* message);

inline constexpr int kMaxTurntableFrames = 10000;

struct RenderJobProgress {
    int done = 0;  ///< frames written
    int total = 0; ///< frames to write (1 for a still)
    double elapsedSeconds = 0;
    double etaSeconds = 0; ///< the mean time a frame took so far x the frames left
    bool encoding = false; ///< every frame is written and ffmpeg is encoding the video
    std::string lastFile;  ///< the file just written
};

enum class RenderJobStatus { Done, Cancelled, Failed };

/// Where a job's time went (`velvet render --timings`): wall-clock milliseconds per phase, in
/// order ("context", "renderer", "scene upload", "environment bake", "frame", "read back",
/// "write"); a turntable adds its frames' time to the same phases.
struct RenderJobTimings {
    std::vector<std::pair<std::string, double>> phases;
    /// The same phases' CPU time (user + system of every thread of the process, llvmpipe's
    /// included): what a loaded machine does not inflate as it does the wall clock.
    std::vector<std::pair<std::string, double>> cpuPhases;
    void add(const std::string& phase, double ms, double cpuMs = 0.0);
};

/// CPU time (user + system, every thread) of this process so far, in milliseconds.
double processCpuMs();

/// Renders and writes @p job (checked or not: it runs checkRenderJob first and fails with its
/// message). @p progress, when set, is called after each frame (and once before the video is
/// encoded); returning false cancels: the frames written so far stay, no video is made. Needs no
/// context: it makes a headless one when none is current (so the editor calls it from a worker
/// thread). Problems found while loading the scene's files (a missing texture) are warnings in
/// @p problems. Failed + @p error when the renderer fails, a frame is not finite or a write or
/// the encode fails.
RenderJobStatus runRenderJob(const Scene& scene, const RenderJob& job,
                             const std::function<bool(const RenderJobProgress&)>& progress,
                             std::string* error, Problems* problems = nullptr,
                             RenderJobTimings* timings = nullptr);

/// "" when every value of @p image is finite; else how many are not and where the first is.
std::string nonFiniteReason(const Image& image);

} // namespace velvet::render
