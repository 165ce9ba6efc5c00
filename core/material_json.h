#pragma once
/// @file material_json.h
/// Material presets as JSON (internal to core; the public API is document_io.h). Reading,
/// writing and the schema are all generated from the parameter and texture-slot metadata: a
/// parameter id "lobes.base.roughness" is the object path lobes → base → roughness.

#include "core/json_read.h"
#include "core/json_value.h"
#include "core/material.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {

/// The parameter ids as a tree of object keys, in metadata order.
struct ParamNode {
    std::string_view key;               ///< "" at the root
    int param = -1;                     ///< ParamId of a leaf, -1 for an object
    std::vector<ParamNode> children;    ///< empty for a leaf
    std::vector<std::string_view> keys; ///< the children's keys (allowed keys of this object)
};
const ParamNode& paramTree();

/// Where a material object sits: alone in a preset file (format, version and name required), or
/// inline in a scene (all three optional).
enum class MaterialPlacement { PresetFile, InlineInScene };

/// Reads the material object @p v at @p path (version 2, or version 1 migrated), recording every
/// problem in @p reader. Relative texture paths resolve against @p baseDir. The result is
/// meaningful only when the reader has no errors.
Material readMaterialJson(JsonReader& reader, const JsonValue& v, const std::string& path,
                          const std::filesystem::path& baseDir, MaterialPlacement placement);

/// The material as a current-version object; texture paths under @p baseDir are made relative.
JsonValue materialToJsonValue(const Material& m, const std::filesystem::path& baseDir,
                              MaterialPlacement placement);

/// Reads "format" and "version" of a document root. Wrong format, a version that is not a
/// positive integer, or a newer version than @p current are errors after which the body cannot be
/// read: nullopt. A missing required key is reported and @p current assumed.
std::optional<int> readFormatAndVersion(JsonReader& reader, const JsonValue& root,
                                        const std::string& path, std::string_view format,
                                        int current, bool required);

} // namespace velvet
