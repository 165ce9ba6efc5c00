#pragma once
/// @file material_import.h
/// Bringing a material in from glTF 2.0 (.gltf / .glb, core/gltf_import.h) or MaterialX 1.39
/// (.mtlx, core/mtlx_import.h) — the one entry point the CLI (`velvet import`) and the editor's
/// File > Import… and drops share. Nothing is dropped silently: whatever the file holds that
/// Velvet cannot map is one warning line naming it; a malformed file (broken JSON or XML, a
/// dangling reference, a missing buffer, a value outside the format's range) is refused with
/// the file and the place. Embedded images are written beside the preset, atomically, under
/// sanitised names that cannot leave the chosen folder (core/export_files.h).
/// docs/interchange.md, "Import".

#include "core/export_files.h"
#include "core/material.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {

/// Why a file could not be imported, and where.
struct ImportProblem {
    enum class Kind {
        Malformed, ///< the file breaks its format (syntax, references, ranges, missing data)
        Selection, ///< several materials and none chosen, or no material of the chosen name
    };
    Kind kind = Kind::Malformed;
    std::string place;   ///< "line 3, column 7", "materials[0].pbrMetallicRoughness.metallicFactor"
    std::string message; ///< what is wrong
};

/// What one format's reader made of one material.
struct ImportedMaterial {
    Material material;
    /// Images the file embeds (glTF buffer views and data: URIs), to be written into the image
    /// folder under these names; the material's slots already name them there.
    std::vector<ExportFile> images;
    std::vector<std::string> warnings; ///< one line per thing not mapped, naming it
    bool hasMesh = false;              ///< glTF: the file holds a mesh (a preview mesh candidate)
};

/// The material that @p select names among @p names: an index ("0", "2"), else an exact name;
/// empty: the only one. False + @p problem (Selection, listing them) when that is ambiguous or
/// matches none, (Malformed) when there are none.
bool selectMaterial(const std::vector<std::string>& names, std::string_view select, size_t& index,
                    ImportProblem& problem);

struct ImportOptions {
    std::string material; ///< NAME or INDEX; empty: the file's only material
    /// Where embedded images are written (the preset's folder); created when missing.
    std::filesystem::path imageFolder;
    /// Embedded images are named STEM_<image name>.<ext> (STEM sanitised; default: the file's).
    std::string imageStem;
    bool force = false; ///< replace existing images (otherwise an existing one refuses the import)
};

struct ImportOutcome {
    enum class Status {
        Ok,
        Malformed, ///< the file is broken (exit 2)
        Selection, ///< several materials and none chosen, or none of that name (exit 2)
        Exists,    ///< an image to write exists and force was not set (nothing written)
        Failed,    ///< unknown format, an unreadable file, or a write failed
    };
    Status status = Status::Ok;
    Material material;
    bool hasMesh = false;
    std::vector<std::string> materialNames;     ///< every material of the file, in file order
    std::vector<std::string> warnings;          ///< one line each
    std::vector<std::filesystem::path> written; ///< embedded images written
    std::string error;                          ///< "FILE: PLACE: MESSAGE" when status is not Ok
    bool ok() const { return status == Status::Ok; }
};

/// ".gltf", ".glb", ".mtlx".
bool isImportableFile(const std::filesystem::path& file);
/// The names of @p file's materials (unnamed ones as ""), in file order. False + @p error
/// ("FILE: PLACE: MESSAGE") when the file cannot be read.
bool listImportableMaterials(const std::filesystem::path& file, std::vector<std::string>& names,
                             std::string* error);
/// Reads the chosen material of @p file and writes its embedded images (nothing is written when
/// anything fails).
ImportOutcome importMaterialFile(const std::filesystem::path& file, const ImportOptions& options);

} // namespace velvet
