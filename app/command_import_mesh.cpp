// velvet import-mesh IN OUT (hidden): the child-process half of the crash-isolated mesh import
// (core/mesh_import.h, DESIGN.md "Data safety"). Imports IN with Assimp and writes the binary
// mesh cache OUT for the parent to read back; a crash or hang here costs the parent nothing.
#include "app/cli.h"
#include "core/mesh_import.h"

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>
#include <new>
#include <sys/resource.h>
#include <thread>
#include <vector>

namespace velvet::cli {

int runImportMesh(const std::vector<std::string>& argv) {
    const std::vector<OptionSpec> options{
        {"help", 'h', false, "", "this text"},
        {"cpu-seconds", 0, true, "S", "CPU-time limit (setrlimit RLIMIT_CPU)"},
        {"memory-mib", 0, true, "M", "address-space limit (RLIMIT_AS)"},
        {"output-mib", 0, true, "M", "size limit of what it writes (RLIMIT_FSIZE)"}};
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
    // Limits on this process before Assimp sees the file (issue 18): the parent tells each limit
    // apart by how the child ends (SIGXCPU, SIGXFSZ, exit kImportExitOutOfMemory).
    const auto limit = [&](const char* name, int resource, rlim_t scale) {
        if (!args->has(name))
            return;
        const rlim_t value = rlim_t(std::strtoull(args->value(name, "0").c_str(), nullptr, 10));
        if (value == 0)
            return;
        rlimit r{value * scale, value * scale};
        if (resource == RLIMIT_CPU)
            r.rlim_max = r.rlim_cur + 1; // SIGXCPU at the soft limit, SIGKILL a second later
        ::setrlimit(resource, &r);
    };
    limit("cpu-seconds", RLIMIT_CPU, 1);
#if !defined(__SANITIZE_ADDRESS__)
    limit("memory-mib", RLIMIT_AS, rlim_t(1) << 20);
#else
    // AddressSanitizer reserves terabytes of shadow address space at start, so any address-space
    // limit kills the child before it reads a byte ("Failed to mmap"): sanitizer builds (make
    // test-asan) import under the time and output limits only.
#endif
    limit("output-mib", RLIMIT_FSIZE, rlim_t(1) << 20);
    // Test hooks: prove that the parent survives a crashing or hanging importer.
    if (std::getenv("VELVET_IMPORT_MESH_SIMULATE_CRASH"))
        std::abort();
    if (std::getenv("VELVET_IMPORT_MESH_SIMULATE_HANG"))
        std::this_thread::sleep_for(std::chrono::hours(1));
    if (std::getenv("VELVET_IMPORT_MESH_SIMULATE_SPIN"))
        for (volatile unsigned long i = 0;; i = i + 1) {
        }
    if (std::getenv("VELVET_IMPORT_MESH_SIMULATE_HOG")) {
        std::vector<std::unique_ptr<char[]>> hog;
        try {
            for (;;) {
                hog.emplace_back(new char[64 << 20]);
                std::memset(hog.back().get(), 1, 64 << 20);
            }
        } catch (const std::bad_alloc&) {
            return kImportExitOutOfMemory;
        }
    }
    MeshData mesh;
    try {
        if (!importMeshInProcess(args->positional[0], mesh, &error)) {
            std::cerr << "velvet import-mesh: " << error << "\n";
            return BadInput;
        }
    } catch (const std::bad_alloc&) {
        return kImportExitOutOfMemory;
    }
    if (!writeMeshCache(args->positional[1], mesh, &error)) {
        std::cerr << "velvet import-mesh: " << error << "\n";
        return BadInput;
    }
    return Ok;
}

} // namespace velvet::cli
