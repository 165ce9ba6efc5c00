/// @file fuzz_import.cpp
/// libFuzzer entry points for the interchange readers: glTF 2.0 (.gltf JSON or .glb container,
/// core/gltf_import.h) and MaterialX (core/mtlx_import.h), one executable per format chosen at
/// compile time by VELVET_FUZZ_FORMAT (tests/fuzz/CMakeLists.txt). Only the readers' public
/// API is called. They take a path, so each input is written to a file in a private temporary
/// folder (the glTF reader resolves buffer and image URIs beside it, so the folder must be a
/// real one, not a memfd). Every input must be refused with a problem that says why, or give
/// materials that survive Velvet's own preset writer and reader: an imported material that
/// `velvet import` could not save as a loadable preset is a finding too (docs/reliability.md,
/// "Fuzzed parsers").

#include "core/document_io.h"
#include "core/material_import.h"
#if VELVET_FUZZ_FORMAT == 1
#include "core/gltf_import.h"
#elif VELVET_FUZZ_FORMAT == 2
#include "core/mtlx_import.h"
#else
#error "VELVET_FUZZ_FORMAT must be 1 (glTF) or 2 (MaterialX)"
#endif

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace {

namespace fs = std::filesystem;

// Created once per process and removed at a normal exit; libFuzzer may end without atexit
// handlers, so scripts/fuzz.sh points TMPDIR into the build tree and empties it each run.
const fs::path& folder() {
    static const fs::path f = [] {
        std::string pattern = (fs::temp_directory_path() / "velvet-fuzz-import-XXXXXX").string();
        if (!mkdtemp(pattern.data()))
            std::abort();
        std::atexit([] {
            std::error_code ec;
            fs::remove_all(folder(), ec);
        });
        return fs::path(pattern);
    }();
    return f;
}

void writeInput(const fs::path& file, const std::uint8_t* data, std::size_t size) {
    std::FILE* out = std::fopen(file.c_str(), "wb");
    if (!out || (size > 0 && std::fwrite(data, 1, size, out) != size) || std::fclose(out) != 0)
        std::abort();
}

// At most this many of a file's materials are imported per input: each is a full read of the
// file, and a document of many materials reaches nothing one of them cannot.
constexpr std::size_t kMaxMaterials = 4;

bool readNames(const fs::path& file, std::vector<std::string>& names,
               velvet::ImportProblem& problem) {
#if VELVET_FUZZ_FORMAT == 1
    return velvet::readGltfMaterialNames(file, names, problem);
#else
    return velvet::readMtlxMaterialNames(file, names, problem);
#endif
}

bool importOne(const fs::path& file, const std::string& select, velvet::ImportedMaterial& out,
               velvet::ImportProblem& problem) {
#if VELVET_FUZZ_FORMAT == 1
    return velvet::importGltfMaterial(file, select, folder() / "images", "fuzz", out, problem);
#else
    return velvet::importMtlxMaterial(file, select, out, problem);
#endif
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
#if VELVET_FUZZ_FORMAT == 1
    // The reader tells .glb from .gltf by the magic, not the name; name it as a user would.
    const bool glb =
        size >= 4 && std::string_view(reinterpret_cast<const char*>(data), 4) == "glTF";
    const fs::path file = folder() / (glb ? "fuzz.glb" : "fuzz.gltf");
#else
    const fs::path file = folder() / "fuzz.mtlx";
#endif
    writeInput(file, data, size);
    std::vector<std::string> names;
    velvet::ImportProblem problem;
    if (!readNames(file, names, problem)) {
        if (problem.message.empty())
            std::abort(); // a refusal always says why
        return 0;
    }
    for (std::size_t i = 0; i < names.size() && i < kMaxMaterials; ++i) {
        velvet::ImportedMaterial imported;
        velvet::ImportProblem refused;
        if (!importOne(file, std::to_string(i), imported, refused)) {
            if (refused.message.empty())
                std::abort();
            continue;
        }
        // What `velvet import` saves must load again as a preset.
        const std::string json = velvet::materialToJson(imported.material, folder());
        velvet::Problems problems;
        if (!velvet::parseMaterial(json, "imported.json", folder(), problems)) {
            for (const velvet::Problem& p : problems.items)
                std::fprintf(stderr, "%s\n", p.toString().c_str());
            std::abort();
        }
    }
    return 0;
}
