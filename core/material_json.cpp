#include "core/material_json.h"

#include "core/document_io.h"
#include "core/document_paths.h"
#include "core/graph/graph_json.h"

#include <algorithm>
#include <array>

namespace velvet {
namespace fs = std::filesystem;
namespace {

constexpr std::array<std::string_view, 4> kHeaderKeys{"format", "version", "name", "tags"};
constexpr std::array<std::string_view, 4> kTextureKeys{"file", "region", "colorSpace", "uv"};
constexpr std::array<std::string_view, 3> kUvKeys{"scale", "offset", "rotation"};
constexpr std::array<std::string_view, 7> kVersion1Keys{
    "format", "version", "name", "albedo", "specular", "roughness", "metallic"};
/// Atlas rectangles beyond this are certainly mistakes (and keep the cast to int safe).
constexpr double kMaxTexel = 1 << 20;

ParamNode buildParamTree() {
    ParamNode root;
    const auto metas = paramMetas();
    for (size_t i = 0; i < metas.size(); ++i) {
        ParamNode* node = &root;
        std::string_view rest = metas[i].id;
        while (!rest.empty()) {
            const size_t dot = rest.find('.');
            const std::string_view key = rest.substr(0, dot);
            rest = dot == std::string_view::npos ? std::string_view() : rest.substr(dot + 1);
            auto it = std::find_if(node->children.begin(), node->children.end(),
                                   [&](const ParamNode& n) { return n.key == key; });
            if (it == node->children.end()) {
                node->children.push_back({key, -1, {}, {}});
                node->keys.push_back(key);
                it = node->children.end() - 1;
            }
            node = &*it;
        }
        node->param = static_cast<int>(i);
    }
    return root;
}

std::vector<std::string_view> textureSlotIds() {
    std::vector<std::string_view> ids;
    for (const TextureSlotMeta& s : textureSlotMetas())
        ids.push_back(s.id);
    return ids;
}

void readParam(JsonReader& r, const JsonValue& v, const std::string& path, ParamId id,
               Material& m) {
    const ParamMeta& meta = paramMeta(id);
    const NumberRange range = closedRange(meta.min, meta.max);
    switch (meta.type) {
    case ParamType::Float:
        if (auto x = r.number(v, path, range))
            m.setScalar(id, static_cast<float>(*x));
        break;
    case ParamType::Color:
        if (auto c = r.vec3(v, path, range))
            m.setColor(id, *c);
        break;
    case ParamType::Choice:
        if (auto i = r.choice(v, path, meta.choices))
            m.setChoice(id, *i);
        break;
    }
}

/// Walks the object tree in step with the metadata tree: one reader for every parameter.
void readParamObject(JsonReader& r, const JsonValue& v, const std::string& path,
                     const ParamNode& node, Material& m) {
    for (const ParamNode& child : node.children) {
        const JsonValue* value = v.find(child.key);
        if (!value)
            continue; // omitted parameters keep their defaults
        const std::string childPath = jsonPathKey(path, child.key);
        if (child.param >= 0)
            readParam(r, *value, childPath, static_cast<ParamId>(child.param), m);
        else if (r.expectObject(*value, childPath, child.keys))
            readParamObject(r, *value, childPath, child, m);
    }
}

/// "uv": {"scale": [u, v], "offset": [u, v], "rotation": degrees}, each optional (texture_ref.h).
void readUvTransform(JsonReader& r, const JsonValue& v, const std::string& path, UvTransform& uv) {
    if (!r.expectObject(v, path, kUvKeys))
        return;
    if (const JsonValue* s = v.find("scale")) {
        const std::string scalePath = jsonPathKey(path, "scale");
        if (auto x = r.vec2(*s, scalePath, closedRange(-kUvScaleLimit, kUvScaleLimit))) {
            if (x->x == 0.0f || x->y == 0.0f)
                r.error(scalePath, "a scale of 0 collapses the texture to one texel; expected a "
                                   "non-zero number in each component");
            else
                uv.scale = *x;
        }
    }
    if (const JsonValue* o = v.find("offset"))
        if (auto x = r.vec2(*o, jsonPathKey(path, "offset"),
                            closedRange(-kUvOffsetLimit, kUvOffsetLimit)))
            uv.offset = *x;
    if (const JsonValue* a = v.find("rotation"))
        if (auto x = r.number(*a, jsonPathKey(path, "rotation"),
                              closedRange(-kUvRotationLimit, kUvRotationLimit)))
            uv.rotation = static_cast<float>(*x);
}

void readTextureRef(JsonReader& r, const JsonValue& v, const std::string& path,
                    const fs::path& baseDir, TextureRef& ref) {
    if (!r.expectObject(v, path, kTextureKeys))
        return;
    if (const JsonValue* file = r.require(v, path, "file")) {
        const std::string filePath = jsonPathKey(path, "file");
        if (auto f = r.string(*file, filePath, false)) {
            ref.file = resolveDocumentPath(*f, baseDir);
            std::error_code ec;
            if (!fs::exists(ref.file, ec))
                r.warning(filePath, "image not found: \"" + ref.file +
                                        "\" (the parameter value is used instead)");
        }
    }
    if (const JsonValue* region = v.find("region")) {
        const std::string regionPath = jsonPathKey(path, "region");
        if (!region->isArray() || region->items.size() != 4) {
            if (region->kind != JsonValue::Kind::Invalid)
                r.error(regionPath, "expected an array of 4 integers [x, y, width, height], got " +
                                        describeValue(*region));
        } else {
            std::array<int, 4> xywh{};
            bool ok = true;
            for (size_t i = 0; i < 4; ++i) {
                const auto n = r.integer(region->items[i], jsonPathIndex(regionPath, i),
                                         closedRange(i < 2 ? 0 : 1, kMaxTexel));
                ok = ok && n.has_value();
                xywh[i] = n ? static_cast<int>(*n) : 0;
            }
            if (ok) {
                ref.useRegion = true;
                ref.region = {xywh[0], xywh[1], xywh[2], xywh[3]};
            }
        }
    }
    if (const JsonValue* cs = v.find("colorSpace"))
        if (auto s = r.string(*cs, jsonPathKey(path, "colorSpace"), false))
            ref.colorSpace = *s;
    if (const JsonValue* uv = v.find("uv"))
        readUvTransform(r, *uv, jsonPathKey(path, "uv"), ref.uv);
}

void readTextures(JsonReader& r, const JsonValue& v, const std::string& path,
                  const fs::path& baseDir, Material& m) {
    const std::vector<std::string_view> ids = textureSlotIds();
    if (!r.expectObject(v, path, ids))
        return;
    for (size_t i = 0; i < ids.size(); ++i) {
        if (const JsonValue* t = v.find(ids[i])) {
            TextureRef ref;
            readTextureRef(r, *t, jsonPathKey(path, ids[i]), baseDir, ref);
            m.setTexture(static_cast<TextureSlot>(i), std::move(ref));
        }
    }
}

/// The "graph" object (core/graph/graph_json.h). Texture nodes' files resolve against @p baseDir
/// like texture slots do; a missing image is a warning (the node samples a fallback).
void readGraph(JsonReader& r, const JsonValue& v, const std::string& path, const fs::path& baseDir,
               Material& m) {
    std::optional<graph::Graph> g = graph::graphFromJson(v, path, r);
    if (!g)
        return;
    for (const auto& [id, node] : g->nodes()) {
        const int file = node.type->settingIndex("file");
        if (!node.type->samplesTexture || file < 0 || node.settings[size_t(file)].empty())
            continue;
        const std::string resolved = resolveDocumentPath(node.settings[size_t(file)], baseDir);
        std::error_code ec;
        if (!fs::exists(resolved, ec))
            r.warning(jsonPathKey(path, "nodes"),
                      "node " + std::to_string(id) + ": image not found: \"" + resolved + "\"");
        g->setSetting(id, "file", resolved);
    }
    m.graph = SharedGraph(std::make_shared<const graph::Graph>(std::move(*g)));
}

/// The "graph" object with texture files relative to @p baseDir.
JsonValue graphToJson(const graph::Graph& g, const fs::path& baseDir) {
    graph::Graph copy = g;
    for (const auto& [id, node] : g.nodes()) {
        const int file = node.type->settingIndex("file");
        if (node.type->samplesTexture && file >= 0 && !node.settings[size_t(file)].empty())
            copy.setSetting(id, "file", relativeDocumentPath(node.settings[size_t(file)], baseDir));
    }
    return graph::graphToJson(copy);
}

void readNameAndTags(JsonReader& r, const JsonValue& v, const std::string& path,
                     MaterialPlacement placement, Material& m) {
    const JsonValue* name =
        placement == MaterialPlacement::PresetFile ? r.require(v, path, "name") : v.find("name");
    if (name)
        if (auto s = r.string(*name, jsonPathKey(path, "name")))
            m.name = *s;
    const JsonValue* tags = v.find("tags");
    if (!tags)
        return;
    const std::string tagsPath = jsonPathKey(path, "tags");
    if (!tags->isArray()) {
        if (tags->kind != JsonValue::Kind::Invalid)
            r.error(tagsPath, "expected an array of strings, got " + describeValue(*tags));
        return;
    }
    for (size_t i = 0; i < tags->items.size(); ++i)
        if (auto s = r.string(tags->items[i], jsonPathIndex(tagsPath, i), false))
            m.tags.push_back(*s);
}

void readVersion2(JsonReader& r, const JsonValue& v, const std::string& path,
                  const fs::path& baseDir, MaterialPlacement placement, Material& m) {
    std::vector<std::string_view> allowed(kHeaderKeys.begin(), kHeaderKeys.end());
    allowed.insert(allowed.end(), paramTree().keys.begin(), paramTree().keys.end());
    allowed.push_back("textures");
    allowed.push_back("graph");
    r.expectObject(v, path, allowed);
    readNameAndTags(r, v, path, placement, m);
    readParamObject(r, v, path, paramTree(), m);
    if (const JsonValue* t = v.find("textures"))
        readTextures(r, *t, jsonPathKey(path, "textures"), baseDir, m);
    if (const JsonValue* g = v.find("graph"))
        readGraph(r, *g, jsonPathKey(path, "graph"), baseDir, m);
}

/// Version 1 is the seed documents' flat material. Their "specular" follows Disney's convention
/// (0.5 is 4 % reflectance, the F0 of IOR 1.5), which KHR_materials_specular reaches with weight 1
/// at the default IOR; hence weight = min(1, 2 × specular).
void readVersion1(JsonReader& r, const JsonValue& v, const std::string& path,
                  MaterialPlacement placement, Material& m) {
    r.expectObject(v, path, kVersion1Keys);
    readNameAndTags(r, v, path, placement, m);
    const NumberRange unit = closedRange(0, 1);
    if (const JsonValue* a = v.find("albedo"))
        if (auto c = r.vec3(*a, jsonPathKey(path, "albedo"), unit))
            m.setColor(ParamId::BaseColor, *c);
    if (const JsonValue* s = v.find("specular"))
        if (auto x = r.number(*s, jsonPathKey(path, "specular"), unit))
            m.setScalar(ParamId::SpecularWeight, std::min(1.0f, 2.0f * static_cast<float>(*x)));
    if (const JsonValue* s = v.find("roughness"))
        if (auto x = r.number(*s, jsonPathKey(path, "roughness"), unit))
            m.setScalar(ParamId::Roughness, static_cast<float>(*x));
    if (const JsonValue* s = v.find("metallic"))
        if (auto x = r.number(*s, jsonPathKey(path, "metallic"), unit))
            m.setScalar(ParamId::Metallic, static_cast<float>(*x));
}

JsonValue paramToJson(const Material& m, ParamId id) {
    const ParamMeta& meta = paramMeta(id);
    const glm::vec3 v = m.value(id);
    switch (meta.type) {
    case ParamType::Float:
        return JsonValue::makeFloat(v.x);
    case ParamType::Color: {
        JsonValue a = JsonValue::makeArray();
        for (int i = 0; i < 3; ++i)
            a.push(JsonValue::makeFloat(v[i]));
        return a;
    }
    case ParamType::Choice: {
        const int i = m.choice(id);
        return JsonValue::makeString(std::string(meta.choices[static_cast<size_t>(i)]));
    }
    }
    return {};
}

void writeParamObject(const Material& m, const ParamNode& node, JsonValue& out) {
    for (const ParamNode& child : node.children) {
        if (child.param >= 0) {
            out.add(std::string(child.key), paramToJson(m, static_cast<ParamId>(child.param)));
        } else {
            JsonValue& o = out.add(std::string(child.key), JsonValue::makeObject());
            writeParamObject(m, child, o);
        }
    }
}

JsonValue textureToJson(const TextureRef& t, const fs::path& baseDir) {
    JsonValue o = JsonValue::makeObject();
    o.add("file", JsonValue::makeString(relativeDocumentPath(t.file, baseDir)));
    if (t.useRegion) {
        JsonValue& r = o.add("region", JsonValue::makeArray());
        for (int x : {t.region.x, t.region.y, t.region.width, t.region.height})
            r.push(JsonValue::makeNumber(x));
    }
    if (!t.colorSpace.empty())
        o.add("colorSpace", JsonValue::makeString(t.colorSpace));
    if (!t.uv.isIdentity()) { // written only when set, so untouched presets stay as they were
        JsonValue& uv = o.add("uv", JsonValue::makeObject());
        const auto pair = [](glm::vec2 p) {
            JsonValue a = JsonValue::makeArray();
            a.push(JsonValue::makeFloat(p.x));
            a.push(JsonValue::makeFloat(p.y));
            return a;
        };
        uv.add("scale", pair(t.uv.scale));
        uv.add("offset", pair(t.uv.offset));
        uv.add("rotation", JsonValue::makeFloat(t.uv.rotation));
    }
    return o;
}

std::string_view otherFormatHint(std::string_view expected, std::string_view got) {
    if (expected == kMaterialFormat && got == kSceneFormat)
        return " (this is a scene, not a material preset)";
    if (expected == kSceneFormat && got == kMaterialFormat)
        return " (this is a material preset, not a scene)";
    return "";
}

} // namespace

const ParamNode& paramTree() {
    static const ParamNode tree = buildParamTree();
    return tree;
}

std::optional<int> readFormatAndVersion(JsonReader& r, const JsonValue& root,
                                        const std::string& path, std::string_view format,
                                        int current, bool required) {
    const std::string formatPath = jsonPathKey(path, "format");
    if (const JsonValue* f = root.find("format")) {
        if (f->kind != JsonValue::Kind::String || f->text != format) {
            if (f->kind != JsonValue::Kind::Invalid)
                r.error(formatPath, "expected \"" + std::string(format) + "\", got " +
                                        describeValue(*f) +
                                        std::string(otherFormatHint(format, f->text)));
            return std::nullopt;
        }
    } else if (required) {
        r.error(formatPath, "required key is missing (expected \"" + std::string(format) + "\")");
    }
    const std::string versionPath = jsonPathKey(path, "version");
    const JsonValue* v = root.find("version");
    if (!v) {
        if (required)
            r.error(versionPath, "required key is missing (the current version is " +
                                     std::to_string(current) + ")");
        return current;
    }
    if (v->kind == JsonValue::Kind::Number && v->integral && v->number > current) {
        r.error(versionPath, "version " + describeValue(*v) + " is newer than this Velvet reads (" +
                                 std::to_string(current) + "); update Velvet");
        return std::nullopt;
    }
    const auto n = r.integer(*v, versionPath, closedRange(1, current));
    if (!n)
        return std::nullopt;
    return static_cast<int>(*n);
}

Material readMaterialJson(JsonReader& r, const JsonValue& v, const std::string& path,
                          const fs::path& baseDir, MaterialPlacement placement) {
    Material m;
    if (v.kind == JsonValue::Kind::Invalid)
        return m;
    if (!v.isObject()) {
        r.error(path, "expected a material object, got " + describeValue(v));
        return m;
    }
    const auto version = readFormatAndVersion(r, v, path, kMaterialFormat, kMaterialVersion,
                                              placement == MaterialPlacement::PresetFile);
    if (!version)
        return m; // a body of an unknown shape: reading on would only produce noise
    if (*version == 1)
        readVersion1(r, v, path, placement, m);
    else
        readVersion2(r, v, path, baseDir, placement, m);
    return m;
}

JsonValue materialToJsonValue(const Material& m, const fs::path& baseDir,
                              MaterialPlacement placement) {
    JsonValue o = JsonValue::makeObject();
    if (placement == MaterialPlacement::PresetFile)
        o.add("format", JsonValue::makeString(std::string(kMaterialFormat)));
    // Inline materials keep their version too, so a later Velvet can migrate them.
    o.add("version", JsonValue::makeNumber(kMaterialVersion));
    o.add("name", JsonValue::makeString(m.name));
    if (!m.tags.empty()) {
        JsonValue& tags = o.add("tags", JsonValue::makeArray());
        for (const std::string& t : m.tags)
            tags.push(JsonValue::makeString(t));
    }
    // Every parameter is written, defaults included: a preset keeps its look if a later version
    // changes a default.
    writeParamObject(m, paramTree(), o);
    JsonValue textures = JsonValue::makeObject();
    for (int i = 0; i < kTextureSlotCount; ++i) {
        const TextureRef& t = m.texture(static_cast<TextureSlot>(i));
        if (!t.empty())
            textures.add(std::string(textureSlotMeta(static_cast<TextureSlot>(i)).id),
                         textureToJson(t, baseDir));
    }
    if (!textures.members.empty())
        o.add("textures", std::move(textures));
    if (m.graph)
        o.add("graph", graphToJson(*m.graph, baseDir));
    return o;
}

} // namespace velvet
