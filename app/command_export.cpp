// velvet export FILE... -f glb|gltf|preset -o OUT: a scene's or preset's material leaves Velvet
// (core/material_export.h; every mapping in docs/interchange.md).
#include "app/cli.h"
#include "app/load_document.h"
#include "core/material_export.h"

#include <filesystem>
#include <iostream>
#include <map>

namespace velvet::cli {
namespace {

namespace fs = std::filesystem;

const std::vector<OptionSpec> kOptions{
    {"format", 'f', true, "FORMAT",
     "glb (glTF 2.0 binary, one file), gltf (JSON + .bin + PNG images), mtlx (MaterialX 1.39 "
     "+ PNG images) or preset (Velvet JSON)"},
    {"output", 'o', true, "OUT",
     "the output folder; with one FILE also a file name with the format's extension"},
    {"mesh", 0, true, "MESH|FILE",
     "glTF: the mesh the material is shown on: sphere, cube, rounded-cube, plane, cloth-drape, "
     "shader-ball, or a mesh file (default: the scene's mesh)"},
    {"shader", 0, true, "NAME",
     "mtlx: the shader node, standard_surface (default), open_pbr_surface or gltf_pbr"},
    {"force", 0, false, "", "replace existing files (otherwise an existing output is exit 2)"},
    {"help", 'h', false, "", "this text"},
};

const char* kHelp =
    "Usage: velvet export FILE... -f glb|gltf|mtlx|preset -o OUT [--mesh MESH|FILE]\n"
    "                    [--shader NAME] [--force]\n"
    "Exports the material of each FILE (a scene, or a material preset) as glTF 2.0 with the\n"
    "KHR_materials_clearcoat, _sheen, _specular, _ior and _emissive_strength extensions, on the\n"
    "preview mesh, as MaterialX 1.39, or as a standalone Velvet preset. Each FILE gives\n"
    "OUT/NAME.glb (or .gltf with NAME.bin and NAME_<map>.png, .mtlx with NAME_<map>.png, or\n"
    "NAME.json), NAME being FILE's name reduced to letters,\n"
    "digits, '-' and '_', so nothing is written outside OUT. What glTF cannot carry (BRDF term\n"
    "choices, the node graph: baking it on the GPU is not implemented yet) is printed as a\n"
    "warning. Files are written atomically; an existing file is refused unless --force.\n"
    "Exit codes: 0 success, 1 usage error, 2 bad input or existing output (for any FILE; the\n"
    "others are still exported).\n\n";

int usage(const std::string& message) {
    std::cerr << "velvet export: " << message << "\nRun 'velvet export --help' for usage.\n";
    return UsageError;
}

std::optional<MeshRef> parseMesh(const std::string& text) {
    const auto names = previewMeshKindNames();
    for (size_t i = 0; i < names.size(); ++i)
        if (names[i] == text && PreviewMeshKind(i) != PreviewMeshKind::Custom)
            return MeshRef{PreviewMeshKind(i), {}};
    std::error_code ec;
    if (!fs::is_regular_file(text, ec))
        return std::nullopt;
    return MeshRef{PreviewMeshKind::Custom, fs::absolute(text).string()};
}

} // namespace

int runExport(const std::vector<std::string>& argv) {
    std::string error;
    auto args = parseArguments(argv, kOptions, &error);
    if (!args)
        return usage(error);
    if (args->has("help")) {
        std::cout << kHelp << optionsHelp(kOptions);
        return Ok;
    }
    if (args->positional.empty())
        return usage("needs at least one FILE");
    if (!args->has("format") || !args->has("output"))
        return usage("needs -f FORMAT and -o OUT");
    ExportOptions options;
    const auto format = exportFormatFromId(args->value("format"));
    if (!format)
        return usage("unknown format \"" + args->value("format") +
                     "\"; formats: glb, gltf, mtlx, preset");
    options.format = *format;
    options.force = args->has("force");
    if (args->has("shader")) {
        const auto shader = mtlxShaderFromId(args->value("shader"));
        if (!shader)
            return usage("unknown --shader \"" + args->value("shader") +
                         "\"; shaders: standard_surface, open_pbr_surface, gltf_pbr");
        if (options.format != ExportFormat::Mtlx)
            return usage("--shader applies to -f mtlx only");
        options.shader = *shader;
    }
    if (args->has("mesh")) {
        if (options.format != ExportFormat::Glb && options.format != ExportFormat::Gltf)
            return usage("--mesh applies to -f glb and -f gltf only (the other formats hold no "
                         "mesh)");
        options.mesh = parseMesh(args->value("mesh"));
        if (!options.mesh)
            return usage("--mesh \"" + args->value("mesh") +
                         "\" is neither a preview mesh name nor a mesh file");
    }

    // OUT names the file when there is one input and OUT carries the format's extension.
    const fs::path out = args->value("output");
    const std::string extension(exportFormatExtension(options.format));
    const bool outIsFile = args->positional.size() == 1 && out.extension() == extension;
    const fs::path folder = outIsFile ? out.parent_path() : out;
    std::vector<std::string> bases;
    std::map<std::string, std::string> byBase;
    for (const std::string& file : args->positional) {
        const std::string base =
            sanitizeFileStem(outIsFile ? out.stem().string() : fs::path(file).stem().string());
        if (auto [it, fresh] = byBase.emplace(base, file); !fresh)
            return usage("\"" + it->second + "\" and \"" + file + "\" would both write " + base +
                         extension + "; export them to different folders");
        bases.push_back(base);
    }

    bool anyFailed = false;
    for (size_t i = 0; i < args->positional.size(); ++i) {
        const std::string& file = args->positional[i];
        Problems problems;
        std::optional<Scene> scene = loadSceneOrPreset(file, problems);
        printProblems(problems);
        if (!scene || problems.hasErrors()) {
            anyFailed = true;
            continue;
        }
        const ExportOutcome outcome = exportMaterial(*scene, folder, bases[i], options);
        for (const std::string& w : outcome.warnings)
            std::cerr << "warning: " << file << ": " << w << "\n";
        if (!outcome.ok()) {
            std::cerr << file << ": " << outcome.error << "\n";
            anyFailed = true;
            continue;
        }
        std::cout << outcome.written.back().string() << "\n";
    }
    return anyFailed ? BadInput : Ok;
}

} // namespace velvet::cli
