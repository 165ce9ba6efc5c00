// velvet export FILE... -f glb|gltf|preset -o OUT: a scene's or preset's material leaves Velvet
// (core/material_export.h; every mapping in docs/interchange.md).
#include "app/batch.h"
#include "app/batch_commands.h"
#include "app/cli.h"
#include "app/load_document.h"
#include "core/material_export.h"
#include "core/texture_set_export.h"
#include "render/baked_export.h"
#include "render/material_bake.h"

#include <charconv>
#include <filesystem>
#include <iostream>
#include <map>

namespace velvet::cli {
namespace {

namespace fs = std::filesystem;

const std::vector<OptionSpec> kOptions{
    {"format", 'f', true, "FORMAT",
     "glb (glTF 2.0 binary, one file), gltf (JSON + .bin + PNG images), mtlx (MaterialX 1.39 "
     "+ PNG images), preset (Velvet JSON) or texture-set (an engine's maps, --target)"},
    {"target", 0, true, "ENGINE",
     "texture-set: unreal (ORM, DirectX normals), unity-hdrp (mask map, OpenGL normals), godot "
     "(ORM, OpenGL normals) or gltf (ORM, OpenGL normals)"},
    {"size", 0, true, "N", "texture-set: width and height of every map, 1 to 8192 (default 1024)"},
    {"bits", 0, true, "8|16|32",
     "texture-set: bits per channel: PNG 8 (default) or 16, TGA 8, EXR 16 (default, half) or 32"},
    {"image", 0, true, "png|tga|exr", "texture-set: the maps' file type (default png)"},
    {"normal", 0, true, "opengl|directx",
     "texture-set: the normal map's green channel, replacing the target's convention"},
    {"output", 'o', true, "OUT",
     "the output folder; with one FILE also a file name with the format's extension"},
    {"mesh", 0, true, "MESH|FILE",
     "glTF: the mesh the material is shown on: sphere, cube, rounded-cube, plane, cloth-drape, "
     "shader-ball, or a mesh file (default: the scene's mesh)"},
    {"shader", 0, true, "NAME",
     "mtlx: the shader node, standard_surface (default), open_pbr_surface or gltf_pbr"},
    {"bake-size", 0, true, "N",
     "glb, gltf, mtlx: width and height of the node graph's baked maps, 1 to 8192 (default 1024)"},
    {"force", 0, false, "", "replace existing files (otherwise an existing output is exit 2)"},
    kJobsOption,
    kShardOption,
    {"help", 'h', false, "", "this text"},
};

const char* kHelp =
    "Usage: velvet export FILE... -f glb|gltf|mtlx|preset -o OUT [--mesh MESH|FILE]\n"
    "                    [--shader NAME] [--bake-size N] [--force]\n"
    "       velvet export FILE... -f texture-set --target ENGINE -o OUT [--size N]\n"
    "                    [--bits B] [--image png|tga|exr] [--normal opengl|directx] [--force]\n"
    "Exports the material of each FILE (a scene, or a material preset) as glTF 2.0 with the\n"
    "KHR_materials_clearcoat, _sheen, _specular, _ior, _emissive_strength and _anisotropy\n"
    "extensions, on the preview mesh, as MaterialX 1.39, or as a standalone Velvet preset.\n"
    "Each FILE gives OUT/NAME.glb (or .gltf with NAME.bin and NAME_<map>.png, .mtlx with\n"
    "NAME_<map>.png, or NAME.json), NAME being FILE's name reduced to letters,\n"
    "digits, '-' and '_', so nothing is written outside OUT. What the node graph drives is\n"
    "baked on the GPU into NAME_baked_<map>.png images (--bake-size, default 1024) that the\n"
    "material reads with white factors; inputs it does not drive stay factors. What the\n"
    "format cannot carry (BRDF term choices) is printed as a warning. Files are written\n"
    "atomically; an existing file is refused unless --force.\n"
    "-f texture-set bakes the material on the GPU (its texture slots, atlas regions and node\n"
    "graph; constants give flat maps) into the maps ENGINE reads, with its names, channel\n"
    "packing and normal-map convention, and OUT/NAME_texture_set.json naming each file's role.\n"
    "Several FILEs (or --jobs, --shard) are exported in parallel child processes, --jobs at a\n"
    "time, with progress on stderr (docs/batch.md).\n"
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

bool parseInt(const std::string& text, int& v) {
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    return ec == std::errc() && ptr == text.data() + text.size();
}

/// -f texture-set: each FILE's material baked and written as @p args' --target's texture set.
int runTextureSetExport(const Arguments& args) {
    for (const char* other : {"mesh", "shader", "bake-size"})
        if (args.has(other))
            return usage("--" + std::string(other) + " does not apply to -f texture-set");
    if (!args.has("target"))
        return usage("-f texture-set needs --target unreal|unity-hdrp|godot|gltf");
    TextureSetOptions options;
    const auto target = textureSetTargetFromId(args.value("target"));
    if (!target)
        return usage("unknown --target \"" + args.value("target") +
                     "\"; targets: unreal, unity-hdrp, godot, gltf");
    options.target = *target;
    if (args.has("size") && !parseInt(args.value("size"), options.size))
        return usage("--size expects a whole number of texels, got '" + args.value("size") + "'");
    if (args.has("bits") && !parseInt(args.value("bits"), options.bits))
        return usage("--bits expects 8, 16 or 32, got '" + args.value("bits") + "'");
    if (args.has("image")) {
        const auto type = textureFileTypeFromId(args.value("image"));
        if (!type)
            return usage("unknown --image \"" + args.value("image") + "\"; types: png, tga, exr");
        options.fileType = *type;
    }
    if (args.has("normal")) {
        const std::string n = args.value("normal");
        if (n != "opengl" && n != "directx")
            return usage("--normal expects opengl or directx, got '" + n + "'");
        options.normal = n == "directx" ? NormalConvention::DirectX : NormalConvention::OpenGl;
    }
    if (const std::string why = checkTextureSetOptions(options); !why.empty())
        return usage(why);

    const fs::path folder = args.value("output");
    std::map<std::string, std::string> byBase;
    for (const std::string& file : args.positional) {
        const std::string base = sanitizeFileStem(fs::path(file).stem().string());
        if (auto [it, fresh] = byBase.emplace(base, file); !fresh)
            return usage("\"" + it->second + "\" and \"" + file + "\" would both write the " +
                         base + " texture set; export them to different folders");
    }
    if (isExportBatch(args)) // several FILEs, --jobs or --shard: one child process per FILE
        return runExportBatch(args, kOptions);
    bool anyFailed = false;
    for (const std::string& file : args.positional) {
        Problems problems;
        std::optional<Scene> scene = loadSceneOrPreset(file, problems);
        printProblems(problems);
        if (!scene || problems.hasErrors()) {
            anyFailed = true;
            continue;
        }
        const ExportOutcome outcome = render::exportTextureSet(
            scene->material, folder, fs::path(file).stem().string(), options, args.has("force"));
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
    if (args->value("format") == "texture-set")
        return runTextureSetExport(*args);
    for (const char* setOnly : {"target", "size", "bits", "image", "normal"})
        if (args->has(setOnly))
            return usage("--" + std::string(setOnly) + " applies to -f texture-set only");
    ExportOptions options;
    const auto format = exportFormatFromId(args->value("format"));
    if (!format)
        return usage("unknown format \"" + args->value("format") +
                     "\"; formats: glb, gltf, mtlx, preset, texture-set");
    options.format = *format;
    options.force = args->has("force");
    if (args->has("bake-size")) {
        if (options.format == ExportFormat::Preset)
            return usage("--bake-size applies to -f glb, gltf and mtlx only (a preset keeps its "
                         "graph)");
        if (!parseInt(args->value("bake-size"), options.bakeSize) || options.bakeSize < 1 ||
            options.bakeSize > 8192)
            return usage("--bake-size expects a whole number of texels from 1 to 8192, got '" +
                         args->value("bake-size") + "'");
    }
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
    if (isExportBatch(*args)) // several FILEs, --jobs or --shard: one child process per FILE
        return runExportBatch(*args, kOptions);

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
        const ExportOutcome outcome =
            render::exportMaterialBaked(*scene, folder, bases[i], options);
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
