// velvet bench [--json] [--short]: renderer variants side by side in one process, one scene.
// DESIGN.md, "Measuring": medians and ratios; tests assert ratios and keys, never times.
#include "app/cli.h"
#include "core/scene_parts.h"
#include "render/gbuffer_layout.h"
#include "render/headless_context.h"
#include "render/offscreen.h"
#include "render/post_bench.h"
#include "render/renderer.h"
#include "render/stage_bench.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

namespace velvet::cli {
namespace {

const std::vector<OptionSpec> kOptions{
    {"json", 0, false, "", "print one JSON object instead of the table"},
    {"short", 0, false, "", "quick mode: 320x180, 3 frames per variant (the ctest)"},
    {"textures", 0, false, "",
     "the texture path instead: a generated 4096² map (2048² with --short) loaded cold and from "
     "the mip cache, peak memory, frames drawn while it loads"},
    {"stage", 0, false, "", "only the look-dev stage's figures (shadows, occlusion)"},
    {"gbuffer", 0, false, "",
     "only the G-buffer layouts: 24 bytes with lobe channels beside the compact 16 bytes"},
    {"frame", 0, false, "",
     "only the steady preview frame of the forward peer's scene (bench/peers/three): the default "
     "scene, key light unshadowed, PBR Neutral tone map; median of 31 frames"},
    {"help", 'h', false, "", "this text"},
};

const char* kHelp =
    "Usage: velvet bench [--json] [--short] [--stage | --gbuffer | --textures | --frame]\n"
    "Renders the default sphere at 1280x720 (--short: 320x180) headless and measures, in one\n"
    "process, the variants side by side: the three many-light paths (light volumes, tiled\n"
    "compute, brute force) at 100 and 1,000 point lights placed in a grid around the mesh with\n"
    "radii giving about 20 lights per pixel at 1,000, and the per-pass times of the frame.\n"
    "Every figure is the median of 7 frames (3 with --short). A light path's cost is the frame's\n"
    "wall-clock time (to its last timer query) minus that of the frame without point lights;\n"
    "per-pass times are GPU timer queries (misattributed between passes on llvmpipe).\n"
    "The look-dev stage: the shader ball on a shadow catcher under the key light, the frame with\n"
    "its shadow (and ambient occlusion) against without, and the shadow-map and occlusion passes;\n"
    "its frames also by the process's CPU time (*_cpu_ms, *_overhead_cpu), steadier under load.\n"
    "Its orbit frames are drawn as the editor draws full-size frames while the camera moves (the\n"
    "shadow masks and occlusion at a quarter); *_at_rest_resolution: the same frames at half.\n"
    "The G-buffer: the 24-byte layout with eight lobe channels beside the compact 16-byte one,\n"
    "alternate frames of two renderers, G-buffer + lighting time and frame time, for the default\n"
    "velvet and for a velvet with four lobe maps (which the compact layout draws as means).\n"
    "Ratios compare variants of the same process; absolute times are machine-specific.\n\n";

/// @p count point lights on a regular grid filling the box [-1.6, 1.6]^3 around the unit sphere,
/// each with radius @p radius; colours vary so the image is not flat.
std::vector<Light> lightGrid(int count, float radius) {
    const int side = int(std::ceil(std::cbrt(double(count))));
    std::vector<Light> lights;
    for (int i = 0; i < count; ++i) {
        const int x = i % side, y = (i / side) % side, z = i / (side * side);
        auto coord = [&](int k) { return -1.6f + 3.2f * (float(k) + 0.5f) / float(side); };
        Light l;
        l.type = LightType::Point;
        l.position = glm::vec3(coord(x), coord(y), coord(z));
        l.range = radius;
        l.intensity = 0.05f;
        l.color = glm::vec3(0.4f + 0.6f * float(x) / side, 0.4f + 0.6f * float(y) / side,
                            0.4f + 0.6f * float(z) / side);
        lights.push_back(l);
    }
    return lights;
}

struct Bench {
    render::Renderer renderer;
    render::OffscreenTarget target;
    Scene scene;
    int width = 1280, height = 720, frames = 7;

