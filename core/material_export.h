#pragma once
/// @file material_export.h
/// Exporting a scene's material — the one entry point the CLI (`velvet export`) and the
/// editor's File > Export… share: glTF 2.0 (.glb / .gltf, core/gltf_export.h) on the scene's or
/// a chosen preview mesh, MaterialX 1.39 (core/mtlx_export.h), or a standalone Velvet preset.
/// docs/interchange.md.

#include "core/baked_maps.h"
#include "core/export_files.h"
#include "core/mtlx_export.h"
#include "core/scene.h"

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {

class TextureCache;

enum class ExportFormat { Glb, Gltf, Preset, Mtlx, Count };

/// "glb", "gltf", "preset", "mtlx" (the CLI's -f values) and back.
std::string_view exportFormatId(ExportFormat format);
std::optional<ExportFormat> exportFormatFromId(std::string_view id);
/// The main file's extension: ".glb", ".gltf", ".json", ".mtlx".
std::string_view exportFormatExtension(ExportFormat format);

struct ExportOptions {
    ExportFormat format = ExportFormat::Glb;
    /// The mesh the material is shown on (glTF only); nullopt: the scene's preview mesh.
    std::optional<MeshRef> mesh;
    /// The MaterialX shader node (-f mtlx only).
    MtlxShader shader = MtlxShader::StandardSurface;
    /// Replace existing files; without it an existing target refuses the whole export.
    bool force = false;
    /// Width and height of the graph's baked maps (glTF, MaterialX), 1 to 8192.
    int bakeSize = 1024;
    /// The graph's maps baked at bakeSize (render/baked_export.h bakes them); null: a graph is
    /// not baked, a warning names what it drives and its inputs' parameters are exported.
    const BakedMaterialMaps* baked = nullptr;
};

/// What an export did.
struct ExportOutcome {
    enum class Status {
        Ok,
        BadInput, ///< a texture or the mesh could not be read (nothing written)
        Exists,   ///< a target exists and force was not set (nothing written)
        Failed,   ///< a name was unsafe or a write failed
    };
    Status status = Status::Ok;
    std::vector<std::filesystem::path> written; ///< every file written, the main file last
    std::vector<std::string> warnings;          ///< what the format cannot carry, one line each
    std::string error;                          ///< one line when status is not Ok
    bool ok() const { return status == Status::Ok; }
};

/// Exports @p scene's material into @p folder as BASE + the format's extension (and, for
/// .gltf, BASE.bin and BASE_<map>.png beside it; for .mtlx the PNG images). @p baseName is
/// sanitised here (sanitizeFileStem), so a name taken from a document cannot leave @p folder.
/// Textures are read through @p textures when given (the editor's cache), else through a cache of
/// its own on the default OpenColorIO config. Custom meshes are imported crash-isolated
/// (core/mesh_import.h). Nothing is written unless every file could be built.
ExportOutcome exportMaterial(const Scene& scene, const std::filesystem::path& folder,
                             std::string_view baseName, const ExportOptions& options,
                             TextureCache* textures = nullptr);

} // namespace velvet
