#pragma once
/// @file mesh_nesting.h
/// How deeply a text mesh file nests, measured before a parser sees it: Assimp's glTF (rapidjson)
/// and COLLADA (irrXML) readers recurse once per level and overflow the child's stack on a file
/// nested a few hundred thousand levels deep (BENCHMARKS.md, "Data safety"). A scan that counts
/// levels without recursing refuses such a file with a message instead of a crash.

#include <cstddef>
#include <string_view>

namespace velvet {

/// No mesh file of any exporter we know nests deeper than a few dozen levels.
inline constexpr std::size_t kMaxMeshFileNesting = 256;

/// Deepest nesting of JSON arrays and objects in @p text (brackets inside strings are skipped),
/// counted up to @p stopAt and no further.
std::size_t jsonNestingDepth(std::string_view text, std::size_t stopAt = kMaxMeshFileNesting + 1);

/// Deepest nesting of XML elements in @p text (comments, CDATA, processing instructions,
/// declarations and self-closing tags do not nest), counted up to @p stopAt.
std::size_t xmlNestingDepth(std::string_view text, std::size_t stopAt = kMaxMeshFileNesting + 1);

} // namespace velvet

#include <filesystem>
#include <string>

namespace velvet {

/// For the text formats that nest (.gltf, the JSON chunk of .glb, .dae): false + one line naming
/// the file and the depth when it nests deeper than kMaxMeshFileNesting. Other formats pass.
bool checkMeshNesting(const std::filesystem::path& file, const std::string& lowerExtension,
                      std::string* error);

} // namespace velvet
