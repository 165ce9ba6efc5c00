// velvet reference [FILE] -o OUT.exr --spp N: the CPU path-traced ground truth of the frame
// `velvet render` draws (reference/reference_renderer.h). FILE, --size and --light-rig mean
// what they mean for `velvet render` (loadSceneArguments, parseSize: one parser for both).
#include "app/cli.h"
#include "app/load_document.h"
#include "core/image.h"
#include "reference/reference_renderer.h"

#include <atomic>
#include <charconv>
#include <csignal>
#include <filesystem>
#include <iostream>

namespace velvet::cli {
namespace {

const std::vector<OptionSpec> kOptions{
    {"output", 'o', true, "OUT.exr", "image to write: OpenEXR, scene-linear half float"},
    {"size", 's', true, "WxH", "image size in pixels (default 512x512, as velvet render)"},
    {"light-rig", 0, true, "ID", "replace the scene's lights with a rig (as velvet render)"},
    {"spp", 0, true, "N", "samples per pixel (default 64)"},
    {"bounces", 0, true, "N", "path vertices after the first hit (default 4)"},
    {"seed", 0, true, "N", "random seed (default 1): the same seed gives the same image"},
    {"threads", 0, true, "N", "worker threads (default: all cores); the image does not change"},
    {"time-limit", 0, true, "SECONDS", "stop after the sample pass that passes this time"},
    {"help", 'h', false, "", "this text"},
};

const char* kHelp =
    "Usage: velvet reference [FILE] -o OUT.exr [--spp N] [--size WxH] [--light-rig ID]\n"
    "Path traces FILE (a scene, or a material preset in the default scene) on the CPU: the same\n"
    "mesh, camera, lights, environment and material as velvet render, with no real-time\n"
    "approximation (docs/reference-renderer.md). Progress on stderr; Ctrl+C writes the samples\n"
    "taken so far.\n\n";

std::atomic<bool> g_interrupted{false};
extern "C" void onSigint(int) {
    g_interrupted.store(true);
}

int usage(const std::string& message) {
    std::cerr << "velvet reference: " << message << "\nRun 'velvet reference --help' for usage.\n";
    return UsageError;
}

template <typename T>
bool parseNumber(const std::string& text, T& v, T lo) {
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    return ec == std::errc() && ptr == text.data() + text.size() && v >= lo;
}

} // namespace

int runReference(const std::vector<std::string>& argv) {
    std::string error;
    auto args = parseArguments(argv, kOptions, &error);
    if (!args)
        return usage(error);
    if (args->has("help")) {
        std::cout << kHelp << optionsHelp(kOptions);
        return Ok;
    }
    if (!args->has("output"))
        return usage("missing -o OUT.exr");
    if (args->positional.size() > 1)
        return usage("one FILE at most, got " + std::to_string(args->positional.size()));
    const std::filesystem::path out = args->value("output");
    std::string ext = out.extension().string();
    for (char& c : ext)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".exr")
        return usage("OUT must end in .exr, got '" + out.string() + "'");

    reference::Options options;
    options.width = options.height = 512;
    if (args->has("size") && !parseSize(args->value("size"), options.width, options.height))
        return usage("--size expects WxH with each side in [1, 8192], got '" + args->value("size") +
                     "'");
    if (args->has("spp") && !parseNumber(args->value("spp"), options.samplesPerPixel, 1))
        return usage("--spp expects a whole number >= 1, got '" + args->value("spp") + "'");
    if (args->has("bounces") && !parseNumber(args->value("bounces"), options.maxBounces, 0))
        return usage("--bounces expects a whole number >= 0, got '" + args->value("bounces") + "'");
    if (args->has("seed") && !parseNumber(args->value("seed"), options.seed, std::uint64_t(0)))
        return usage("--seed expects a whole number, got '" + args->value("seed") + "'");
    if (args->has("threads") && !parseNumber(args->value("threads"), options.threads, 1))
        return usage("--threads expects a whole number >= 1, got '" + args->value("threads") + "'");
    if (args->has("time-limit")) {
        float seconds = 0;
        if (!parseFloat(args->value("time-limit"), seconds) || seconds <= 0.0f)
            return usage("--time-limit expects seconds > 0, got '" + args->value("time-limit") +
                         "'");
        options.timeLimitSeconds = seconds;
    }
    if (const int code = checkOutputFolder(out); code != Ok)
        return code;

    Problems problems;
    std::optional<Scene> scene;
    if (const int code = loadSceneArguments(*args, "reference", scene, problems); code != Ok)
        return code;

    g_interrupted = false;
    auto previous = std::signal(SIGINT, onSigint);
    reference::Result result;
    const bool ok = reference::render(
        *scene, options, result, &error, &problems,
        [](int done, int total) {
            std::cerr << "\rvelvet reference: " << done << "/" << total << " samples per pixel"
                      << std::flush;
        },
        &g_interrupted);
    std::signal(SIGINT, previous);
    std::cerr << "\n";
    printProblems(problems);
    if (!ok) {
        std::cerr << "velvet reference: rendering failed: " << error << "\n";
        return RenderFailure;
    }
    if (result.cancelled)
        std::cerr << "velvet reference: interrupted; writing " << result.passesDone
                  << " complete samples per pixel (and part of the next)\n";
    if (!writeImage(out, result.image, PixelFormat::Half, &error)) {
        std::cerr << "velvet reference: " << error << "\n";
        return RenderFailure;
    }
    return Ok;
}

} // namespace velvet::cli
