#pragma once
/// @file document_io.h
/// Material presets and scenes as versioned JSON (docs/file-formats.md, resources/schemas/).
/// Loading validates everything first and builds the model only when there is no error, so a
/// caller never sees a half-read document. Every problem carries the file and its JSON path.

#include "core/diagnostics.h"
#include "core/material.h"
#include "core/scene.h"

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace velvet {

inline constexpr std::string_view kMaterialFormat = "velvet.material";
inline constexpr std::string_view kSceneFormat = "velvet.scene";
inline constexpr int kMaterialVersion = 2; ///< version 1: the seed documents' flat material
inline constexpr int kSceneVersion = 2;    ///< version 1: no `atlases` key

/// Files larger than this are refused before they are read.
inline constexpr std::uintmax_t kMaxDocumentBytes = 16u * 1024u * 1024u;
/// Deeper JSON nesting is refused while parsing.
inline constexpr int kMaxJsonDepth = 64;

enum class DocumentKind { Material, Scene, Unknown };

/// Reads only enough to tell a preset from a scene (by its "format"); Unknown on any problem.
DocumentKind detectDocumentKind(const std::filesystem::path& file);

/// Parses a material preset. @p fileName names the source in problems. Relative texture paths are
/// resolved against @p baseDir.
std::optional<Material> parseMaterial(std::string_view text, const std::string& fileName,
                                      const std::filesystem::path& baseDir, Problems& problems);
std::optional<Material> loadMaterialFile(const std::filesystem::path& file, Problems& problems);
/// Pretty JSON of the current version. Texture paths under @p baseDir are written relative to it.
std::string materialToJson(const Material& material, const std::filesystem::path& baseDir = {});
/// Atomic write (temp file + rename). On failure returns false and fills @p error.
bool saveMaterialFile(const Material& material, const std::filesystem::path& file,
                      std::string* error);

std::optional<Scene> parseScene(std::string_view text, const std::string& fileName,
                                const std::filesystem::path& baseDir, Problems& problems);
std::optional<Scene> loadSceneFile(const std::filesystem::path& file, Problems& problems);
std::string sceneToJson(const Scene& scene, const std::filesystem::path& baseDir = {});
bool saveSceneFile(const Scene& scene, const std::filesystem::path& file, std::string* error);

/// A scene showing @p material in the default scene (used when a preset is rendered alone).
Scene sceneWithMaterial(Material material);
/// The built-in default scene: the library's velvet preset on a sphere, a key light, the studio
/// HDRI. Never fails: a missing preset falls back to the default material (and is reported).
Scene defaultScene(Problems* problems = nullptr);
/// The forward peer's scene (`velvet bench --frame`, bench/peers/three, the inline-display
/// tests): the default scene with the key light's shadow off and the PBR Neutral tone map as
/// the whole post chain.
Scene forwardPeerScene();

/// The JSON Schema (draft 2020-12) generated from the parameter metadata, for
/// resources/schemas/. @p kind is Material or Scene.
std::string jsonSchema(DocumentKind kind);

} // namespace velvet
