#include "render/render_job.h"

#include "core/frame_pattern.h"
#include "core/image.h"
#include "core/image_ops.h"
#include "core/video_encoder.h"
#include "render/gbuffer.h"
#include "render/headless_context.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <epoxy/gl.h>
#include <filesystem>
#include <time.h>
#include <unistd.h>

namespace velvet::render {
namespace fs = std::filesystem;
namespace {

std::string lowerExtension(const std::string& file) {
    std::string ext = fs::path(file).extension().string();
    for (char& c : ext)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

bool folderExists(const std::string& file, std::string* message) {
    const fs::path folder =
        fs::path(file).parent_path().empty() ? fs::path(".") : fs::path(file).parent_path();
    std::error_code ec;
    if (fs::is_directory(folder, ec))
        return true;
    *message = file + ": the folder '" + folder.string() + "' does not exist";
    return false;
}

/// The first three channels of @p rgba (the files hold opaque colour).
Image toRgb(const Image& rgba) {
    Image out(rgba.width, rgba.height, 3);
    for (int y = 0; y < rgba.height; ++y)
        for (int x = 0; x < rgba.width; ++x) {
            const glm::vec4 p = rgba.rgba(x, y);
            float* o = out.at(x, y);
            o[0] = p.r, o[1] = p.g, o[2] = p.b;
        }
    return out;
}

/// A folder of its own under the system's temporary folder, removed with its contents at the
/// end of the scope (the frames of a --video with no -o).
struct TemporaryFolder {
    fs::path path;
    bool make(std::string* error) {
        std::error_code ec;
        std::string name = (fs::temp_directory_path(ec) / "velvet-turntable-XXXXXX").string();
        if (!::mkdtemp(name.data())) {
            *error = "cannot make a temporary folder for the frames: " + name;
            return false;
        }
        path = name;
        return true;
    }
    ~TemporaryFolder() {
        std::error_code ec;
        if (!path.empty())
            fs::remove_all(path, ec);
    }
};

} // namespace

std::string nonFiniteReason(const Image& image) {
    size_t bad = 0, first = 0;
    for (size_t i = 0; i < image.pixels.size(); ++i)
        if (!std::isfinite(image.pixels[i]) && bad++ == 0)
            first = i / size_t(std::max(1, image.channels));
    if (bad == 0)
        return {};
    const size_t w = size_t(std::max(1, image.width));
    return std::to_string(bad) +
           " channel values of the image are not finite (NaN or infinity), "
           "the first at pixel (" +
           std::to_string(first % w) + ", " + std::to_string(first / w) +
           "): a value in the scene is beyond what the renderer can carry (an environment, light "
           "or camera value far out of range)";
}

RenderJobCheck checkRenderJob(const RenderJob& job, std::string* message) {
    std::string ignored;
    std::string& why = message ? *message : ignored;
    const FrameSettings& s = job.settings;
    if (s.width < 1 || s.height < 1 || s.width > 8192 || s.height > 8192) {
        why = "the size must be 1 to 8192 pixels a side, got " + std::to_string(s.width) + "x" +
              std::to_string(s.height);
        return RenderJobCheck::Usage;
    }
    if (job.supersample < 1 || job.supersample > kMaxSupersample) {
        why = "supersampling takes 1 to " + std::to_string(kMaxSupersample) +
              " samples per pixel side, got " + std::to_string(job.supersample);
        return RenderJobCheck::Usage;
    }
    if (const long long n = job.supersample,
        drawn = (long long)s.width * n * (long long)s.height * n;
        drawn > kMaxSupersampledPixels) {
        why = "supersampling " + std::to_string(s.width) + "x" + std::to_string(s.height) + " by " +
              std::to_string(n) + " draws " + std::to_string(s.width * n) + "x" +
              std::to_string(s.height * n) + " pixels, more than the 8192x8192 a frame may have: " +
              "lower the size or the supersampling";
        return RenderJobCheck::Usage;
    }
    if (job.frames < 0 || job.frames > kMaxTurntableFrames) {
        why = "a turntable has 1 to " + std::to_string(kMaxTurntableFrames) + " frames, got " +
              std::to_string(job.frames);
        return RenderJobCheck::Usage;
    }
    if (job.frames == 0) {
        const std::string ext = lowerExtension(job.output);
        if (ext != ".png" && ext != ".exr") {
            why = "the image must end in .png or .exr, got '" + job.output + "'";
            return RenderJobCheck::Usage;
        }
        if (!job.video.empty()) {
            why = "a video needs a turntable (frames); a still is one image";
            return RenderJobCheck::Usage;
        }
        return folderExists(job.output, &why) ? RenderJobCheck::Ok : RenderJobCheck::BadInput;
    }
    if (job.output.empty() && job.video.empty()) {
        why = "a turntable needs a frame pattern (e.g. out/%03d.png) or a video";
        return RenderJobCheck::Usage;
    }
    if (job.fps < 1 || job.fps > 240) {
        why = "the frame rate must be 1 to 240 frames a second, got " + std::to_string(job.fps);
        return RenderJobCheck::Usage;
    }
    if (!job.output.empty()) {
        if (!parseFramePattern(job.output, &why))
            return RenderJobCheck::BadInput;
        const std::string ext = lowerExtension(job.output);
        if (ext != ".png" && ext != ".exr") {
            why = "'" + job.output + "': the frames must be .png or .exr files";
            return RenderJobCheck::BadInput;
        }
        if (!job.video.empty() && ext != ".png") {
            why = "'" + job.output + "': a video is encoded from .png frames (8-bit, display " +
                  "encoded); .exr frames are scene-linear";
            return RenderJobCheck::BadInput;
        }
        if (!folderExists(job.output, &why))
            return RenderJobCheck::BadInput;
    }
    if (!job.video.empty()) {
        if (!isVideoExtension(job.video)) {
            why = "'" + job.video + "': the video must end in .mp4, .mov or .mkv";
            return RenderJobCheck::BadInput;
        }
        if (!folderExists(job.video, &why))
            return RenderJobCheck::BadInput;
        if (findProgram("ffmpeg").empty()) {
            why = ffmpegMissingMessage();
            return RenderJobCheck::BadInput;
        }
    }
    return RenderJobCheck::Ok;
}

void RenderJobTimings::add(const std::string& phase, double ms, double cpuMs) {
    for (size_t i = 0; i < phases.size(); ++i)
        if (phases[i].first == phase) {
            phases[i].second += ms;
            cpuPhases[i].second += cpuMs;
            return;
        }
    phases.emplace_back(phase, ms);
    cpuPhases.emplace_back(phase, cpuMs);
}

double processCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

RenderJobStatus runRenderJob(const Scene& sceneIn, const RenderJob& job,
                             const std::function<bool(const RenderJobProgress&)>& progress,
                             std::string* error, Problems* problems, RenderJobTimings* timings) {
    // Each phase's wall-clock time since the last lap (finish() waits for the GPU where a
    // phase's work would otherwise spill into the next).
    auto lapStart = std::chrono::steady_clock::now();
    double lapCpu = timings ? processCpuMs() : 0.0;
    const auto lap = [&](const char* phase) {
        const auto now = std::chrono::steady_clock::now();
        if (timings) {
            glFinish();
            const double cpu = processCpuMs();
            timings->add(phase,
                         std::chrono::duration<double, std::milli>(
                             std::chrono::steady_clock::now() - lapStart)
                             .count(),
                         cpu - lapCpu);
            lapCpu = cpu;
        }
        lapStart = timings ? std::chrono::steady_clock::now() : now;
    };
    std::string ignored;
    std::string& why = error ? *error : ignored;
    if (checkRenderJob(job, &why) != RenderJobCheck::Ok)
        return RenderJobStatus::Failed;
    const auto start = std::chrono::steady_clock::now();
    const bool still = job.frames == 0;
    const int total = still ? 1 : job.frames;

    TemporaryFolder temporary;
    std::string pattern = job.output;
    if (!still && pattern.empty()) {
        if (!temporary.make(&why))
            return RenderJobStatus::Failed;
        pattern = (temporary.path / "%05d.png").string();
    }
    std::optional<FramePattern> frames;
    if (!still)
        frames = parseFramePattern(pattern, &why);

    // The frame's camera is the scene's (the editor hands its orbit in settings.camera), turned
    // with the rest of the scene by the turntable.
    Scene scene = sceneIn;
    FrameSettings settings = job.settings;
    if (settings.camera) {
        scene.camera = *settings.camera;
        settings.camera.reset();
    }
    // Supersampled: drawn larger, each written image the box-filtered mean of its samples.
    const int ss = job.supersample;
    settings.width *= ss;
    settings.height *= ss;
    // A supersampled still has the viewport at rest's time to spare: its reflections sampled too,
    // each of a pixel's samples another rotation of the set (FrameSettings::reflectionSamples).
    if (ss > 1) {
        settings.reflectionSamples = kRefinementReflectionSamples;
        settings.reflectionSampleTotal = kRefinementReflectionSamples * ss * ss;
        settings.reflectionSampleBlock = ss;
    }

    std::unique_ptr<HeadlessContext> context;
    if (!HeadlessContext::isAnyContextCurrent()) {
        context = HeadlessContext::create(&why);
        if (!context) {
            why = "rendering failed: " + why;
            return RenderJobStatus::Failed;
        }
    }
    lap("context");
    RenderJobStatus status = RenderJobStatus::Done;
    {
        // Renderer and target die inside this scope, with the context still current.
        Renderer renderer;
        const auto renderFailed = [&] {
            why = "rendering failed: " + why;
            return RenderJobStatus::Failed;
        };
        if (!renderer.initialize(&why))
            return renderFailed();
        if (job.colorManagement)
            renderer.setColorManagement(job.colorManagement);
        lap("renderer");
        renderer.setScene(scene, problems);
        lap("scene upload");
        renderer.finishEnvironment(); // one bake for every frame
        renderer.finishGraph();
        lap("environment bake");
        ColorTarget target;
        if (!target.resize(settings.width, settings.height, GL_RGBA8, &why))
            return renderFailed();
        const bool exr = lowerExtension(pattern) == ".exr";
        const float time0 = settings.time;
        for (int i = 0; i < total; ++i) {
            if (!still) {
                // Only the camera, lights and environment rotation change: nothing is uploaded
                // again but the lights (the rotation is a uniform).
                const Scene turned =
                    turntableScene(scene, job.mode, turntableAngleDeg(i, job.frames));
                renderer.update(turned,
                                ScenePart::Camera | ScenePart::Lights | ScenePart::Environment,
                                problems);
                // Animated effects (grain, the FBM background) move on with the video's clock.
                settings.time = time0 + float(i) / float(job.fps);
            }
            if (!renderer.render(settings, target.framebuffer(), &why))
                return renderFailed();
            lap("frame");
            // The scene-linear image is always read: it is where a NaN or an infinity shows (the
            // 8-bit display image has already turned them into 0 or 1).
            const Image linear = renderer.readLinear();
            if (const std::string bad = nonFiniteReason(linear); !bad.empty()) {
                why = "rendering failed" +
                      (still ? std::string() : " at frame " + std::to_string(i)) + ": " + bad +
                      "; " + (i == 0 ? "nothing was written" : "the frames before it were written");
                return RenderJobStatus::Failed;
            }
            const std::string file = still ? job.output : framePath(*frames, i);
            const bool linearFile = still ? lowerExtension(job.output) == ".exr" : exr;
            // A .png is filtered after the display step (tone curve and encoding), as renderers
            // resolve samples for display: a bright edge stays a clean ramp instead of one
            // unclipped sample dominating its pixel; an .exr is filtered in scene-linear.
            const Image written =
                toRgb(boxDownsample(linearFile ? linear : renderer.readDisplay(), ss));
            lap("read back");
            if (!writeImage(file, written, linearFile ? PixelFormat::Half : PixelFormat::UInt8,
                            &why))
                return RenderJobStatus::Failed;
            lap("write");
            if (progress) {
                RenderJobProgress p;
                p.done = i + 1;
                p.total = total;
                p.elapsedSeconds =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                p.etaSeconds = p.elapsedSeconds / double(p.done) * double(total - p.done);
                p.lastFile = file;
                if (!progress(p)) {
                    status = RenderJobStatus::Cancelled;
                    break;
                }
            }
        }
        if (problems) // no OCIO config, no encoding view: reported once, never printed here
            for (Problem& p : renderer.takeWarnings().items)
                problems->items.push_back(std::move(p));
    }
    if (status == RenderJobStatus::Done && !job.video.empty()) {
        if (progress) {
            RenderJobProgress p;
            p.done = p.total = total;
            p.encoding = true;
            p.elapsedSeconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (!progress(p))
                return RenderJobStatus::Cancelled;
        }
        if (!encodeVideo(pattern, job.frames, job.fps, job.video, &why))
            return RenderJobStatus::Failed;
    }
    return status;
}

} // namespace velvet::render
