#pragma once
/// @file scene_document.h
/// A scene with the atlases it names, saved as one document: what the editor's Save does and the
/// CLI can do without Qt (docs/file-formats.md, "Scenes" and "Atlases").

#include "core/atlas_document.h"
#include "core/diagnostics.h"
#include "core/scene.h"

#include <filesystem>
#include <optional>

namespace velvet {

/// A scene and its atlases (Scene::atlases names the atlas file; empty: none).
struct SceneDocument {
    Scene scene;
    AtlasSet atlases;
};

/// Where the atlases of a scene saved as @p sceneFile go: "<stem>.atlas.json" beside it.
std::filesystem::path atlasFileFor(const std::filesystem::path& sceneFile);

/// Saves @p document as @p sceneFile. First, when any atlas has an entry, the atlases go to
/// atlasFileFor(@p sceneFile) (saveAtlasFile: sources that exist only in memory are written beside
/// it as float EXR); then the scene, naming that file by its absolute path, or naming none when
/// there are no atlases. Every file is written atomically (temp file + rename, a backup of the
/// previous one). Returns the document as saved (its scene names the atlas file, its atlases'
/// sources name their files), for the caller to adopt; on failure nothing, with one error in
/// @p problems naming the file that could not be written. The atlases are written before the
/// scene, so a failed atlas write leaves the scene file untouched.
std::optional<SceneDocument> saveSceneDocument(const SceneDocument& document,
                                               const std::filesystem::path& sceneFile,
                                               Problems& problems);

} // namespace velvet
