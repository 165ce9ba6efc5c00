#include "core/scene_document.h"

#include "core/document_io.h"

#include <string>

namespace velvet {

std::filesystem::path atlasFileFor(const std::filesystem::path& sceneFile) {
    return sceneFile.parent_path() / (sceneFile.stem().string() + ".atlas.json");
}

std::optional<SceneDocument> saveSceneDocument(const SceneDocument& document,
                                               const std::filesystem::path& sceneFile,
                                               Problems& problems) {
    // Work on a copy: saveAtlasFile names the sources it writes as it goes, and the caller's
    // document must not be half updated when a later write fails.
    SceneDocument saved = document;
    saved.scene.atlases.clear();
    std::string error;
    if (!saved.atlases.empty()) {
        const std::filesystem::path atlasFile = atlasFileFor(sceneFile);
        if (!saveAtlasFile(saved.atlases, atlasFile, &error)) {
            // The message already names the file (atomic_file.h, atlas_document.h).
            problems.error("", "", error);
            return std::nullopt;
        }
        // Absolute, as the scene's other file references are held in memory; the scene writer
        // stores it relative to the scene's folder.
        saved.scene.atlases =
            std::filesystem::absolute(atlasFile).lexically_normal().generic_string();
    }
    if (!saveSceneFile(saved.scene, sceneFile, &error)) {
        problems.error("", "", error);
        return std::nullopt;
    }
    return saved;
}

} // namespace velvet
