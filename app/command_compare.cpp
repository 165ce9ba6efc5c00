// velvet compare A B -o HEATMAP.png: per-pixel CIEDE2000 between two images after the same
// display transform (core/image_compare.h), its mean, 95th percentile and maximum, and a heat
// map with a legend (issue 15; docs/reference-renderer.md). With --table, the viewport against
// the reference for the library's presets (app/reference_table.h).
#include "app/cli.h"
#include "app/load_document.h"
#include "app/reference_table.h"
#include "core/image.h"
#include "core/image_compare.h"
#include "core/light_rigs.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace velvet::cli {
namespace {

const std::vector<OptionSpec> kOptions{
    {"output", 'o', true, "HEATMAP.png", "heat map of the per-pixel ΔE2000, with a legend"},
    {"max", 0, true, "DE", "ΔE at the top of the heat map's scale (default 10)"},
    {"table", 0, false, "", "no A B: the viewport against the reference for library presets"},
    {"preset", 0, true, "A,B", "--table: these presets (default: every library preset)"},
    {"mesh", 0, true, "A,B", "--table: these meshes (default sphere,shader-ball)"},
    {"light-rig", 0, true, "A,B", "--table: these rigs (default environment,three-point)"},
    {"size", 0, true, "N", "--table: image side in pixels (default 48)"},
    {"spp", 0, true, "N", "--table: reference samples per pixel (default 64)"},
    {"bounces", 0, true, "N", "--table: reference path vertices after the first hit (default 4)"},
    {"reflection-samples", 0, true, "N",
     "--table: the viewport's reflection samples per sample, as at rest (default 16; 0: the "
     "split sum of a frame drawn while the view moves)"},
    {"no-screen-space-reflections", 0, false, "",
     "--table: the viewport without the mesh's reflections of itself (its occlusion alone)"},
    {"images", 0, true, "DIR", "--table: write each case's viewport, reference and heat map"},
    {"help", 'h', false, "", "this text"},
};

const char* kHelp =
    "Usage: velvet compare A B [-o HEATMAP.png] [--max DE]\n"
    "Compares two images pixel by pixel with CIEDE2000 (CIE 142-2001) after the same display\n"
    "transform, and prints the mean, the 95th percentile and the maximum. An image with float\n"
    "samples (.exr, .hdr: scene-linear, as velvet render and velvet reference write them) goes\n"
    "through velvet render's default display transform (Khronos PBR Neutral, sRGB encoding);\n"
    "an integer image (.png, …) is taken as display-referred sRGB. Both must have the same size.\n"
    "\n"
    "velvet compare --table [--preset A,B] [--mesh A,B] [--light-rig A,B] [--size N] [--spp N]\n"
    "                       [--bounces N] [--reflection-samples N]\n"
    "                       [--no-screen-space-reflections] [--images DIR]\n"
    "renders each library preset on each mesh under each rig (the default HDRI stays) with the\n"
    "viewport's renderer and the reference path tracer, and prints a Markdown table of the\n"
    "mean, 95th percentile and maximum ΔE2000 over the pixels the mesh covers, against issue\n"
    "15's goal (mean < 2, p95 < 5). The viewport's image is the editor's at rest: 4x4 samples a\n"
    "pixel, reflections sampled, the mesh's reflections of itself traced in screen space over\n"
    "the refinement's 16 frames, each reading the light of the one before.\n"
    "Progress on stderr.\n"
    "Exit codes: 0 success, 1 usage error, 2 bad input, 3 rendering failure.\n\n";

int usage(const std::string& message) {
    std::cerr << "velvet compare: " << message << "\nRun 'velvet compare --help' for usage.\n";
    return UsageError;
}

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> items;
    size_t begin = 0;
    while (begin <= text.size()) {
        const size_t end = std::min(text.find(',', begin), text.size());
        if (end > begin)
            items.push_back(text.substr(begin, end - begin));
        begin = end + 1;
    }
    return items;
}

bool parseCount(const std::string& text, int& v, int lo, int hi) {
    float f = 0.0f;
    if (!parseFloat(text, f) || f != std::floor(f) || f < float(lo) || f > float(hi))
        return false;
    v = int(f);
    return true;
}

