// velvet bench --frame: the steady preview frame of the scene the forward peer draws (issue 16,
// bench/peers/three): Velvet's default scene — the unit sphere, the default camera, crimson
// velvet, the studio HDRI for light and background, the key light (its shadow off: the peer casts
// none) — with a post chain of the PBR Neutral tone map only. The figure is the median wall-clock
// time of a frame to its last timer query (the frame has finished on the GPU), the same method as
// `velvet bench`'s frame_nolights_wall_ms; the passes are GPU timer queries. The frame is drawn
// as the editor's viewport draws it: display only (FrameSettings::displayOnly: the tone map
// inside the lighting pass), after a material value edit (a slider dragged: each frame changes
// the roughness, so the background's pixels are kept, render/frame_reuse.h, and, the velvet's
// values being the same at every pixel, its G-buffer: gbuffer_kept_frames). Beside it, in
// turn, the same frame while the camera orbits (orbit_: half a degree a frame, every pixel
// drawn), through the scene-linear target with the tone map a pass of its own (hdr_), and with
// the generic lighting program (every term and lobe at run time, generic_), and as the editor
// refines a still view (refine_: each frame jittered and folded into the progressive mean,
// render/progressive_accumulation.h), and the value edit drawing its G-buffer again
// (gbuffer_drawn_), so each gain and cost is measured on the same machine state.
#include "app/cli.h"
#include "core/document_io.h"
#include "core/post_effects.h"
#include "render/headless_context.h"
#include "render/offscreen.h"
#include "render/progressive_accumulation.h"
#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <iomanip>
#include <iostream>