    /// One frame; @p wallMs is the wall-clock time until its last timer query is available.
    /// llvmpipe runs fragment work when a framebuffer is flushed, not where the timestamps
    /// are written, so its per-pass GPU times misattribute work between passes; the path
    /// comparisons use wall-clock frame times instead (the same on every driver).
    bool frame(const render::FrameSettings& fs, render::FrameTimings& t, std::string* error,
               double* wallMs = nullptr) {
        const auto start = std::chrono::steady_clock::now();
        if (!renderer.render(fs, target.framebuffer(), error))
            return false;
        t = renderer.lastTimings(); // waits for the timer queries: the frame has finished
        if (wallMs)
            *wallMs =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count();
        return true;
    }

    /// Medians over `frames` frames (after one warm-up frame) of every FrameTimings field.
    bool measure(const render::FrameSettings& fs, render::FrameTimings& out, double& wallMs,
                 std::string* error) {
        // The IBL bake runs in slices across frames; its work must not land in any figure.
        renderer.finishEnvironment();
        renderer.finishGraph(); // a structural graph change of the scene, built now
        render::FrameTimings t;
        if (!frame(fs, t, error))
            return false;
        std::vector<double> g, l, p, total, local, wall;
        for (int i = 0; i < frames; ++i) {
            double w = 0.0;
            if (!frame(fs, t, error, &w))
                return false;
            wall.push_back(w);
            g.push_back(t.gbufferMs), l.push_back(t.lightingMs), p.push_back(t.postMs);
            total.push_back(t.totalMs), local.push_back(t.localLightsMs);
        }
        out.gbufferMs = median(g), out.lightingMs = median(l), out.postMs = median(p);
        out.totalMs = median(total), out.localLightsMs = median(local);
        wallMs = median(wall);
        return true;
    }

    /// Lights per pixel averaged over the pixels the mesh covers (the lights-per-pixel view).
    bool averageLightsPerPixel(double& average, double& pairs, std::string* error) {
        render::FrameSettings fs = settings();
        fs.view = render::DebugView::Depth;
        render::FrameTimings t;
        if (!frame(fs, t, error))
            return false;
        const Image depth = renderer.readLinear();
        fs.view = render::DebugView::LightsPerPixel;
        fs.lightPath = render::LightPath::Tiled;
        if (!frame(fs, t, error))
            return false;
        const Image count = renderer.readLinear();
        double sum = 0.0;
        long covered = 0;
        for (int y = 0; y < count.height; ++y)
            for (int x = 0; x < count.width; ++x)
                if (depth.rgba(x, y).x > 0.0f) {
                    sum += count.rgba(x, y).x;
                    ++covered;
                }
        pairs = sum;
        average = covered ? sum / double(covered) : 0.0;
        return true;
    }

