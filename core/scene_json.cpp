#include "core/scene_json.h"

#include "core/document_io.h"
#include "core/document_paths.h"
#include "core/material_json.h"
#include "core/post_chain_json.h"
#include "core/scene_fields.h"

#include <algorithm>
#include <array>
#include <glm/geometric.hpp>
#include <vector>

namespace velvet {
namespace fs = std::filesystem;
namespace {

constexpr std::array<std::string_view, 10> kSceneKeys{
    "format", "version",  "camera",         "lights", "environment",
    "mesh",   "material", "materialPreset", "post",   "atlases"};
constexpr std::array<std::string_view, 1> kPostKeys{"effects"};

template <class S>
std::vector<std::string_view> keysOf(std::span<const Field<S>> fields) {
    std::vector<std::string_view> keys;
    for (const Field<S>& f : fields)
        keys.push_back(f.key);
    return keys;
}

template <class S>
void readField(JsonReader& r, const JsonValue& v, const std::string& path, const Field<S>& f,
               const fs::path& baseDir, S& out) {
    switch (f.kind) {
    case FieldKind::Number:
        if (auto x = r.number(v, path, f.range))
            out.*f.number = static_cast<float>(*x);
        break;
    case FieldKind::Vec2:
        if (auto x = r.vec2(v, path, f.range))
            out.*f.vec2 = *x;
        break;
    case FieldKind::Vec3:
        if (auto x = r.vec3(v, path, f.range))
            out.*f.vec3 = *x;
        break;
    case FieldKind::Bool:
        if (auto x = r.boolean(v, path))
            out.*f.flag = *x;
        break;
    case FieldKind::Text:
        if (auto x = r.string(v, path))
            out.*f.text = *x;
        break;
    case FieldKind::Path:
        if (auto x = r.string(v, path)) {
            out.*f.text = resolveDocumentPath(*x, baseDir);
            std::error_code ec;
            if (!x->empty() && !fs::exists(out.*f.text, ec))
                r.warning(path, "file not found: \"" + out.*f.text +
                                    "\" (the renderer falls back to its default)");
        }
        break;
    case FieldKind::Choice:
        if (auto x = r.choice(v, path, f.choices))
            f.setChoice(out, *x);
        break;
    }
}

template <class S>
void readFields(JsonReader& r, const JsonValue& v, const std::string& path,
                std::span<const Field<S>> fields, const fs::path& baseDir, S& out) {
    const std::vector<std::string_view> keys = keysOf(fields);
    if (!r.expectObject(v, path, keys))
        return;
    for (const Field<S>& f : fields) {
        const JsonValue* value = f.required ? r.require(v, path, f.key) : v.find(f.key);
        if (value)
            readField(r, *value, jsonPathKey(path, f.key), f, baseDir, out);
    }
}

template <class S>
bool sameAsDefault(const Field<S>& f, const S& s) {
    static const S def{};
    switch (f.kind) {
    case FieldKind::Number:
        return s.*f.number == def.*f.number;
    case FieldKind::Vec2:
        return s.*f.vec2 == def.*f.vec2;
    case FieldKind::Vec3:
        return s.*f.vec3 == def.*f.vec3;
    case FieldKind::Bool:
        return s.*f.flag == def.*f.flag;
    case FieldKind::Text:
    case FieldKind::Path:
        return s.*f.text == def.*f.text;
    case FieldKind::Choice:
        return f.getChoice(s) == f.getChoice(def);
    }
    return false;
}

JsonValue floats(std::initializer_list<float> values) {
    JsonValue a = JsonValue::makeArray();
    for (float x : values)
        a.push(JsonValue::makeFloat(x));
    return a;
}

template <class S>
JsonValue writeFields(const S& s, std::span<const Field<S>> fields, const fs::path& baseDir) {
    JsonValue o = JsonValue::makeObject();
    for (const Field<S>& f : fields) {
        if (f.relevant && !f.relevant(s) && sameAsDefault(f, s))
            continue;
        JsonValue v;
        switch (f.kind) {
        case FieldKind::Number:
            v = JsonValue::makeFloat(s.*f.number);
            break;
        case FieldKind::Vec2:
            v = floats({(s.*f.vec2).x, (s.*f.vec2).y});
            break;
        case FieldKind::Vec3:
            v = floats({(s.*f.vec3).x, (s.*f.vec3).y, (s.*f.vec3).z});
            break;
        case FieldKind::Bool:
            v = JsonValue::makeBool(s.*f.flag);
            break;
        case FieldKind::Text:
            v = JsonValue::makeString(s.*f.text);
            break;
        case FieldKind::Path:
            v = JsonValue::makeString(relativeDocumentPath(s.*f.text, baseDir));
            break;
        case FieldKind::Choice:
            v = JsonValue::makeString(std::string(f.choices[static_cast<size_t>(f.getChoice(s))]));
            break;
        }
        o.add(std::string(f.key), std::move(v));
    }
    return o;
}

std::string vecText(glm::vec3 v) {
    return "[" + formatNumber(v.x) + ", " + formatNumber(v.y) + ", " + formatNumber(v.z) + "]";
}

/// Rules between fields, which per-field ranges cannot express. Only checked on fields that were
/// read without error, so one mistake gives one message.
void checkCamera(JsonReader& r, const JsonValue& v, const Camera& c) {
    if (v.find("far") || v.find("near"))
        if (c.farPlane <= c.nearPlane)
            r.error("camera.far", "expected a number greater than near (" +
                                      formatNumber(c.nearPlane) + "), got " +
                                      formatNumber(c.farPlane));
}

void checkLight(JsonReader& r, const std::string& path, const Light& l) {
    if (l.type == LightType::Spot && l.innerConeDeg > l.outerConeDeg)
        r.error(jsonPathKey(path, "innerCone"), "the inner cone (" + formatNumber(l.innerConeDeg) +
                                                    "°) must not be wider than the outer cone (" +
                                                    formatNumber(l.outerConeDeg) + "°)");
    if ((l.type == LightType::Directional || l.type == LightType::Spot ||
         l.type == LightType::Area) &&
        glm::dot(l.direction, l.direction) <= 0.0f)
        r.error(jsonPathKey(path, "direction"),
                "expected a non-zero direction, got " + vecText(l.direction));
}

/// A uniform environment's radiance is colour x intensity; each is bounded alone, and their
/// product must fit the half-float environment map and HDR buffer as well (kMaxSceneRadiance).
void checkEnvironment(JsonReader& r, const Environment& e) {
    if (!e.hdri.empty())
        return;
    const double radiance =
        double(std::max({e.color.r, e.color.g, e.color.b})) * double(e.intensity);
    if (radiance > kMaxSceneRadiance)
        r.error("environment.intensity",
                "the uniform environment's radiance, colour x intensity (" +
                    formatNumber(radiance) + "), exceeds " + formatNumber(kMaxSceneRadiance) +
                    ", the largest the renderer's half-float buffers hold");
}

void readLights(JsonReader& r, const JsonValue& v, const fs::path& baseDir, Scene& s) {
    if (v.kind == JsonValue::Kind::Invalid)
        return;
    if (!v.isArray()) {
        r.error("lights", "expected an array of lights, got " + describeValue(v));
        return;
    }
    for (size_t i = 0; i < v.items.size(); ++i) {
        const std::string path = jsonPathIndex("lights", i);
        Light light;
        const size_t before = r.errorCount();
        readFields(r, v.items[i], path, lightFields(), baseDir, light);
        if (r.errorCount() == before)
            checkLight(r, path, light);
        s.lights.push_back(std::move(light));
    }
}

void readPost(JsonReader& r, const JsonValue& v, PostChain& post) {
    if (!r.expectObject(v, "post", kPostKeys))
        return;
    // Types, parameters and the stage order are checked against the effect catalogue.
    if (const JsonValue* effects = v.find("effects"))
        readPostEffects(r, *effects, "post.effects", post);
}

void readMaterialReference(JsonReader& r, const JsonValue& root, const fs::path& baseDir,
                           Problems& problems, Scene& s) {
    const JsonValue* material = root.find("material");
    const JsonValue* preset = root.find("materialPreset");
    if (material && material->kind == JsonValue::Kind::String) {
        if (preset)
            r.error("materialPreset", "not allowed when \"material\" names a preset file");
        if (material->text.empty()) {
            r.error("material", "expected a preset file path or a material object, got \"\"");
            return;
        }
        s.materialPreset = resolveDocumentPath(material->text, baseDir);
        if (auto m = loadMaterialFile(s.materialPreset, problems))
            s.material = std::move(*m);
        else
            r.error("material", "the preset \"" + s.materialPreset +
                                    "\" could not be loaded (see its problems)");
        return;
    }
    if (material)
        s.material =
            readMaterialJson(r, *material, "material", baseDir, MaterialPlacement::InlineInScene);
    if (preset)
        if (auto p = r.string(*preset, "materialPreset"))
            s.materialPreset = resolveDocumentPath(*p, baseDir);
}

JsonValue postToJson(const PostChain& post) {
    JsonValue o = JsonValue::makeObject();
    o.add("effects", postEffectsToJson(post));
    return o;
}

} // namespace

Scene readSceneJson(JsonReader& r, const JsonValue& root, const fs::path& baseDir,
                    Problems& problems) {
    Scene s;
    if (root.kind == JsonValue::Kind::Invalid)
        return s;
    if (!root.isObject()) {
        r.error("", "expected a scene object, got " + describeValue(root));
        return s;
    }
    const std::optional<int> version =
        readFormatAndVersion(r, root, "", kSceneFormat, kSceneVersion, true);
    if (!version)
        return s;
    // Version 1 migrates as it is: it only lacks the `atlases` key, which it may not have.
    r.expectObject(root, "",
                   *version >= 2 ? std::span<const std::string_view>(kSceneKeys)
                                 : std::span<const std::string_view>(kSceneKeys).first(9));
    if (const JsonValue* v = root.find("camera")) {
        const size_t before = r.errorCount();
        readFields(r, *v, "camera", cameraFields(), baseDir, s.camera);
        if (r.errorCount() == before)
            checkCamera(r, *v, s.camera);
    }
    if (const JsonValue* v = root.find("lights"))
        readLights(r, *v, baseDir, s);
    if (const JsonValue* v = root.find("environment")) {
        const size_t before = r.errorCount();
        readFields(r, *v, "environment", environmentFields(), baseDir, s.environment);
        if (r.errorCount() == before)
            checkEnvironment(r, s.environment);
    }
    if (const JsonValue* v = root.find("mesh")) {
        const size_t before = r.errorCount();
        readFields(r, *v, "mesh", meshFields(), baseDir, s.mesh);
        if (r.errorCount() == before && s.mesh.kind == PreviewMeshKind::Custom &&
            s.mesh.file.empty())
            r.error("mesh.file", "a mesh file is required when kind is \"custom\"");
    }
    readMaterialReference(r, root, baseDir, problems, s);
    if (const JsonValue* v = root.find("post"))
        readPost(r, *v, s.post);
    if (const JsonValue* v = root.find("atlases"); v && *version >= 2)
        if (auto x = r.string(*v, "atlases", false)) {
            s.atlases = resolveDocumentPath(*x, baseDir);
            std::error_code ec;
            if (!fs::exists(s.atlases, ec))
                r.warning("atlases", "file not found: \"" + s.atlases +
                                         "\" (the scene opens without its atlases)");
        }
    return s;
}

JsonValue sceneToJsonValue(const Scene& s, const fs::path& baseDir) {
    JsonValue o = JsonValue::makeObject();
    o.add("format", JsonValue::makeString(std::string(kSceneFormat)));
    o.add("version", JsonValue::makeNumber(kSceneVersion));
    o.add("camera", writeFields(s.camera, cameraFields(), baseDir));
    JsonValue& lights = o.add("lights", JsonValue::makeArray());
    for (const Light& l : s.lights)
        lights.push(writeFields(l, lightFields(), baseDir));
    o.add("environment", writeFields(s.environment, environmentFields(), baseDir));
    o.add("mesh", writeFields(s.mesh, meshFields(), baseDir));
    // The material is always written inline so that edits made after loading a preset are saved;
    // materialPreset keeps the informational link.
    o.add("material", materialToJsonValue(s.material, baseDir, MaterialPlacement::InlineInScene));
    if (!s.materialPreset.empty())
        o.add("materialPreset",
              JsonValue::makeString(relativeDocumentPath(s.materialPreset, baseDir)));
    o.add("post", postToJson(s.post));
    if (!s.atlases.empty())
        o.add("atlases", JsonValue::makeString(relativeDocumentPath(s.atlases, baseDir)));
    return o;
}

} // namespace velvet
