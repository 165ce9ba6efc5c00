#include "core/document_paths.h"

namespace velvet {

namespace fs = std::filesystem;

std::string resolveDocumentPath(const std::string& documentPath, const fs::path& baseDir) {
    const fs::path p(documentPath);
    if (documentPath.empty() || baseDir.empty() || p.is_absolute())
        return documentPath;
    return (baseDir / p).lexically_normal().generic_string();
}

std::string relativeDocumentPath(const std::string& modelPath, const fs::path& baseDir) {
    const fs::path p(modelPath);
    if (modelPath.empty() || baseDir.empty() || !p.is_absolute())
        return modelPath;
    const fs::path rel = p.lexically_normal().lexically_relative(baseDir.lexically_normal());
    // Only files inside the folder become relative: "../x" would break when the document moves
    // without its parent folder.
    if (rel.empty() || rel.native().starts_with(".."))
        return modelPath;
    return rel.generic_string();
}

} // namespace velvet
