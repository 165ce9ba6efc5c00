#pragma once
/// @file shipped_schema.h
/// The one check every test of a generated schema runs: the file shipped in resources/schemas/ is
/// exactly the text the code generates. One switch regenerates them all:
///   VELVET_UPDATE_SCHEMAS=1 ctest --test-dir build -R
///   'test_core_(document_io|atlas_document|post_chain)'

#include "core/atomic_file.h"

#include <cstdlib>
#include <filesystem>
#include <string>

namespace velvet::test {

/// The environment variable that makes the schema tests rewrite the shipped files.
inline constexpr const char* kUpdateSchemasVariable = "VELVET_UPDATE_SCHEMAS";

/// Compares @p shipped with @p generated; first rewrites it (atomically) when
/// VELVET_UPDATE_SCHEMAS is 1. Returns "" when they match, else one line saying what is wrong and
/// how to regenerate.
inline std::string checkShippedSchema(const std::filesystem::path& shipped,
                                      const std::string& generated) {
    std::string error;
    const char* update = std::getenv(kUpdateSchemasVariable);
    if (update && std::string(update) == "1" && !writeFileAtomically(shipped, generated, &error))
        return error;
    const auto text = readWholeFile(shipped, 1 << 24, &error);
    if (!text)
        return error;
    if (*text != generated)
        return shipped.filename().string() + " is out of date; regenerate with " +
               kUpdateSchemasVariable + "=1 ctest --test-dir build -R " +
               "'test_core_(document_io|atlas_document|post_chain)'";
    return {};
}

} // namespace velvet::test
