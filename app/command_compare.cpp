// velvet compare A B -o HEATMAP.png: per-pixel CIEDE2000 between two images after the same
// display transform (core/image_compare.h), its mean, 95th percentile and maximum, and a heat
// map with a legend (issue 15; docs/reference-renderer.md).
#include "app/cli.h"
#include "app/load_document.h"
#include "core/image.h"
#include "core/image_compare.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace velvet::cli {
namespace {

const std::vector<OptionSpec> kOptions{
    {"output", 'o', true, "HEATMAP.png", "heat map of the per-pixel ΔE2000, with a legend"},
    {"max", 0, true, "DE", "ΔE at the top of the heat map's scale (default 10)"},
    {"help", 'h', false, "", "this text"},
};

const char* kHelp =
    "Usage: velvet compare A B [-o HEATMAP.png] [--max DE]\n"
    "Compares two images pixel by pixel with CIEDE2000 (CIE 142-2001) after the same display\n"
    "transform, and prints the mean, the 95th percentile and the maximum. An image with float\n"
    "samples (.exr, .hdr: scene-linear, as velvet render and velvet reference write them) goes\n"
    "through velvet render's default display transform (Khronos PBR Neutral, sRGB encoding);\n"
    "an integer image (.png, …) is taken as display-referred sRGB. Both must have the same size.\n"
    "Exit codes: 0 success, 1 usage error, 2 bad input.\n\n";

int usage(const std::string& message) {
    std::cerr << "velvet compare: " << message << "\nRun 'velvet compare --help' for usage.\n";
    return UsageError;
}

/// @p file as display-referred sRGB: float files through the default display transform.
bool loadDisplayReferred(const std::string& file, Image& out, std::string* error) {
    ImageInfo info;
    if (!readImageInfo(file, info, error) || !readImage(file, out, error))
        return false;
    if (info.isFloat)
        out = defaultDisplayTransform(out);
    return true;
}

} // namespace

int runCompare(const std::vector<std::string>& argv) {
    std::string error;
    auto args = parseArguments(argv, kOptions, &error);
    if (!args)
        return usage(error);
    if (args->has("help")) {
        std::cout << kHelp << optionsHelp(kOptions);
        return Ok;
    }
    if (args->positional.size() != 2)
        return usage("needs two images A and B, got " + std::to_string(args->positional.size()));
    float scaleMax = 10.0f;
    if (args->has("max") && (!parseFloat(args->value("max"), scaleMax) || scaleMax <= 0.0f))
        return usage("--max expects a ΔE > 0, got '" + args->value("max") + "'");
    const std::filesystem::path out = args->value("output");
    if (!out.empty()) {
        std::string ext = out.extension().string();
        for (char& c : ext)
            c = char(std::tolower(static_cast<unsigned char>(c)));
        if (ext != ".png")
            return usage("the heat map is a .png, got '" + out.string() + "'");
        if (const int code = checkOutputFolder(out); code != Ok)
            return code;
    }
    Image a, b;
    if (!loadDisplayReferred(args->positional[0], a, &error) ||
        !loadDisplayReferred(args->positional[1], b, &error)) {
        std::cerr << "velvet compare: " << error << "\n";
        return BadInput;
    }
    Image deltaE;
    DeltaEStats stats;
    if (!compareImages(a, b, deltaE, stats, &error)) {
        std::cerr << "velvet compare: " << args->positional[0] << " and " << args->positional[1]
                  << ": " << error << "\n";
        return BadInput;
    }
    char line[160];
    std::snprintf(line, sizeof line, "mean %.4f\np95 %.4f\nmax %.4f\n", stats.mean, stats.p95,
                  stats.max);
    std::cout << "ΔE2000 over " << stats.pixels << " pixels\n" << line;
    if (!out.empty() &&
        !writeImage(out, heatMapWithLegend(deltaE, scaleMax), PixelFormat::UInt8, &error)) {
        std::cerr << "velvet compare: " << error << "\n";
        return BadInput;
    }
    return Ok;
}

} // namespace velvet::cli
