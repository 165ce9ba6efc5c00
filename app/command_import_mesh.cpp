// velvet import-mesh IN OUT (hidden): the child-process half of the crash-isolated mesh import
// (core/mesh_import.h, DESIGN.md "Data safety"). Imports IN with Assimp and writes the binary
// mesh cache OUT for the parent to read back; a crash or hang here costs the parent nothing.
#include "app/cli.h"
#include "core/mesh_import.h"

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <thread>

namespace velvet::cli {

int runImportMesh(const std::vector<std::string>& argv) {
    const std::vector<OptionSpec> options{{"help", 'h', false, "", "this text"}};
    std::string error;
    auto args = parseArguments(argv, options, &error);
    if (args && args->has("help")) {
        std::cout << "Usage: velvet import-mesh IN OUT\nImports the mesh file IN (OBJ, FBX, "
                     "glTF/GLB, PLY, STL, DAE) and writes Velvet's binary mesh cache OUT "
                     "(core/mesh_import.h). Used by Velvet itself to import in a child process.\n\n"
                  << optionsHelp(options);
        return Ok;
    }
    if (!args || args->positional.size() != 2) {
        std::cerr << "velvet import-mesh: " << (args ? "needs IN and OUT" : error) << "\n";
        return UsageError;
    }
    // Test hooks: prove that the parent survives a crashing or hanging importer.
    if (std::getenv("VELVET_IMPORT_MESH_SIMULATE_CRASH"))
        std::abort();
    if (std::getenv("VELVET_IMPORT_MESH_SIMULATE_HANG"))
        std::this_thread::sleep_for(std::chrono::hours(1));
    MeshData mesh;
    if (!importMeshInProcess(args->positional[0], mesh, &error)) {
        std::cerr << "velvet import-mesh: " << error << "\n";
        return BadInput;
    }
    if (!writeMeshCache(args->positional[1], mesh, &error)) {
        std::cerr << "velvet import-mesh: " << error << "\n";
        return BadInput;
    }
    return Ok;
}

} // namespace velvet::cli
