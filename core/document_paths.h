#pragma once
/// @file document_paths.h
/// File paths inside documents (internal to core's readers and writers). A document stores paths
/// relative to its own folder where it can, so a folder of presets and textures can be moved or
/// shared; the model holds them resolved.

#include <filesystem>
#include <string>

namespace velvet {

/// The model path for @p documentPath: a relative path is joined to @p baseDir and normalised;
/// an absolute path, or any path when @p baseDir is empty, is kept.
std::string resolveDocumentPath(const std::string& documentPath,
                                const std::filesystem::path& baseDir);

/// The document path for @p modelPath: relative to @p baseDir with "/" separators when the file
/// lies under it, else unchanged.
std::string relativeDocumentPath(const std::string& modelPath,
                                 const std::filesystem::path& baseDir);

} // namespace velvet
