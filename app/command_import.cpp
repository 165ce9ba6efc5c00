// velvet import FILE -o PRESET.json: a glTF 2.0 (.gltf, .glb) or MaterialX (.mtlx) material comes
// in as a Velvet preset (core/material_import.h; every mapping in docs/interchange.md).
#include "app/cli.h"
#include "core/document_io.h"
#include "core/material_import.h"

#include <filesystem>
#include <iostream>

namespace velvet::cli {
namespace {

namespace fs = std::filesystem;

const std::vector<OptionSpec> kOptions{
    {"output", 'o', true, "PRESET.json",
     "the preset to write (a scene with --mesh); embedded images are written beside it"},
    {"material", 'm', true, "NAME|INDEX",
     "which material of the file (needed when it holds several; --list shows them)"},
    {"mesh", 0, false, "",
     "glTF: write a scene whose preview mesh is the file's mesh, instead of a preset"},
    {"list", 0, false, "", "print the file's materials (index and name) and exit"},
    {"force", 0, false, "", "replace an existing output and images"},
    {"help", 'h', false, "", "this text"},
};

const char* kHelp =
    "Usage: velvet import FILE -o PRESET.json [--material NAME|INDEX] [--mesh] [--force]\n"
    "       velvet import FILE --list\n"
    "Imports a material from glTF 2.0 (.gltf, .glb: the metallic-roughness core,\n"
    "KHR_materials_clearcoat, _sheen, _specular, _ior, _emissive_strength, _anisotropy,\n"
    "KHR_texture_transform;\n"
    "KHR_materials_pbrSpecularGlossiness is converted) or MaterialX 1.39 (.mtlx: "
    "standard_surface,\n"
    "open_pbr_surface, gltf_pbr; node graphs become Velvet graph nodes where a counterpart\n"
    "exists). Embedded images are written beside the preset as PRESET_<image>.png|jpg.\n"
    "Whatever cannot be mapped is printed as a warning, by name. Files are written atomically;\n"
    "an existing output is refused unless --force.\n"
    "Exit codes: 0 success (warnings included), 1 usage error, 2 malformed file (with the place),\n"
    "no such material, or an existing output.\n\n";

int usage(const std::string& message) {
    std::cerr << "velvet import: " << message << "\nRun 'velvet import --help' for usage.\n";
    return UsageError;
}

} // namespace

int runImport(const std::vector<std::string>& argv) {
    std::string error;
    auto args = parseArguments(argv, kOptions, &error);
    if (!args)
        return usage(error);
    if (args->has("help")) {
        std::cout << kHelp << optionsHelp(kOptions);
        return Ok;
    }
    if (args->positional.size() != 1)
        return usage("needs exactly one FILE");
    const fs::path file = args->positional[0];
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) {
        std::cerr << file.string() << ": no such file\n";
        return BadInput;
    }
    if (!isImportableFile(file))
        return usage(file.string() + ": not a glTF (.gltf, .glb) or MaterialX (.mtlx) file");
    if (args->has("list")) {
        std::vector<std::string> names;
        if (!listImportableMaterials(file, names, &error)) {
            std::cerr << error << "\n";
            return BadInput;
        }
        for (size_t i = 0; i < names.size(); ++i)
            std::cout << i << "\t" << names[i] << "\n";
        return Ok;
    }
    if (!args->has("output"))
        return usage("needs -o PRESET.json");
    const fs::path out = fs::absolute(args->value("output")).lexically_normal();
    if (out.extension() != ".json")
        return usage("-o must name a .json file");
    const std::string ext = file.extension().string();
    const bool mesh = args->has("mesh");
    if (mesh && ext != ".gltf" && ext != ".glb")
        return usage("--mesh applies to glTF files only (MaterialX holds no mesh)");
    if (!args->has("force") && fs::exists(out, ec)) {
        std::cerr << out.string() << ": exists (use --force to replace it)\n";
        return BadInput;
    }

    ImportOptions options;
    options.material = args->value("material");
    options.imageFolder = out.parent_path();
    options.imageStem = out.stem().string();
    options.force = args->has("force");
    ImportOutcome outcome = importMaterialFile(file, options);
    for (const std::string& w : outcome.warnings)
        std::cerr << "warning: " << file.string() << ": " << w << "\n";
    if (!outcome.ok()) {
        std::cerr << outcome.error << "\n";
        return BadInput;
    }
    fs::create_directories(out.parent_path(), ec); // as export makes its folder; a failure
                                                   // is said by the save below
    if (mesh && !outcome.hasMesh)
        std::cerr << "warning: " << file.string() << ": --mesh: the file holds no mesh; the "
                  << "scene keeps the sphere\n";
    bool saved;
    if (mesh) {
        Scene scene = sceneWithMaterial(outcome.material);
        if (outcome.hasMesh)
            scene.mesh = MeshRef{PreviewMeshKind::Custom, fs::absolute(file).string()};
        saved = saveSceneFile(scene, out, &error);
    } else {
        saved = saveMaterialFile(outcome.material, out, &error);
    }
    if (!saved) {
        std::cerr << error << "\n";
        return BadInput;
    }
    for (const fs::path& p : outcome.written)
        std::cout << p.string() << "\n";
    std::cout << out.string() << "\n";
    return Ok;
}

} // namespace velvet::cli
