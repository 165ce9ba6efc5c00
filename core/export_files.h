#pragma once
/// @file export_files.h
/// The files an export writes, and writing them safely (DESIGN.md, "Data safety"): names that
/// come from documents are sanitised so that nothing lands outside the chosen folder, an
/// existing file is refused unless the caller forces it, every file is written atomically.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {

/// One file of an export: its name inside the output folder (a single path component) and its
/// bytes. A multi-file export lists the files a reader follows last (a .gltf after its .bin and
/// images), so a reader never sees a document whose parts are not there yet.
struct ExportFile {
    std::string name;
    std::string bytes;
};

/// The files an exporter built in memory, and what the format could not carry: one line each
/// (a BRDF term choice, the node graph, a clamped value), never dropped silently (DESIGN.md,
/// "Interchange").
struct BuiltExport {
    std::vector<ExportFile> files;
    std::vector<std::string> warnings;
};

/// @p name reduced to a safe file stem: ASCII letters, digits, '-' and '_' are kept, every
/// other character (path separators, dots, spaces, control and non-ASCII bytes) becomes '_',
/// runs of '_' collapse and '_' is trimmed from both ends; at most 100 characters. "../../x"
/// gives "x", "Crimson velvet" "Crimson_velvet"; an empty result gives @p fallback.
std::string sanitizeFileStem(std::string_view name, std::string_view fallback = "material");

/// Why writeExportFiles() failed.
enum class ExportWriteError {
    None,
    Exists,  ///< a target exists and force was not given (nothing written)
    Unsafe,  ///< a name is not a plain file name, or would leave the folder (nothing written)
    IoError, ///< the folder could not be made, or a write failed
};

/// Writes @p files into @p folder (created when missing). Every name is checked first — a
/// single component, no "." or "..", inside the folder once resolved — and, unless @p force,
/// that no target exists; only then is anything written, each file atomically (temp file in the
/// folder, fsync, rename: core/atomic_file.h), in the order given. @p written gets the paths
/// written. On failure returns the reason and a one-line @p error naming the file.
ExportWriteError writeExportFiles(const std::filesystem::path& folder,
                                  const std::vector<ExportFile>& files, bool force,
                                  std::string* error,
                                  std::vector<std::filesystem::path>* written = nullptr);

} // namespace velvet
