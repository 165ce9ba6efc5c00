// velvet render [FILE] -o OUT [--size WxH] …: headless rendering through the real deferred path.
#include "app/cli.h"
#include "app/load_document.h"
#include "core/document_io.h"
#include "core/image.h"
#include "render/offscreen.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <iostream>

namespace velvet::cli {
namespace {

const std::vector<OptionSpec> kOptions{
    {"output", 'o', true, "OUT",
     "image to write: .png (8-bit, display encoded) or .exr (linear half)"},
    {"size", 's', true, "WxH", "image size in pixels (default 512x512, at most 8192 per side)"},
    {"exposure", 0, true, "EV", "exposure in stops before tone mapping (default 0)"},
    {"tonemap", 0, true, "NAME", "pbr-neutral (default), aces, reinhard or linear"},
    {"view", 0, true, "NAME", "final (default), albedo, normal, depth, roughness or metallic"},
    {"help", 'h', false, "", "this text"},
};

const char* kHelp =
    "Usage: velvet render [FILE] -o OUT [--size WxH]\n"
    "Renders FILE (a scene, or a material preset shown in the default scene; no FILE: the default\n"
    "scene) off screen through the deferred renderer. Needs no display.\n\n";

bool parseSize(const std::string& text, int& w, int& h) {
    auto x = text.find_first_of("xX");
    if (x == std::string::npos)
        return false;
    auto parse = [](std::string_view s, int& v) {
        auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        return ec == std::errc() && ptr == s.data() + s.size() && v >= 1 && v <= 8192;
    };
    return parse(std::string_view(text).substr(0, x), w) &&
           parse(std::string_view(text).substr(x + 1), h);
}

bool parseFloat(const std::string& text, float& v) {
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    return ec == std::errc() && ptr == text.data() + text.size() && std::isfinite(v);
}

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
const std::pair<const char*, render::DebugView> kViews[] = {
    {"final", render::DebugView::Final},         {"albedo", render::DebugView::Albedo},
    {"normal", render::DebugView::Normal},       {"depth", render::DebugView::Depth},
    {"roughness", render::DebugView::Roughness}, {"metallic", render::DebugView::Metallic},
};

/// Keeps the first three channels (the file holds opaque colour).
Image toRgb(const Image& rgba) {
    Image out(rgba.width, rgba.height, 3);
    for (int y = 0; y < rgba.height; ++y)
        for (int x = 0; x < rgba.width; ++x) {
            glm::vec4 p = rgba.rgba(x, y);
            float* o = out.at(x, y);
            o[0] = p.r, o[1] = p.g, o[2] = p.b;
        }
    return out;
}

int usage(const std::string& message) {
    std::cerr << "velvet render: " << message << "\nRun 'velvet render --help' for usage.\n";
    return UsageError;
}

} // namespace

int runRender(const std::vector<std::string>& argv) {
    std::string error;
    auto args = parseArguments(argv, kOptions, &error);
    if (!args)
        return usage(error);
    if (args->has("help")) {
        std::cout << kHelp << optionsHelp(kOptions);
        return Ok;
    }
    if (!args->has("output"))
        return usage("missing -o OUT");
    if (args->positional.size() > 1)
        return usage("one FILE at most, got " + std::to_string(args->positional.size()));

    const std::filesystem::path out = args->value("output");
    std::string ext = out.extension().string();
    for (char& c : ext)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".png" && ext != ".exr")
        return usage("OUT must end in .png or .exr, got '" + out.string() + "'");

    render::FrameSettings settings;
    settings.width = settings.height = 512;
    if (args->has("size") && !parseSize(args->value("size"), settings.width, settings.height))
        return usage("--size expects WxH with each side in [1, 8192], got '" + args->value("size") +
                     "'");
    if (args->has("exposure") && !parseFloat(args->value("exposure"), settings.exposureEv))
        return usage("--exposure expects a number, got '" + args->value("exposure") + "'");
    if (args->has("tonemap") &&
        !parseName(args->value("tonemap"), kToneMappers, settings.toneMapper))
        return usage("--tonemap: unknown tone mapper '" + args->value("tonemap") + "'");
    if (args->has("view") && !parseName(args->value("view"), kViews, settings.view))
        return usage("--view: unknown view '" + args->value("view") + "'");

    // Check the destination before the (slow) render so bad input writes nothing and fails fast.
    const std::filesystem::path folder = out.parent_path().empty() ? "." : out.parent_path();
    std::error_code ec;
    if (!std::filesystem::is_directory(folder, ec)) {
        std::cerr << out.string() << ": the folder '" << folder.string() << "' does not exist\n";
        return BadInput;
    }

    Problems problems;
    std::optional<Scene> scene;
    if (args->positional.empty())
        scene = defaultScene(&problems);
    else
        scene = loadSceneOrPreset(args->positional[0], problems);
    if (!scene || problems.hasErrors()) {
        printProblems(problems);
        return BadInput;
    }

    Image linear, display;
    const bool wantExr = ext == ".exr";
    if (!render::renderSceneOffscreen(*scene, settings, wantExr ? &linear : nullptr,
                                      wantExr ? nullptr : &display, &error, &problems)) {
        printProblems(problems);
        std::cerr << "velvet render: rendering failed: " << error << "\n";
        return RenderFailure;
    }
    printProblems(problems); // warnings only (missing textures or HDRI fell back)

    if (!writeImage(out, toRgb(wantExr ? linear : display),
                    wantExr ? PixelFormat::Half : PixelFormat::UInt8, &error)) {
        std::cerr << "velvet render: " << error << "\n";
        return RenderFailure;
    }
    return Ok;
}

} // namespace velvet::cli
