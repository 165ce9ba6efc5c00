#include "core/export_files.h"

#include "core/atomic_file.h"

#include <set>
#include <system_error>

namespace velvet {

namespace fs = std::filesystem;

std::string sanitizeFileStem(std::string_view name, std::string_view fallback) {
    std::string out;
    for (const char c : name) {
        const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                          (c >= '0' && c <= '9') || c == '-' || c == '_';
        const char mapped = keep ? c : '_';
        if (mapped == '_' && (out.empty() || out.back() == '_'))
            continue; // collapse runs; no leading '_'
        out += mapped;
        if (out.size() >= 100)
            break;
    }
    while (!out.empty() && out.back() == '_')
        out.pop_back();
    return out.empty() ? std::string(fallback) : out;
}

namespace {

/// True when @p name is one plain path component (no separator, not "." or "..", not empty).
bool isPlainName(const std::string& name) {
    if (name.empty() || name == "." || name == ".." || name.size() > 255)
        return false;
    for (const char c : name)
        if (c == '/' || c == '\\' || c == '\0')
            return false;
    return true;
}

} // namespace

ExportWriteError writeExportFiles(const fs::path& folder, const std::vector<ExportFile>& files,
                                  bool force, std::string* error, std::vector<fs::path>* written) {
    auto fail = [&](ExportWriteError why, const std::string& message) {
        if (error)
            *error = message;
        return why;
    };
    const fs::path dir = folder.empty() ? fs::path(".") : folder;
    std::error_code ec;
    // Every check before the first write: an export is refused whole, never half-written.
    std::set<std::string> seen;
    for (const ExportFile& f : files) {
        if (!isPlainName(f.name))
            return fail(ExportWriteError::Unsafe, "refusing to write \"" + f.name +
                                                      "\": not a plain file name inside " +
                                                      dir.string());
        if (!seen.insert(f.name).second)
            return fail(ExportWriteError::Unsafe, "two outputs share the name \"" + f.name + "\"");
        const fs::path target = dir / f.name;
        const fs::file_status st = fs::symlink_status(target, ec);
        if (fs::exists(st)) {
            // A link could point anywhere: replacing it writes a new file in the folder, but
            // refuse anyway so that --force never follows a link out of the folder.
            if (fs::is_symlink(st))
                return fail(ExportWriteError::Unsafe,
                            target.string() + ": is a symbolic link; refusing to replace it");
            if (fs::is_directory(st))
                return fail(ExportWriteError::IoError, target.string() + ": is a folder");
            if (!force)
                return fail(ExportWriteError::Exists,
                            target.string() + ": exists; use --force to replace it");
        }
    }
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
        return fail(ExportWriteError::IoError,
                    "cannot create the folder " + dir.string() + ": " + ec.message());
    // Resolved once created: a name that is a plain component cannot leave it, and this
    // asserts the folder a file lands in is the folder asked for.
    const fs::path canonicalDir = fs::canonical(dir, ec);
    for (const ExportFile& f : files) {
        const fs::path target = dir / f.name;
        if (!ec && fs::weakly_canonical(target, ec).parent_path() != canonicalDir)
            return fail(ExportWriteError::Unsafe, "refusing to write " + target.string() +
                                                      ": it would leave " + dir.string());
        std::string why;
        if (!writeFileAtomically(target, f.bytes, &why))
            return fail(ExportWriteError::IoError, why);
        if (written)
            written->push_back(target);
    }
    return ExportWriteError::None;
}

} // namespace velvet
