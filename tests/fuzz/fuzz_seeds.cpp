/// @file fuzz_seeds.cpp
/// Writes the generated part of the fuzzers' seed corpora into the folder named on the command
/// line: a default scene, an atlas document, mesh caches of the procedural meshes, and each
/// shipped preset (the folder named second) exported by Velvet's own writers as a .glb, a .gltf
/// and a .mtlx of each MaterialX shader. (The shipped presets and post chains, the tests'
/// malformed files and the hand-written files in tests/fuzz/seeds are seeds as they are.)

#include "core/atlas_document.h"
#include "core/color_management.h"
#include "core/document_io.h"
#include "core/gltf_export.h"
#include "core/mesh.h"
#include "core/mesh_import.h"
#include "core/mtlx_export.h"
#include "core/texture_cache.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {

// RFC 4648 base64, for the data: URI a seed .gltf carries its buffer in.
std::string base64(const std::string& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const size_t n = std::min<size_t>(3, bytes.size() - i);
        std::uint32_t v = 0;
        for (size_t k = 0; k < 3; ++k)
            v = (v << 8) | (k < n ? std::uint8_t(bytes[i + k]) : 0u);
        for (size_t k = 0; k < 4; ++k)
            out += k <= n ? digits[(v >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

// A .gltf seed must stand alone (the fuzzer writes one file): its .bin goes inline.
std::string inlineBuffers(const velvet::BuiltExport& built) {
    std::string json;
    for (const velvet::ExportFile& f : built.files)
        if (f.name.ends_with(".gltf"))
            json = f.bytes;
    for (const velvet::ExportFile& f : built.files) {
        if (!f.name.ends_with(".bin"))
            continue;
        const std::string quoted = "\"" + f.name + "\"";
        const size_t at = json.find(quoted);
        if (at != std::string::npos)
            json.replace(at, quoted.size(),
                         "\"data:application/octet-stream;base64," + base64(f.bytes) + "\"");
    }
    return json;
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: fuzz_seeds FOLDER PRESETS\n");
        return 2;
    }
    const fs::path root = argv[1];
    for (const char* kind : {"scene", "atlas", "mesh_cache", "gltf", "mtlx"})
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
    // The exporters' output: every extension and shader input Velvet writes, on a small mesh so
    // a .glb stays under the fuzzers' 64 KiB input limit. The presets have no texture files.
    velvet::ColorManagement colorManagement;
    velvet::TextureCache textures(colorManagement);
    const velvet::MeshData plane = velvet::makePlane(1.0f, 1);
    for (const auto& entry : fs::directory_iterator(argv[2])) {
        if (entry.path().extension() != ".json")
            continue;
        velvet::Problems problems;
        const auto material = velvet::loadMaterialFile(entry.path(), problems);
        if (!material) {
            std::fprintf(stderr, "fuzz_seeds: %s does not load\n", entry.path().c_str());
            return 1;
        }
        const std::string stem = entry.path().stem().string();
        velvet::BuiltExport built;
        for (const auto container : {velvet::GltfContainer::Glb, velvet::GltfContainer::Gltf}) {
            built = {};
            if (!velvet::buildGltf(*material, plane, stem, container, textures, built, &error)) {
                std::fprintf(stderr, "fuzz_seeds: %s: %s\n", stem.c_str(), error.c_str());
                return 1;
            }
            const std::string name =
                stem + (container == velvet::GltfContainer::Glb ? ".glb" : ".gltf");
            for (const velvet::ExportFile& f : built.files)
                if (f.name.ends_with(".glb"))
                    std::ofstream(root / "gltf" / name, std::ios::binary) << f.bytes;
            if (container == velvet::GltfContainer::Gltf)
                std::ofstream(root / "gltf" / name, std::ios::binary) << inlineBuffers(built);
        }
        for (int shader = 0; shader < int(velvet::MtlxShader::Count); ++shader) {
            built = {};
            const auto s = static_cast<velvet::MtlxShader>(shader);
            const std::string base = stem + "_" + std::string(velvet::mtlxShaderId(s));
            if (!velvet::buildMtlx(*material, base, s, textures, built, &error)) {
                std::fprintf(stderr, "fuzz_seeds: %s: %s\n", base.c_str(), error.c_str());
                return 1;
            }
            for (const velvet::ExportFile& f : built.files)
                if (f.name.ends_with(".mtlx"))
                    std::ofstream(root / "mtlx" / f.name, std::ios::binary) << f.bytes;
        }
    }
    return 0;
}