int runTable(const Arguments& args) {
    ReferenceTableOptions options;
    if (args.has("size") && !parseCount(args.value("size"), options.size, 4, 1024))
        return usage("--size expects a whole number of pixels in [4, 1024], got '" +
                     args.value("size") + "'");
    if (args.has("spp") && !parseCount(args.value("spp"), options.samples, 1, 65536))
        return usage("--spp expects a whole number in [1, 65536], got '" + args.value("spp") + "'");
    if (args.has("bounces") && !parseCount(args.value("bounces"), options.bounces, 0, 64))
        return usage("--bounces expects a whole number in [0, 64], got '" + args.value("bounces") +
                     "'");
    if (args.has("reflection-samples") &&
        !parseCount(args.value("reflection-samples"), options.reflectionSamples, 0, 256))
        return usage("--reflection-samples expects a whole number in [0, 256], got '" +
                     args.value("reflection-samples") + "'");
    options.screenSpaceReflections = !args.has("no-screen-space-reflections");
    const std::vector<std::string> library = libraryPresets();
    std::vector<std::string> presets =
        args.has("preset") ? splitList(args.value("preset")) : library;
    for (const std::string& p : presets)
        if (std::find(library.begin(), library.end(), p) == library.end())
            return usage("--preset: no library preset '" + p + "'");
    std::vector<PreviewMeshKind> meshes{PreviewMeshKind::Sphere, PreviewMeshKind::ShaderBall};
    if (args.has("mesh")) {
        meshes.clear();
        const auto names = previewMeshKindNames();
        for (const std::string& m : splitList(args.value("mesh"))) {
            const auto it = std::find(names.begin(), names.end(), m);
            if (it == names.end() || *it == "custom")
                return usage("--mesh: no preview mesh '" + m + "'");
            meshes.push_back(PreviewMeshKind(it - names.begin()));
        }
    }
    std::vector<std::string> rigs{"environment", "three-point"};
    if (args.has("light-rig")) {
        rigs = splitList(args.value("light-rig"));
        for (const std::string& r : rigs)
            if (!lightRigLights(r))
                return usage("--light-rig: unknown rig '" + r + "'");
    }
    if (presets.empty() || meshes.empty() || rigs.empty())
        return usage("--table: nothing to measure");
    if (args.has("images"))
        if (const int code = checkOutputFolder(std::filesystem::path(args.value("images")) / "x");
            code != Ok)
            return code;

    ReferenceTable table;
    std::string error;
    if (!table.start(&error)) {
        std::cerr << "velvet compare: rendering failed: " << error << "\n";
        return RenderFailure;
    }
    std::cout << referenceTableHeader() << std::flush;
    int met = 0, total = 0;
    for (const std::string& preset : presets)
        for (const PreviewMeshKind mesh : meshes)
            for (const std::string& rig : rigs) {
                ReferenceTableRow row;
                if (!table.measure({preset, mesh, rig}, options, row, &error)) {
                    std::cerr << "velvet compare: " << error << "\n";
                    return RenderFailure;
                }
                std::cout << referenceTableLine(row) << std::flush;
                if (args.has("images")) {
                    const std::filesystem::path base =
                        std::filesystem::path(args.value("images")) /
                        (preset + "_" + std::string(previewMeshKindNames()[size_t(mesh)]) + "_" +
                         rig);
                    if (!writeImage(base.string() + "_viewport.png", row.viewport,
                                    PixelFormat::UInt8, &error) ||
                        !writeImage(base.string() + "_reference.png", row.reference,
                                    PixelFormat::UInt8, &error) ||
                        !writeImage(base.string() + "_delta.png",
                                    heatMapWithLegend(row.deltaE, 10.0), PixelFormat::UInt8,
                                    &error)) {
                        std::cerr << "velvet compare: " << error << "\n";
                        return BadInput;
                    }
                }
                std::cerr << "  " << preset << ": viewport " << int(row.viewportMs)
                          << " ms, reference " << int(row.referenceMs) << " ms\n";
                met += meetsReferenceGoal(row.stats) ? 1 : 0;
                ++total;
            }
    std::cout << "\n"
              << met << " of " << total << " cases meet the goal (mean < 2, p95 < 5) at "
              << options.size << "x" << options.size << ", " << options.samples
              << " reference samples per pixel, " << options.bounces << " bounces\n";
    return Ok;
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
    if (args->has("table")) {
        if (!args->positional.empty())
            return usage("--table takes no images");
        return runTable(*args);
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
