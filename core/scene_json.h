#pragma once
/// @file scene_json.h
/// Scenes as JSON (internal to core; the public API is document_io.h).

#include "core/json_read.h"
#include "core/json_value.h"
#include "core/scene.h"

#include <filesystem>
#include <string>

namespace velvet {

/// Reads a scene document root, recording every problem in @p reader (a material preset the scene
/// names is loaded and reports its own problems into @p problems). Relative paths resolve against
/// @p baseDir. The result is meaningful only when the reader has no errors.
Scene readSceneJson(JsonReader& reader, const JsonValue& root, const std::filesystem::path& baseDir,
                    Problems& problems);

/// The scene as a current-version document; the material is written inline.
JsonValue sceneToJsonValue(const Scene& scene, const std::filesystem::path& baseDir);

} // namespace velvet
