#include "core/material_export.h"

#include "core/color_management.h"
#include "core/document_io.h"
#include "core/gltf_export.h"
#include "core/mesh_import.h"
#include "core/texture_cache.h"

#include <array>
#include <memory>

namespace velvet {
namespace {

constexpr std::array<std::string_view, size_t(ExportFormat::Count)> kIds{"glb", "gltf", "preset",
                                                                         "mtlx"};
constexpr std::array<std::string_view, size_t(ExportFormat::Count)> kExtensions{".glb", ".gltf",
                                                                                ".json", ".mtlx"};

ExportOutcome failure(ExportOutcome::Status status, std::string error) {
    ExportOutcome o;
    o.status = status;
    o.error = std::move(error);
    return o;
}

bool loadMesh(const MeshRef& ref, MeshData& mesh, std::string* error) {
    if (ref.kind != PreviewMeshKind::Custom) {
        mesh = makePreviewMesh(ref.kind);
        return true;
    }
    if (ref.file.empty()) {
        *error = "mesh: a custom mesh needs a file";
        return false;
    }
    return importMesh(ref.file, mesh, error);
}

} // namespace

std::string_view exportFormatId(ExportFormat format) {
    return kIds[size_t(format)];
}

std::optional<ExportFormat> exportFormatFromId(std::string_view id) {
    for (size_t i = 0; i < kIds.size(); ++i)
        if (kIds[i] == id)
            return ExportFormat(i);
    return std::nullopt;
}

std::string_view exportFormatExtension(ExportFormat format) {
    return kExtensions[size_t(format)];
}

ExportOutcome exportMaterial(const Scene& scene, const std::filesystem::path& folder,
                             std::string_view baseName, const ExportOptions& options,
                             TextureCache* textures) {
    const std::string base = sanitizeFileStem(baseName);
    std::vector<ExportFile> files;
    std::vector<std::string> warnings;
    if (options.format == ExportFormat::Preset) {
        // The native format carries everything (graph, BRDF terms, regions): no warnings.
        // Texture paths inside the folder become relative, others stay absolute.
        files.push_back(
            {base + ".json", materialToJson(scene.material, std::filesystem::absolute(folder))});
    } else {
        std::string error;
        std::unique_ptr<ColorManagement> ownColour;
        std::unique_ptr<TextureCache> ownCache;
        if (!textures) {
            ownColour = std::make_unique<ColorManagement>();
            if (!ownColour->loadDefault(&error))
                return failure(ExportOutcome::Status::BadInput, error);
            ownCache = std::make_unique<TextureCache>(*ownColour);
            textures = ownCache.get();
        }
        BuiltExport built;
        if (options.format == ExportFormat::Mtlx) {
            // A MaterialX document has no mesh: it is assigned in the renderer that reads it.
            if (!buildMtlx(scene.material, base, options.shader, *textures, built, &error,
                           options.baked))
                return failure(ExportOutcome::Status::BadInput, error);
        } else {
            MeshData mesh;
            if (!loadMesh(options.mesh.value_or(scene.mesh), mesh, &error))
                return failure(ExportOutcome::Status::BadInput, error);
            const auto container =
                options.format == ExportFormat::Glb ? GltfContainer::Glb : GltfContainer::Gltf;
            if (!buildGltf(scene.material, mesh, base, container, *textures, built, &error,
                           options.baked))
                return failure(ExportOutcome::Status::BadInput, error);
        }
        files = std::move(built.files);
        warnings = std::move(built.warnings);
    }
    ExportOutcome outcome;
    outcome.warnings = std::move(warnings);
    std::string error;
    switch (writeExportFiles(folder, files, options.force, &error, &outcome.written)) {
    case ExportWriteError::None:
        return outcome;
    case ExportWriteError::Exists:
        outcome.status = ExportOutcome::Status::Exists;
        break;
    case ExportWriteError::Unsafe:
    case ExportWriteError::IoError:
        outcome.status = ExportOutcome::Status::Failed;
        break;
    }
    outcome.error = error;
    return outcome;
}

} // namespace velvet