namespace velvet::cli {
namespace {

/// CPU time of the whole process (llvmpipe's rasteriser threads included), in ms. On a machine
/// whose other processes compete for the cores a frame's wall time swings with them; the CPU
/// time the frame's work takes does far less (llvmpipe's threads spin little: they wait on
/// condition variables).
double processCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

} // namespace

int runFrameBench(bool json, bool quick) {
    std::string error;
    auto context = render::HeadlessContext::create(&error);
    if (!context) {
        std::cerr << "velvet bench: no headless OpenGL context: " << error << "\n";
        return RenderFailure;
    }
    const int width = quick ? 320 : 1280, height = quick ? 180 : 720, frames = quick ? 5 : 21;
    // Two renderers, alternate frames: the lighting pass specialised to the frame (the default)
    // and the generic one, so both see the same machine state (render/lighting_features.h).
    enum class Change { ValueEdit, Orbit, Refine };
    struct Variant {
        const char* name;
        bool specialised;
        bool displayOnly;
        Change change;
        render::Renderer renderer;
        std::vector<double> wall, cpu, gbuffer, lighting, post;
        int backgroundKept = 0;
        int gbufferKept = 0; ///< frames that kept the G-buffer (a value edit: FramePasses)
    };
    Variant variants[6] = {
        {"", true, true, Change::ValueEdit, {}, {}, {}, {}, {}, {}},
        {"orbit_", true, true, Change::Orbit, {}, {}, {}, {}, {}, {}},
        {"hdr_", true, false, Change::ValueEdit, {}, {}, {}, {}, {}, {}},
        {"generic_", false, false, Change::ValueEdit, {}, {}, {}, {}, {}, {}},
        {"refine_", true, true, Change::Refine, {}, {}, {}, {}, {}, {}},
        // The value edit drawing its G-buffer again (FrameSettings::keepGBuffer
        // off): what keeping it saves.
        {"gbuffer_drawn_", true, true, Change::ValueEdit, {}, {}, {}, {}, {}, {}}};
    render::OffscreenTarget target;
    if (!target.resize(width, height, &error)) {
        std::cerr << "velvet bench: " << error << "\n";
        return RenderFailure;
    }
    for (Variant& v : variants) {
        if (!v.renderer.initialize(&error)) {
            std::cerr << "velvet bench: renderer initialisation failed: " << error << "\n";
            return RenderFailure;
        }
        v.renderer.setSpecialisedPrograms(v.specialised);
        v.renderer.setScene(forwardPeerScene());
        v.renderer.finishEnvironment(); // the bake runs in slices across frames: not measured
        v.renderer.finishGraph();
    }
    render::FrameSettings fs;
    fs.width = width;
    fs.height = height;
    Scene edited = forwardPeerScene();
    const float roughness = edited.material.scalar(ParamId::Roughness);
    for (int i = 0; i < frames + 2; ++i)
        for (Variant& v : variants) {
            fs.displayOnly = v.displayOnly;
            fs.keepGBuffer = &v != &variants[5];
            // What changed since the last frame: a value (the roughness, by turns 1 % either
            // side) or the camera (the yaw).
            fs.camera.reset();
            fs.accumulation = -1;
            fs.jitter = glm::vec2(0.0f);
            fs.reflectionSamples = 0;
            if (v.change == Change::Refine) { // the editor's still view: one more frame of its mean
                fs.accumulation = i % render::kRefinementFrames;
                fs.jitter = render::progressiveJitter(fs.accumulation);
                fs.reflectionSamples = render::kRefinementReflectionSamples;
                fs.reflectionSampleTotal =
                    render::kRefinementFrames * render::kRefinementReflectionSamples;
                fs.reflectionSampleSet = fs.accumulation;
            } else if (v.change == Change::Orbit) {
                Camera camera = edited.camera;
                camera.yawDeg += 0.5f * float(i);
                fs.camera = camera;
            } else if (i >= 2) { // the warm-up builds the specialised programs (no edit)
                edited.material.setScalar(ParamId::Roughness, roughness * (i % 2 ? 1.01f : 0.99f));
                v.renderer.update(edited, ScenePart::MaterialValues);
            }
            const auto start = std::chrono::steady_clock::now();
            const double cpuStart = processCpuMs();
            if (!v.renderer.render(fs, target.framebuffer(), &error)) {
                std::cerr << "velvet bench: rendering failed: " << error << "\n";
                return RenderFailure;
            }
            const render::FrameTimings t = v.renderer.lastTimings(); // waits: frame finished
            const double cpuMs = processCpuMs() - cpuStart;
            const double ms =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count();
            if (i < 2) // warm-up: llvmpipe compiles a program's machine code at its first draw
                continue;
            v.wall.push_back(ms);
            v.cpu.push_back(cpuMs);
            v.gbuffer.push_back(t.gbufferMs);
            v.lighting.push_back(t.lightingMs);
            v.post.push_back(t.postMs);
            v.backgroundKept += v.renderer.lastFramePasses().backgroundKept ? 1 : 0;
            v.gbufferKept += v.renderer.lastFramePasses().gbufferKept ? 1 : 0;
        }
    std::vector<std::pair<std::string, double>> figures{
        {"width", width}, {"height", height}, {"frames", frames}};
    for (Variant& v : variants) {
        const std::string p = v.name;
        figures.emplace_back(p + "frame_wall_ms", median(v.wall));
        figures.emplace_back(p + "frame_cpu_ms", median(v.cpu));
        figures.emplace_back(p + "gbuffer_ms", median(v.gbuffer));
        figures.emplace_back(p + "lighting_ms", median(v.lighting));
        figures.emplace_back(p + "post_ms", median(v.post));
        if (v.displayOnly)
            figures.emplace_back(p + "background_kept_frames", v.backgroundKept);
        figures.emplace_back(p + "gbuffer_kept_frames", v.gbufferKept);
    }
    // What keeping the background saves: an orbit's frame against a value edit's.
    figures.emplace_back("background_kept_speedup",
                         median(variants[1].wall) / median(variants[0].wall));
    // The specialisation's gain: the generic programs against the specialised ones, both
    // through the scene-linear target; the inline display step's: that path against the frame.
    figures.emplace_back("specialised_lighting_speedup",
                         median(variants[3].lighting) / median(variants[2].lighting));
    figures.emplace_back("specialised_frame_speedup",
                         median(variants[3].wall) / median(variants[2].wall));
    figures.emplace_back("specialised_frames",
                         variants[0].renderer.lastFrameSpecialised() ? 1.0 : 0.0);
    // The inline display step's gain, both frames drawing every pixel (an orbit's frame).
    figures.emplace_back("inline_display_cpu_speedup",
                         median(variants[2].cpu) / median(variants[1].cpu));
    figures.emplace_back("inline_display_speedup",
                         median(variants[2].wall) / median(variants[1].wall));
    // A refinement frame (jittered, every pixel drawn, then folded into the mean) against an
    // orbit's frame (every pixel drawn): what the mean adds.
    figures.emplace_back("refine_vs_orbit", median(variants[4].wall) / median(variants[1].wall));
    figures.emplace_back("gbuffer_kept_speedup",
                         median(variants[5].wall) / median(variants[0].wall));
    const render::FramePasses passes = variants[0].renderer.lastFramePasses();
    figures.emplace_back("inline_display_frames", passes.inlineDisplay ? 1.0 : 0.0);
    figures.emplace_back("fullscreen_passes", passes.fullScreen);
    figures.emplace_back("orbit_fullscreen_passes",
                         variants[1].renderer.lastFramePasses().fullScreen);
    figures.emplace_back("hdr_fullscreen_passes",
                         variants[2].renderer.lastFramePasses().fullScreen);
    if (json) {
        std::cout << "{\"gl_renderer\": \"" << context->renderer() << "\"";
        for (const auto& [k, v] : figures)
            std::cout << ", \"" << k << "\": " << v;
        std::cout << "}\n";
    } else {
        std::cout << "velvet bench --frame on " << context->renderer() << "\n";
        for (const auto& [k, v] : figures)
            std::cout << "  " << std::left << std::setw(28) << k << std::right << std::setw(10)
                      << std::fixed << std::setprecision(2) << v << "\n";
    }
    return Ok;
}

} // namespace velvet::cli
