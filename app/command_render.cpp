// velvet render [FILE] -o OUT [--size WxH] …: headless rendering through the real deferred path.
#include "app/batch.h"
#include "app/batch_commands.h"
#include "app/cli.h"
#include "app/load_document.h"
#include "core/color_management.h"
#include "core/document_io.h"
#include "core/frame_pattern.h"
#include "core/image.h"
#include "core/image_codec.h"
#include "core/light_rigs.h"
#include "core/post_chain_io.h"
#include "core/turntable.h"
#include "render/render_job.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <sstream>
#include <unistd.h>

namespace velvet::cli {
namespace {

const std::vector<OptionSpec> kOptions{
    {"output", 'o', true, "OUT",
     "image to write: .png (8-bit, display encoded) or .exr (linear half)"},
    {"size", 's', true, "WxH", "image size in pixels (default 512x512, at most 8192 per side)"},
    {"exposure", 0, true, "EV", "exposure in stops before the tone mapping (default 0)"},
    {"tonemap", 0, true, "NAME",
     "built-in tone mapper: pbr-neutral (default), aces, reinhard or linear"},
    {"display", 0, true, "NAME", "OpenColorIO display (default: the config's default display)"},
    {"view", 0, true, "NAME",
     "OpenColorIO view, e.g. Standard, ACES, AgX, Raw; or a debug view name (as --debug-view)"},
    {"look", 0, true, "NAME", "OpenColorIO look applied before the view (a,b for several)"},
    {"debug-view", 0, true, "NAME",
     "final (default), albedo, normal, depth, roughness, metallic, position, specular, "
     "clearcoat, sheen, occlusion, emissive, material-id, lights-per-pixel (heat map), "
     "diffuse-only, specular-only, base-specular, sheen-only, clearcoat-only (lobe views: direct "
     "light only), anisotropy (direction x strength), specular-occlusion"},
    {"thumbnail", 0, false, "",
     "show a material preset as its library thumbnail does: fabrics and leather on the cloth "
     "drape, other materials on the sphere (what velvet thumbnails renders)"},
    {"light-rig", 0, true, "ID",
     "replace the scene's lights with a rig: key, three-point, softboxes, sun, stage-spot, "
     "coloured-points or environment (the HDRI alone)"},
    {"timings", 0, false, "",
     "print where the time went on stderr: start-up, scene load, renderer, environment bake, "
     "frame, read back, write (milliseconds)"},
    {"time", 0, true, "SECONDS",
     "animation time in seconds, >= 0 (default 0): film grain, night-vision grain, vaporwave "
     "static, paintbrush strokes and the procedural FBM background; the same time gives the same "
     "image"},
    {"chain", 0, true, "CHAIN.json",
     "post-effect chain preset (resources/post-chains/) replacing the scene's chain"},
    // Batches (app/batch_commands.h, docs/batch.md): several FILEs, -o a folder.
    {"format", 0, true, "png|exr", "batch: the images' type in the -o folder (default png)"},
    kJobsOption,
    kShardOption,
    {"turntable", 0, true, "FRAMES",
     "render a turntable of FRAMES frames (1 to 10000), frame i turned by 360 i / FRAMES "
     "degrees, to -o PATTERN (one frame number: out/%03d.png, from 000), and/or --video"},
    {"turntable-mode", 0, true, "MODE",
     "what turns: mesh (default; the lights and the environment stay with the camera) or light "
     "(the HDRI and the lights turn around the mesh)"},
    {"video", 0, true, "OUT.mp4",
     "also encode the turntable's frames into a video (.mp4, .mov or .mkv, H.264) with the "
     "ffmpeg program; without -o the frames go to a temporary folder"},
    {"fps", 0, true, "N", "the video's frame rate, 1 to 240 (default 30)"},
    {"supersample", 0, true, "N",
     "anti-aliasing: N x N samples a pixel, 1 to 4 (default 1), each image drawn N times larger "
     "each way and box-filtered down (about N^2 the frame time); from 2, glossy reflections are "
     "sampled as in the editor's view at rest (more time for glossy materials)"},
    {"no-screen-space-reflections", 0, false, "",
     "with --supersample 2 or more: a mesh that can see itself (the shader ball, an import) "
     "reflects the environment darkened by its occlusion instead of its own parts traced on "
     "screen (one lighting pass fewer)"},
    {"help", 'h', false, "", "this text"},
};

const char* kHelp =
    "Usage: velvet render [FILE] -o OUT [--size WxH] [--display NAME] [--view NAME] [--look NAME]\n"
    "       velvet render [FILE] --turntable FRAMES [-o out/%03d.png] [--video out.mp4]\n"
    "Renders FILE (a scene, or a material preset shown in the default scene; no FILE: the default\n"
    "scene) off screen through the deferred renderer. Needs no display.\n\n"
    "Colour: by default the image goes through the built-in Khronos PBR Neutral tone mapper\n"
    "(--tonemap picks another), then OpenColorIO's encoding for the display (--display, default\n"
    "the config's default display) from the config named by $OCIO or the shipped one. A\n"
    "tone-mapping --view (ACES, AgX, Raw) or a --look instead applies OCIO's whole display\n"
    "transform (exposure, look, display/view); a missing --view is the display's default view.\n"
    "EXR output is scene-linear either way.\n\n"
    "Batch: with several FILEs (or --jobs, --shard), -o names a folder and each FILE is rendered\n"
    "as OUT/STEM.png (--format exr: .exr) in its own process, --jobs at a time; progress on\n"
    "stderr; a failed FILE is reported and the others go on (exit 2). docs/batch.md.\n\n"
    "Turntable: --turntable FRAMES writes FRAMES images, turning the mesh (or, with\n"
    "--turntable-mode light, the HDRI and the lights) once around, with one line of progress\n"
    "per frame on stderr (frames done / total, elapsed, ETA). docs/turntable.md.\n\n";

template <typename Enum, size_t N>
bool parseName(const std::string& text, const std::pair<const char*, Enum> (&table)[N], Enum& out) {
    for (const auto& [name, value] : table)
        if (text == name) {
            out = value;
            return true;
        }
    return false;
}

const std::pair<const char*, render::ToneMapper> kToneMappers[] = {
    {"pbr-neutral", render::ToneMapper::KhronosPbrNeutral},
    {"aces", render::ToneMapper::AcesFitted},
    {"reinhard", render::ToneMapper::Reinhard},
    {"linear", render::ToneMapper::Linear},
};
const std::pair<const char*, render::DebugView> kDebugViews[] = {
    {"final", render::DebugView::Final},
    {"albedo", render::DebugView::Albedo},
    {"normal", render::DebugView::Normal},
    {"depth", render::DebugView::Depth},
    {"roughness", render::DebugView::Roughness},
    {"metallic", render::DebugView::Metallic},
    {"position", render::DebugView::Position},
    {"specular", render::DebugView::Specular},
    {"clearcoat", render::DebugView::Clearcoat},
    {"sheen", render::DebugView::Sheen},
    {"occlusion", render::DebugView::Occlusion},
    {"emissive", render::DebugView::Emissive},
    {"material-id", render::DebugView::MaterialId},
    {"lights-per-pixel", render::DebugView::LightsPerPixel},
    {"diffuse-only", render::DebugView::DiffuseOnly},
    {"specular-only", render::DebugView::SpecularOnly},
    {"base-specular", render::DebugView::BaseSpecular},
    {"sheen-only", render::DebugView::SheenOnly},
    {"clearcoat-only", render::DebugView::ClearcoatOnly},
    {"anisotropy", render::DebugView::Anisotropy},
    {"specular-occlusion", render::DebugView::SpecularOcclusion},
};

int usage(const std::string& message) {
    std::cerr << "velvet render: " << message << "\nRun 'velvet render --help' for usage.\n";
    return UsageError;
}

/// "a", "b", "c" (names may hold spaces, e.g. "Display P3").
std::string quotedList(const std::vector<std::string>& names) {
    std::string out;
    for (const auto& n : names)
        out += (out.empty() ? "\"" : ", \"") + n + "\"";
    return out.empty() ? "none" : out;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

/// The displays, views and looks of @p cm, for --help.
std::string colorManagementHelp(const ColorManagement& cm) {
    std::ostringstream s;
    s << "OpenColorIO config: " << cm.configPath().string() << "\n";
    for (const auto& display : cm.displays()) {
        s << "  display \"" << display << "\""
          << (display == cm.defaultDisplay() ? " (default)" : "") << ", views:";
        const std::string defaultView = cm.defaultView(display);
        const char* separator = " ";
        for (const auto& view : cm.views(display)) {
            s << separator << view << (view == defaultView ? " (default)" : "");
            separator = ", ";
        }
        s << "\n";
    }
    s << "  looks: " << quotedList(cm.looks()) << "\n";
    return s.str();
}

/// Checks --display, --view and --look against the OCIO config and puts the resolved names into
/// @p settings (display and view always filled in, so the renderer uses exactly what was checked).
/// Returns Ok, UsageError for an unknown name (the message lists the valid ones), or BadInput when
/// the config cannot be loaded.
int resolveColorManagement(const Arguments& args, render::FrameSettings& settings,
                           std::shared_ptr<const ColorManagement>& out) {
    if (!args.has("display") && !args.has("view") && !args.has("look"))
        return Ok;
    auto cm = std::make_shared<ColorManagement>();
    std::string error;
    if (!cm->loadDefault(&error)) {
        std::cerr << error << "\n";
        return BadInput;
    }
    const std::string config = cm->configPath().string();
    const std::string display = args.value("display", cm->defaultDisplay());
    if (!contains(cm->displays(), display))
        return usage("--display: unknown display \"" + display + "\" in " + config +
                     "; valid displays: " + quotedList(cm->displays()));
    const std::string view = args.value("view", cm->defaultView(display));
    if (!contains(cm->views(display), view))
        return usage("--view: display \"" + display + "\" has no view \"" + view + "\" in " +
                     config + "; valid views: " + quotedList(cm->views(display)));
    // OCIO's look syntax: a comma-separated list, each name optionally prefixed by + or -
    // (OCIO::LookTransform::setLooks, "look parse").
    const std::string looks = args.value("look");
    std::istringstream list(looks);
    for (std::string look; std::getline(list, look, ',');) {
        look.erase(0, look.find_first_not_of(" \t"));
        look.erase(look.find_last_not_of(" \t") + 1);
        if (!look.empty() && (look[0] == '+' || look[0] == '-'))
            look.erase(0, 1);
        if (!contains(cm->looks(), look))
            return usage("--look: unknown look \"" + look + "\" in " + config +
                         "; valid looks: " + quotedList(cm->looks()));
    }
    // A tone-mapping view (ACES, AgX, Raw) or a look is OCIO's whole transform; an encoding-only
    // view (Standard) follows the built-in curve. The message names what the user gave that
    // conflicts (an implicit default view is no reason when it only encodes).
    if (args.has("tonemap")) {
        const bool toneMappingView = !cm->isEncodingView(display, view, nullptr).value_or(false);
        std::string reasons;
        if (toneMappingView)
            reasons = args.has("view") ? "a tone-mapping --view (\"" + view + "\")"
                                       : "display \"" + display + "\"'s default view \"" + view +
                                             "\", which tone-maps,";
        if (!looks.empty())
            reasons += std::string(reasons.empty() ? "" : " and ") + "a --look (\"" + looks + "\")";
        if (!reasons.empty())
            return usage("--tonemap picks the built-in tone mapper; it cannot be combined with " +
                         reasons + ", which OpenColorIO applies instead");
    }
    settings.display = display;
    settings.displayView = view;
    settings.look = looks;
    out = std::move(cm);
    return Ok;
}

} // namespace

namespace {

/// Milliseconds from the process's start to now (Linux: /proc/self/stat's start time against
/// /proc/uptime, in clock ticks of 10 ms), or -1 where that cannot be read.
double msSinceProcessStart() {
    std::ifstream stat("/proc/self/stat"), uptime("/proc/uptime");
    std::string text((std::istreambuf_iterator<char>(stat)), {});
    const size_t paren = text.rfind(')'); // the command name may hold spaces
    double upSeconds = 0;
    if (paren == std::string::npos || !(uptime >> upSeconds))
        return -1;
    std::istringstream fields(text.substr(paren + 2));
    std::string field;
    for (int i = 3; i <= 22 && fields >> field; ++i)
        if (i == 22) // starttime, in clock ticks since boot
            return 1000.0 * (upSeconds - std::stod(field) / double(sysconf(_SC_CLK_TCK)));
    return -1;
}

struct RenderTimings {
    double beforeMainMs = -1;
    double beforeMainCpuMs = render::processCpuMs(); // at construction: the start of main
    double sceneLoadMs = 0, sceneLoadCpuMs = 0;
    std::chrono::steady_clock::time_point mainStart = std::chrono::steady_clock::now();
};

double msBetween(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

/// `--timings`: one line per phase on stderr, then the whole process's time.
void printRenderTimings(const RenderTimings& t, const render::RenderJobTimings& job) {
    std::vector<std::pair<std::string, double>> phases;
    if (t.beforeMainMs >= 0)
        phases.emplace_back("start-up (to main)", t.beforeMainMs);
    phases.emplace_back("arguments, scene load", t.sceneLoadMs);
    phases.insert(phases.end(), job.phases.begin(), job.phases.end());
    const double inMain = msBetween(t.mainStart, std::chrono::steady_clock::now());
    std::cerr << "velvet render: timings (ms, wall clock)\n";
    for (const auto& [name, ms] : phases) {
        char line[96];
        std::snprintf(line, sizeof line, "  %-24s %8.1f\n", name.c_str(), ms);
        std::cerr << line;
    }
    char line[96];
    std::snprintf(line, sizeof line, "  %-24s %8.1f\n", "total",
                  inMain + std::max(t.beforeMainMs, 0.0));
    std::cerr << line;
    // CPU time, every thread (llvmpipe's rasterisers too): the measure a shared machine does
    // not inflate. "start-up" is what the process had used when main began.
    std::cerr << "velvet render: CPU time (ms, user + system, all threads)\n";
    std::vector<std::pair<std::string, double>> cpu{{"start-up (to main)", t.beforeMainCpuMs},
                                                    {"arguments, scene load", t.sceneLoadCpuMs}};
    cpu.insert(cpu.end(), job.cpuPhases.begin(), job.cpuPhases.end());
    for (const auto& [name, ms] : cpu) {
        std::snprintf(line, sizeof line, "  %-24s %8.1f\n", (name + " cpu").c_str(), ms);
        std::cerr << line;
    }
    std::snprintf(line, sizeof line, "  %-24s %8.1f\n", "total cpu", render::processCpuMs());
    std::cerr << line;
    // OpenImageIO is loaded on first use (core/image_codec.h): a render whose environment came
    // from the disk cache and that writes a PNG never loads it.
    std::snprintf(line, sizeof line, "  %-24s %s\n", "image codec (OpenImageIO)",
                  codec::imageCodecLoaded() ? "loaded" : "not loaded");
    std::cerr << line;
}

} // namespace

int runRender(const std::vector<std::string>& argv) {
    RenderTimings timings; // --timings
    timings.beforeMainMs = msSinceProcessStart();
    std::string error;
    auto args = parseArguments(argv, kOptions, &error);
    if (!args)
        return usage(error);
    if (args->has("help")) {
        std::cout << kHelp << optionsHelp(kOptions) << "\n";
        ColorManagement cm;
        if (cm.loadDefault(&error))
            std::cout << colorManagementHelp(cm);
        else
            std::cout << "OpenColorIO: " << error << "\n";
        return Ok;
    }
    if (isRenderBatch(*args)) { // several FILEs, --jobs or --shard: one child process per FILE
        if (!args->has("output"))
            return usage("missing -o OUT");
        return runRenderBatch(*args, kOptions);
    }
    render::RenderJob job;
    if (args->has("turntable")) {
        const std::string text = args->value("turntable");
        int frames = 0;
        auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), frames);
        if (ec != std::errc() || ptr != text.data() + text.size() || frames < 1 ||
            frames > render::kMaxTurntableFrames)
            return usage("--turntable expects a number of frames from 1 to " +
                         std::to_string(render::kMaxTurntableFrames) + ", got '" + text + "'");
        job.frames = frames;
    } else {
        for (const char* name : {"turntable-mode", "video", "fps"})
            if (args->has(name))
                return usage(std::string("--") + name + " needs --turntable FRAMES");
    }
    if (args->has("turntable-mode")) {
        const auto mode = parseTurntableMode(args->value("turntable-mode"));
        if (!mode)
            return usage("--turntable-mode expects mesh or light, got '" +
                         args->value("turntable-mode") + "'");
        job.mode = *mode;
    }
    if (args->has("fps")) {
        const std::string text = args->value("fps");
        auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), job.fps);
        if (ec != std::errc() || ptr != text.data() + text.size() || job.fps < 1 || job.fps > 240)
            return usage("--fps expects 1 to 240 frames a second, got '" + text + "'");
    }
    if (args->has("supersample")) {
        const std::string text = args->value("supersample");
        auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), job.supersample);
        if (ec != std::errc() || ptr != text.data() + text.size()) // the range: checkRenderJob
            return usage("--supersample expects 1 to " + std::to_string(render::kMaxSupersample) +
                         " samples per pixel side, got '" + text + "'");
    }
    job.output = args->value("output");
    job.video = args->value("video");
    if (job.output.empty() && (job.frames == 0 || job.video.empty()))
        return usage(job.frames == 0 ? "missing -o OUT" : "missing -o PATTERN or --video OUT");
    if (args->positional.size() > 1)
        return usage("one FILE at most, got " + std::to_string(args->positional.size()));

    const std::filesystem::path out = job.output;
    std::string ext = out.extension().string();
    for (char& c : ext)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (job.frames == 0 && ext != ".png" && ext != ".exr")
        return usage("OUT must end in .png or .exr, got '" + out.string() + "'");
    // A still named with a frame number would be written under a name the user did not mean.
    if (job.frames == 0 && looksLikeFramePattern(job.output)) {
        std::cerr << out.string()
                  << ": a '%' in the name of a still; a numbered sequence needs --turntable "
                     "FRAMES\n";
        return BadInput;
    }

    render::FrameSettings settings;
    settings.width = settings.height = 512;
    if (args->has("size") && !parseSize(args->value("size"), settings.width, settings.height))
        return usage("--size expects WxH with each side in [1, 8192], got '" + args->value("size") +
                     "'");
    if (args->has("exposure") && !parseFloat(args->value("exposure"), settings.exposureEv))
        return usage("--exposure expects a number, got '" + args->value("exposure") + "'");
    if (args->has("time") &&
        (!parseFloat(args->value("time"), settings.time) || settings.time < 0.0f))
        return usage("--time expects a number of seconds >= 0, got '" + args->value("time") + "'");
    if (args->has("tonemap") &&
        !parseName(args->value("tonemap"), kToneMappers, settings.toneMapper))
        return usage("--tonemap: unknown tone mapper '" + args->value("tonemap") + "'");
    if (args->has("debug-view") &&
        !parseName(args->value("debug-view"), kDebugViews, settings.view))
        return usage("--debug-view: unknown debug view '" + args->value("debug-view") + "'");
    // `--view NAME` also names a debug view (albedo, normal, …, as the renderer's debug views are
    // asked for elsewhere): OCIO's views are capitalised (Standard, ACES, AgX, Raw), the debug
    // views lowercase, so a name that is a debug view is one and leaves OCIO's view alone.
    if (args->has("view") && !args->has("debug-view") &&
        parseName(args->value("view"), kDebugViews, settings.view))
        args->options.erase("view");
    std::shared_ptr<const ColorManagement> colorManagement;
    if (const int code = resolveColorManagement(*args, settings, colorManagement); code != Ok)
        return code;

    settings.screenSpaceReflections = !args->has("no-screen-space-reflections");
    // Check the destination before the (slow) render so bad input writes nothing and fails fast.
    job.settings = settings;
    job.colorManagement = colorManagement;
    if (job.frames == 0) {
        if (const int code = checkOutputFolder(out); code != Ok)
            return code;
    }
    std::string why;
    const render::RenderJobCheck check = render::checkRenderJob(job, &why);
    if (check == render::RenderJobCheck::Usage)
        return usage(why); // e.g. the size and the supersampling together too large
    if (check != render::RenderJobCheck::Ok) {
        std::cerr << "velvet render: " << why << "\n";
        return BadInput; // a bad pattern, a missing folder, no ffmpeg (the values parsed above)
    }

    Problems problems;
    std::optional<Scene> scene;
    if (const int code = loadSceneArguments(*args, "render", scene, problems); code != Ok)
        return code;
    if (args->has("chain")) {
        const auto preset = loadPostChainFile(args->value("chain"), problems);
        if (!preset || problems.hasErrors()) {
            printProblems(problems);
            return BadInput;
        }
        scene->post = preset->chain;
    }

    // One line per frame on stderr: a turntable is minutes of work, and a script reading stdout
    // gets nothing mixed into it.
    const auto progress = [&](const render::RenderJobProgress& p) {
        if (job.frames == 0)
            return true;
        char line[160];
        if (p.encoding)
            std::snprintf(line, sizeof line, "velvet render: encoding %s with ffmpeg\n",
                          job.video.c_str());
        else
            std::snprintf(line, sizeof line,
                          "velvet render: frame %d/%d (%3.0f %%), %.1f s elapsed, ETA %.1f s\n",
                          p.done, p.total, 100.0 * p.done / p.total, p.elapsedSeconds,
                          p.etaSeconds);
        std::cerr << line << std::flush;
        return true;
    };
    render::RenderJobTimings jobTimings;
    const bool timed = args->has("timings");
    timings.sceneLoadMs = msBetween(timings.mainStart, std::chrono::steady_clock::now());
    timings.sceneLoadCpuMs = render::processCpuMs() - timings.beforeMainCpuMs;
    const render::RenderJobStatus status = render::runRenderJob(
        *scene, job, progress, &error, &problems, timed ? &jobTimings : nullptr);
    if (timed)
        printRenderTimings(timings, jobTimings);
    printProblems(problems); // warnings only (missing textures or HDRI fell back)
    if (status != render::RenderJobStatus::Done) {
        std::cerr << "velvet render: " << error << "\n";
        return RenderFailure;
    }
    return Ok;
}

} // namespace velvet::cli
