#pragma once
/// @file atomic_file.h
/// Whole-file reads with a size limit and atomic writes (temp file in the same folder, flush,
/// rename), so a crash never leaves a half-written document.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace velvet {

/// Reads @p file; refuses files larger than @p maxBytes before reading. nullopt + @p error on
/// failure.
std::optional<std::string> readWholeFile(const std::filesystem::path& file, std::uintmax_t maxBytes,
                                         std::string* error);
/// As readWholeFile, but @p reason gets the failure without the file name ("is a folder", "is
/// 50.0 MB, more than the 16.0 MB limit"), for callers that report the file separately.
std::optional<std::string> readFileWithLimit(const std::filesystem::path& file,
                                             std::uintmax_t maxBytes, std::string* reason);
/// Writes @p data to @p file atomically. With @p keepBackup an existing file is kept as "file.bak".
bool writeFileAtomically(const std::filesystem::path& file, std::string_view data,
                         std::string* error, bool keepBackup = false);

} // namespace velvet
