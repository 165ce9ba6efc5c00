#include "core/document_io.h"

#include "core/atomic_file.h"
#include "core/json_read.h"
#include "core/json_value.h"
#include "core/light_rigs.h"
#include "core/material_json.h"
#include "core/post_effects.h"
#include "core/resources.h"
#include "core/scene_json.h"

namespace velvet {
namespace fs = std::filesystem;
namespace {

bool errorsSince(const Problems& problems, size_t before) {
    for (size_t i = before; i < problems.items.size(); ++i)
        if (problems.items[i].severity == Problem::Severity::Error)
            return true;
    return false;
}

/// Documents name their files relative to their own folder; the model holds absolute paths so
/// that the renderer can open them from any working directory.
fs::path folderOf(const fs::path& file) {
    std::error_code ec;
    const fs::path abs = fs::absolute(file, ec);
    return (ec ? file : abs).lexically_normal().parent_path();
}

std::optional<std::string> readDocument(const fs::path& file, Problems& problems) {
    std::string reason;
    auto text = readFileWithLimit(file, kMaxDocumentBytes, &reason);
    if (!text)
        problems.error(file.string(), "", reason);
    return text;
}

std::string absoluteGeneric(const fs::path& p) {
    std::error_code ec;
    const fs::path abs = fs::absolute(p, ec);
    return (ec ? p : abs).lexically_normal().generic_string();
}

} // namespace

DocumentKind detectDocumentKind(const fs::path& file) {
    Problems ignored;
    const auto text = readFileWithLimit(file, kMaxDocumentBytes, nullptr);
    if (!text)
        return DocumentKind::Unknown;
    const auto root = parseJson(*text, file.string(), ignored, kMaxJsonDepth);
    if (!root || !root->isObject())
        return DocumentKind::Unknown;
    const JsonValue* format = root->find("format");
    if (!format || format->kind != JsonValue::Kind::String)
        return DocumentKind::Unknown;
    if (format->text == kMaterialFormat)
        return DocumentKind::Material;
    if (format->text == kSceneFormat)
        return DocumentKind::Scene;
    return DocumentKind::Unknown;
}

std::optional<Material> parseMaterial(std::string_view text, const std::string& fileName,
                                      const fs::path& baseDir, Problems& problems) {
    const size_t before = problems.items.size();
    const auto root = parseJson(text, fileName, problems, kMaxJsonDepth);
    if (!root)
        return std::nullopt;
    JsonReader reader(fileName, problems);
    Material m = readMaterialJson(reader, *root, "", baseDir, MaterialPlacement::PresetFile);
    // All or nothing: a caller never sees a material built from a document with errors.
    if (errorsSince(problems, before))
        return std::nullopt;
    return m;
}

std::optional<Material> loadMaterialFile(const fs::path& file, Problems& problems) {
    const auto text = readDocument(file, problems);
    if (!text)
        return std::nullopt;
    return parseMaterial(*text, file.string(), folderOf(file), problems);
}

std::string materialToJson(const Material& material, const fs::path& baseDir) {
    return writeJson(materialToJsonValue(material, baseDir, MaterialPlacement::PresetFile));
}

bool saveMaterialFile(const Material& material, const fs::path& file, std::string* error) {
    return writeFileAtomically(file, materialToJson(material, folderOf(file)), error, true);
}

std::optional<Scene> parseScene(std::string_view text, const std::string& fileName,
                                const fs::path& baseDir, Problems& problems) {
    const size_t before = problems.items.size();
    const auto root = parseJson(text, fileName, problems, kMaxJsonDepth);
    if (!root)
        return std::nullopt;
    JsonReader reader(fileName, problems);
    Scene s = readSceneJson(reader, *root, baseDir, problems);
    if (errorsSince(problems, before))
        return std::nullopt;
    return s;
}

std::optional<Scene> loadSceneFile(const fs::path& file, Problems& problems) {
    const auto text = readDocument(file, problems);
    if (!text)
        return std::nullopt;
    return parseScene(*text, file.string(), folderOf(file), problems);
}

std::string sceneToJson(const Scene& scene, const fs::path& baseDir) {
    return writeJson(sceneToJsonValue(scene, baseDir));
}

bool saveSceneFile(const Scene& scene, const fs::path& file, std::string* error) {
    return writeFileAtomically(file, sceneToJson(scene, folderOf(file)), error, true);
}

Scene defaultScene(Problems* problems) {
    Problems ignored;
    Problems& out = problems ? *problems : ignored;
    Scene scene;
    const fs::path preset = resources::path("presets/crimson_velvet.json");
    if (auto m = loadMaterialFile(preset, out)) {
        scene.material = std::move(*m);
        scene.materialPreset = absoluteGeneric(preset);
    }
    // A warm key light from the upper left, in front of the mesh (the camera looks down -Z), so
    // the sheen shows on the lit rim and the HDRI fills the shadow side (core/light_rigs.h).
    scene.lights = *lightRigLights("key");
    scene.environment.hdri = absoluteGeneric(resources::path("hdri/studio.exr"));
    scene.environment.intensity = 1.0f;
    return scene;
}

Scene sceneWithMaterial(Material material) {
    Scene scene = defaultScene();
    scene.material = std::move(material);
    scene.materialPreset.clear();
    return scene;
}

Scene forwardPeerScene() {
    Scene scene = defaultScene();
    for (Light& light : scene.lights)
        light.castShadows = false;
    scene.post = PostChain{};
    EffectInstance tonemap = makeEffect("tonemap");
    tonemap.params["operator"] = {float(toneMapOperatorIndex("pbr-neutral"))};
    scene.post.effects.push_back(tonemap);
    return scene;
}

} // namespace velvet
