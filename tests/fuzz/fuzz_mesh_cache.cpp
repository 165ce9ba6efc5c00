/// @file fuzz_mesh_cache.cpp
/// libFuzzer entry point for the mesh cache reader (core/mesh_import.h), the one binary format
/// Velvet reads from another process. The reader takes a path, so each input is written to an
/// anonymous in-memory file (memfd) and read through /proc/self/fd.

#include "core/mesh_import.h"

#include <cstdint>
#include <cstdlib>
#include <string>
#include <sys/mman.h>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const int fd = memfd_create("velvet-fuzz-mesh", MFD_CLOEXEC);
    if (fd < 0)
        std::abort();
    std::size_t written = 0;
    while (written < size) {
        const ssize_t n = write(fd, data + written, size - written);
        if (n <= 0)
            std::abort();
        written += std::size_t(n);
    }
    velvet::MeshData mesh;
    std::string error;
    velvet::MeshImportLimits limits;
    limits.maxTriangles = 100'000; // keep each run small; the check itself is what is fuzzed
    const bool ok =
        velvet::readMeshCache("/proc/self/fd/" + std::to_string(fd), mesh, &error, limits);
    close(fd);
    // A mesh the reader accepts is safe to draw: every index names a vertex.
    if (ok) {
        for (const std::uint32_t index : mesh.indices)
            if (index >= mesh.vertices.size())
                std::abort();
        if (mesh.indices.size() % 3 != 0)
            std::abort();
    } else if (error.empty()) {
        std::abort(); // a refusal always says why
    }
    return 0;
}