    render::FrameSettings settings() const {
        render::FrameSettings fs;
        fs.width = width;
        fs.height = height;
        return fs;
    }
};

std::string jsonNumber(double v) {
    if (!std::isfinite(v))
        return "null";
    std::ostringstream s;
    s << std::setprecision(6) << v;
    return s.str();
}

/// The look-dev stage's figures (issue 14, docs/shadows.md) as key/value pairs.
bool stageFigures(int width, int height, int frames,
                  std::vector<std::pair<std::string, double>>& figures, std::string* error) {
    render::StageBenchReport stage;
    if (!render::measureStage(width, height, frames, stage, error))
        return false;
    figures.emplace_back("stage_frame_off_ms", stage.frameOffMs);
    figures.emplace_back("stage_frame_shadow_ms", stage.frameShadowMs);
    figures.emplace_back("stage_frame_shadow_ao_ms", stage.frameStageMs);
    figures.emplace_back("stage_frame_shadow_ao_value_edit_ms", stage.frameStageValueEditMs);
    figures.emplace_back("stage_occlusion_kept_frames", double(stage.occlusionKeptFrames));
    figures.emplace_back("stage_shadow_overhead", stage.shadowOverhead);
    figures.emplace_back("stage_shadow_ao_overhead", stage.stageOverhead);
    figures.emplace_back("stage_frame_shadow_ao_own_upsample_ms", stage.frameStageOwnUpsampleMs);
    figures.emplace_back("stage_shadow_ao_own_upsample_overhead", stage.stageOwnUpsampleOverhead);
    figures.emplace_back("shadow_map_pass_ms", stage.shadowMapMs);
    figures.emplace_back("occlusion_pass_ms", stage.occlusionMs);
    figures.emplace_back("shadow_mask_pass_ms", stage.shadowMaskMs);
    figures.emplace_back("stage_frame_shadow_at_rest_resolution_ms", stage.frameShadowRestMs);
    figures.emplace_back("stage_frame_shadow_ao_at_rest_resolution_ms", stage.frameStageRestMs);
    figures.emplace_back("stage_shadow_overhead_at_rest_resolution", stage.shadowRestOverhead);
    figures.emplace_back("stage_shadow_ao_overhead_at_rest_resolution", stage.stageRestOverhead);
    figures.emplace_back("shadow_mask_pass_at_rest_resolution_ms", stage.shadowMaskRestMs);
    figures.emplace_back("occlusion_pass_at_rest_resolution_ms", stage.occlusionRestMs);
    figures.emplace_back("stage_refine_traced_ms", stage.refineTracedMs);
    figures.emplace_back("stage_refine_untraced_ms", stage.refineUntracedMs);
    figures.emplace_back("stage_refine_traced_overhead", stage.refineTracedOverhead);
    figures.emplace_back("stage_frame_off_cpu_ms", stage.cpuOffMs);
    figures.emplace_back("stage_frame_shadow_cpu_ms", stage.cpuShadowMs);
    figures.emplace_back("stage_frame_shadow_ao_cpu_ms", stage.cpuStageMs);
    figures.emplace_back("stage_shadow_overhead_cpu", stage.cpuShadowOverhead);
    figures.emplace_back("stage_shadow_ao_overhead_cpu", stage.cpuStageOverhead);
    figures.emplace_back("stage_frame_shadow_unsettled_cpu_ms", stage.cpuShadowUnsettledMs);
    figures.emplace_back("stage_shadow_unsettled_overhead_cpu", stage.cpuShadowUnsettledOverhead);
    figures.emplace_back("shadow_mask_texels", stage.shadowMaskTexels);
    figures.emplace_back("shadow_mask_filtered_share", stage.shadowMaskFilteredShare);
    return true;
}

} // namespace

double median(std::vector<double> v) {
    if (v.empty())
        return NAN;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int runBench(const std::vector<std::string>& argv) {
    std::string error;
    auto args = parseArguments(argv, kOptions, &error);
    if (!args || !args->positional.empty()) {
        std::cerr << "velvet bench: " << (args ? "takes no FILE" : error)
                  << "\nRun 'velvet bench --help' for usage.\n";
        return UsageError;
    }
    if (args->has("help")) {
        std::cout << kHelp << optionsHelp(kOptions);
        return Ok;
    }
    const bool json = args->has("json");
    if (args->has("textures"))
        return runTextureBench(json, args->has("short"));
    if (args->has("frame"))
        return runFrameBench(json, args->has("short"));
    auto context = render::HeadlessContext::create(&error);
    if (!context) {
        std::cerr << "velvet bench: no headless OpenGL context: " << error << "\n";
        return RenderFailure;
    }
    std::vector<std::pair<std::string, double>> figures;
    auto put = [&](const std::string& key, double v) { figures.emplace_back(key, v); };
    std::vector<std::pair<std::string, std::string>> notes; ///< string-valued keys
    int code = Ok;
    {
        Bench b;
        if (args->has("short"))
            b.width = 320, b.height = 180, b.frames = 3;
        auto failed = [&](const std::string& what) {
            std::cerr << "velvet bench: " << what << ": " << error << "\n";
            return RenderFailure;
        };
        if (!b.renderer.initialize(&error) || !b.target.resize(b.width, b.height, &error))
            return failed("renderer initialisation failed");
        // The look-dev stage: shadows and ambient occlusion on and off (--stage: only these).
        if (!args->has("gbuffer") && !stageFigures(b.width, b.height, b.frames, figures, &error))
            return failed("stage measurement failed");
        // The G-buffer layouts side by side (--gbuffer: only these).
        if (!args->has("stage") &&
            !gbufferLayoutFigures(b.width, b.height, b.frames, figures, &error))
            return failed("G-buffer layout measurement failed");
        if (args->has("stage") || args->has("gbuffer")) {
            for (const auto& [k, v] : figures)
                std::cout << (json ? "\"" + k + "\": " : "  " + k + " ") << jsonNumber(v) << "\n";
            return Ok;
        }

        // Radii for about 20 lights per pixel at 1,000 lights: start from the density estimate
        // (20 = density * 4/3 pi r^3) and correct twice by the measured average.
        const double targetAverage = 20.0;
        float radius = float(std::cbrt(targetAverage / (1000.0 / std::pow(3.2, 3)) /
                                       (4.0 / 3.0 * 3.14159265358979)));
        double avg1000 = 0.0, pairs1000 = 0.0, avg100 = 0.0, pairs100 = 0.0;
        for (int i = 0; i < 3; ++i) {
            b.scene.lights = lightGrid(1000, radius);
            b.renderer.setScene(b.scene);
            if (!b.averageLightsPerPixel(avg1000, pairs1000, &error))
                return failed("lights-per-pixel measurement failed");
            if (i < 2 && avg1000 > 0.0)
                radius *= float(std::cbrt(targetAverage / avg1000));
        }

        std::map<std::string, render::FrameTimings> t;
        std::map<std::string, double> wall;
        // The same frame without point lights: the base the light paths' costs are measured from.
        b.scene.lights.clear();
        b.renderer.setScene(b.scene);
        if (!b.measure(b.settings(), t["nolights"], wall["nolights"], &error))
            return failed("rendering failed");
        for (int count : {100, 1000}) {
            b.scene.lights = lightGrid(count, radius);
            b.renderer.setScene(b.scene);
            if (count == 100 && !b.averageLightsPerPixel(avg100, pairs100, &error))
                return failed("lights-per-pixel measurement failed");
            for (auto [name, path] : {std::pair{"volumes", render::LightPath::Volumes},
                                      std::pair{"tiled", render::LightPath::Tiled},
                                      std::pair{"brute", render::LightPath::Brute}}) {
                render::FrameSettings fs = b.settings();
                fs.lightPath = path;
                const std::string key = "lights" + std::to_string(count) + "_" + name;
                if (!b.measure(fs, t[key], wall[key], &error))
                    return failed("rendering failed");
            }
        }
        // A path's cost: its frame's wall-clock median minus the frame without point lights
        // (floored at 1 % of that frame so ratios stay finite).
        auto lightsMs = [&](const std::string& k) {
            return std::max(wall[k] - wall["nolights"], 0.01 * wall["nolights"]);
        };
        put("width", b.width);
        put("height", b.height);
        put("frames", b.frames);
        put("lights_radius_m", radius);
        put("lights1000_avg_lights_per_pixel", avg1000);
        put("lights100_avg_lights_per_pixel", avg100);
        for (const char* k : {"lights100_volumes", "lights100_tiled", "lights100_brute",
                              "lights1000_volumes", "lights1000_tiled", "lights1000_brute"})
            put(std::string(k) + "_ms", lightsMs(k));
        put("lights1000_speedup_vs_volumes",
            lightsMs("lights1000_volumes") / lightsMs("lights1000_tiled"));
        put("lights1000_speedup_vs_brute",
            lightsMs("lights1000_brute") / lightsMs("lights1000_tiled"));
        put("lights_growth_1000_vs_100",
            lightsMs("lights1000_tiled") / lightsMs("lights100_tiled"));
        put("light_pixel_pairs_ratio_1000_vs_100", pairs100 > 0 ? pairs1000 / pairs100 : NAN);
        put("frame_nolights_wall_ms", wall["nolights"]);
        put("lights_growth_1000_vs_100_volumes",
            lightsMs("lights1000_volumes") / lightsMs("lights100_volumes"));
        // The frame at 1,000 lights on the tiled path, pass by pass (GPU timer queries; on
        // llvmpipe see frame() above). "ibl" is the full-screen pass (environment + directional
        // lights), "lighting" the point-light pass.
        const render::FrameTimings& f = t["lights1000_tiled"];
        put("frame_lights1000_tiled_wall_ms", wall["lights1000_tiled"]);
        put("gbuffer_ms", f.gbufferMs);
        put("lighting_ms", f.localLightsMs);
        put("ibl_ms", f.lightingMs - f.localLightsMs);
        put("post_ms", f.postMs);
        put("total_ms", f.totalMs);

        // The post chain (issue 4): the default chain's share of a frame at 100 lights, bloom
        // against one full-resolution 9-tap gaussian, and each effect alone.
        render::PostBenchReport post;
        if (!render::measurePostChain(b.width, b.height, 100, b.frames, post, &error))
            return failed("post-chain measurement failed");
        put("post_chain_share", post.postChainShare);
        put("post_frame_ms", post.frameMs);
        put("post_frame_no_chain_ms", post.frameNoPostMs);
        put("bloom_ms", post.bloomMs);
        put("gauss9_ms", post.gauss9Ms);
        put("bloom_vs_gauss9", post.bloomVsGauss9);
        for (const auto& [effect, ms] : post.effectMs) {
            std::string key = "effect_" + effect + "_ms";
            for (char& c : key)
                if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_')
                    c = '_';
            put(key, ms);
        }

        // Responsiveness (issue 5): 100 value edits through Renderer::update compile no shader;
        // an edit reaches a finished frame (update + render + the frame's last timer query)
        // in param_edit_to_frame_ms (median), or at half resolution (the editor's interactive
        // render scale while a slider is dragged) in param_edit_to_frame_half_ms.
        {
            b.scene.lights.clear();
            b.renderer.setScene(b.scene);
            b.renderer.finishEnvironment();
            b.renderer.finishGraph();
            render::FrameTimings ft;
            if (!b.frame(b.settings(), ft, &error))
                return failed("rendering failed");
            const int compilesBefore = b.renderer.shaderCompileCount();
            std::vector<double> full, half;
            for (int i = 0; i < 100; ++i) {
                render::FrameSettings fs = b.settings();
                const bool reduced = i % 2 == 1;
                fs.renderScale = reduced ? 0.5f : 1.0f;
                Scene edited = b.scene;
                edited.material.setValue(ParamId::Roughness,
                                         glm::vec3(0.1f + 0.8f * float(i % 10) / 9.0f));
                const auto start = std::chrono::steady_clock::now();
                b.renderer.update(edited, ScenePart::MaterialValues);
                if (!b.frame(fs, ft, &error))
                    return failed("rendering failed");
                const double ms = std::chrono::duration<double, std::milli>(
                                      std::chrono::steady_clock::now() - start)
                                      .count();
                (reduced ? half : full).push_back(ms);
            }
            put("param_edit_recompiles", b.renderer.shaderCompileCount() - compilesBefore);
            put("param_edit_to_frame_ms", median(full));
            put("param_edit_to_frame_half_ms", median(half));
            put("param_edit_half_speedup", median(full) / std::max(1e-6, median(half)));
            // What travels as a mask (issue 11), old way and new way interleaved so both see the
            // same machine state: an orbit step as every mouse move used to be (the whole scene,
            // camera included, through setScene) against the camera as a per-frame setting; a
            // roughness edit through setScene against update(MaterialValues).
            std::vector<double> orbitWhole, orbitMask, editWhole, editMask;
            const auto timed = [&](std::vector<double>& into, auto&& work) {
                const auto start = std::chrono::steady_clock::now();
                const bool ok = work();
                into.push_back(std::chrono::duration<double, std::milli>(
                                   std::chrono::steady_clock::now() - start)
                                   .count());
                return ok;
            };
            Scene scene = b.scene;
            for (int i = 0; i < 2 * b.frames + 10; ++i) {
                Camera camera = b.scene.camera;
                camera.yawDeg += 3.0f * float(i);
                render::FrameSettings fs = b.settings();
                Scene moved = scene;
                moved.camera = camera;
                const bool ok =
                    timed(orbitWhole,
                          [&] {
                              b.renderer.setScene(moved);
                              return b.frame(fs, ft, &error);
                          }) &&
                    timed(orbitMask,
                          [&] {
                              render::FrameSettings perFrame = fs;
                              perFrame.camera = camera;
                              return b.frame(perFrame, ft, &error);
                          }) &&
                    timed(editWhole,
                          [&] {
                              scene.material.setValue(ParamId::Roughness,
                                                      glm::vec3(0.2f + 0.05f * float(i % 10)));
                              b.renderer.setScene(scene);
                              return b.frame(fs, ft, &error);
                          }) &&
                    timed(editMask, [&] {
                        scene.material.setValue(ParamId::Roughness,
                                                glm::vec3(0.25f + 0.05f * float(i % 10)));
                        b.renderer.update(scene, ScenePart::MaterialValues);
                        return b.frame(fs, ft, &error);
                    });
                if (!ok)
                    return failed("rendering failed");
            }
            put("orbit_frame_ms", median(orbitMask));
            put("orbit_frame_whole_scene_ms", median(orbitWhole));
            put("orbit_speedup_vs_whole_scene",
                median(orbitWhole) / std::max(1e-6, median(orbitMask)));
            put("param_edit_mask_ms", median(editMask));
            put("param_edit_whole_scene_ms", median(editWhole));
            put("param_edit_speedup_vs_whole_scene",
                median(editWhole) / std::max(1e-6, median(editMask)));
            // What the editor window adds per frame needs a display: tests/ui/bench_viewport
            // measures it under xvfb-run (BENCHMARKS.md, "Responsiveness").
            put("viewport_overhead_ms", NAN);
            notes.emplace_back("viewport_overhead_note",
                               "needs a display: run tests/bench_viewport under xvfb-run");
        }
    }

    if (json) {
        std::cout << "{\"gl_renderer\": \"" << context->renderer() << "\"";
        for (const auto& [k, v] : figures)
            std::cout << ", \"" << k << "\": " << jsonNumber(v);
        for (const auto& [k, v] : notes)
            std::cout << ", \"" << k << "\": \"" << v << "\"";
        std::cout << "}\n";
    } else {
        std::cout << "velvet bench on " << context->renderer() << "\n\n";
        auto figure = [&](const std::string& k) {
            for (const auto& [key, v] : figures)
                if (key == k)
                    return v;
            return 0.0;
        };
        std::cout << "point-light pass, ms   volumes     tiled     brute\n";
        for (const char* n : {"100", "1000"}) {
            std::cout << std::left << std::setw(20) << (std::string(n) + " lights") << std::right
                      << std::fixed << std::setprecision(2);
            for (const char* path : {"volumes", "tiled", "brute"})
                std::cout << std::setw(10)
                          << figure(std::string("lights") + n + "_" + path + "_ms");
            std::cout << "\n";
        }
        std::cout << "\n";
        for (const auto& [k, v] : figures)
            std::cout << "  " << std::left << std::setw(40) << k << std::right << std::setw(12)
                      << std::fixed << std::setprecision(3) << v << "\n";
    }
    return code;
}

} // namespace velvet::cli
