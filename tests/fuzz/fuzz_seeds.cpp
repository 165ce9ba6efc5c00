/// @file fuzz_seeds.cpp
/// Writes the generated part of the fuzzers' seed corpora into the folder named on the command
/// line: a default scene, an atlas document and mesh caches of the procedural meshes. (The
/// shipped presets and post chains and the tests' malformed files are seeds as they are.)

#include "core/atlas_document.h"
#include "core/document_io.h"
#include "core/mesh.h"
#include "core/mesh_import.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: fuzz_seeds FOLDER\n");
        return 2;
    }
    const fs::path root = argv[1];
    for (const char* kind : {"scene", "atlas", "mesh_cache"})
        fs::create_directories(root / kind);
    std::ofstream(root / "scene" / "default.json") << velvet::sceneToJson(velvet::defaultScene());
    std::ofstream(root / "atlas" / "two_regions.json")
        << R"({"format": "velvet.atlas", "version": 1, "atlases": {"albedo": {
              "width": 16, "height": 16, "padding": 1, "entries": [
              {"name": "a", "file": "a.png", "region": [0, 0, 8, 8]},
              {"name": "b", "file": "b.png", "region": [8, 8, 8, 8]}]}}})";
    std::string error;
    if (!velvet::writeMeshCache(root / "mesh_cache" / "cube.vmesh", velvet::makeCube(), &error) ||
        !velvet::writeMeshCache(root / "mesh_cache" / "plane.vmesh", velvet::makePlane(1.0f, 2),
                                &error)) {
        std::fprintf(stderr, "fuzz_seeds: %s\n", error.c_str());
        return 1;
    }
    return 0;
}
