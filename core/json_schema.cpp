// JSON Schemas (draft 2020-12) of presets and scenes, generated from the same metadata tables the
// readers use, so the shipped schemas in resources/schemas/ cannot describe a different format
// (a test compares them with this output).
#include "core/document_io.h"
#include "core/material_json.h"
#include "core/post_chain_json.h"
#include "core/scene_fields.h"

#include <cmath>

namespace velvet {
namespace {

JsonValue str(std::string_view s) {
    return JsonValue::makeString(std::string(s));
}

JsonValue strings(std::span<const std::string_view> names) {
    JsonValue a = JsonValue::makeArray();
    for (std::string_view n : names)
        a.push(str(n));
    return a;
}

JsonValue object() {
    return JsonValue::makeObject();
}

void addRange(JsonValue& o, const NumberRange& r) {
    if (std::isfinite(r.min))
        o.add(r.minExclusive ? "exclusiveMinimum" : "minimum", JsonValue::makeFloat(r.min));
    if (std::isfinite(r.max))
        o.add(r.maxExclusive ? "exclusiveMaximum" : "maximum", JsonValue::makeFloat(r.max));
}

JsonValue numberSchema(const NumberRange& r) {
    JsonValue o = object();
    o.add("type", str("number"));
    addRange(o, r);
    return o;
}

JsonValue vectorSchema(size_t n, const NumberRange& r) {
    JsonValue o = object();
    o.add("type", str("array"));
    o.add("items", numberSchema(r));
    o.add("minItems", JsonValue::makeNumber(static_cast<double>(n)));
    o.add("maxItems", JsonValue::makeNumber(static_cast<double>(n)));
    return o;
}

JsonValue floats(glm::vec3 v, int n) {
    JsonValue a = JsonValue::makeArray();
    for (int i = 0; i < n; ++i)
        a.push(JsonValue::makeFloat(v[i]));
    return a;
}

JsonValue paramSchema(const ParamMeta& m) {
    JsonValue o = object();
    std::string description(m.tooltip);
    if (!m.unit.empty())
        description += " Unit: " + std::string(m.unit) + ".";
    o.add("description", JsonValue::makeString(description));
    const NumberRange range = closedRange(m.min, m.max);
    switch (m.type) {
    case ParamType::Float:
        o.add("type", str("number"));
        addRange(o, range);
        o.add("default", JsonValue::makeFloat(m.defaultValue.x));
        break;
    case ParamType::Color: {
        JsonValue v = vectorSchema(3, range);
        for (JsonMember& member : v.members)
            o.add(member.key, std::move(member.value));
        o.add("default", floats(m.defaultValue, 3));
        break;
    }
    case ParamType::Choice:
        o.add("enum", strings(m.choices));
        o.add("default", str(m.choices[static_cast<size_t>(m.defaultValue.x)]));
        break;
    }
    return o;
}

JsonValue closedObject() {
    JsonValue o = object();
    o.add("type", str("object"));
    o.add("additionalProperties", JsonValue::makeBool(false));
    return o;
}

void addParamProperties(const ParamNode& node, JsonValue& properties) {
    for (const ParamNode& child : node.children) {
        if (child.param >= 0) {
            properties.add(std::string(child.key),
                           paramSchema(paramMeta(static_cast<ParamId>(child.param))));
        } else {
            JsonValue o = closedObject();
            addParamProperties(child, o.add("properties", object()));
            properties.add(std::string(child.key), std::move(o));
        }
    }
}

JsonValue formatSchema(std::string_view format) {
    JsonValue o = object();
    o.add("const", str(format));
    return o;
}

JsonValue versionSchema(int current) {
    JsonValue o = object();
    o.add("type", str("integer"));
    o.add("minimum", JsonValue::makeNumber(1));
    o.add("maximum", JsonValue::makeNumber(current));
    return o;
}

JsonValue textureSchema() {
    JsonValue o = closedObject();
    o.add("required", strings(std::array<std::string_view, 1>{"file"}));
    JsonValue& p = o.add("properties", object());
    JsonValue& file = p.add("file", object());
    file.add("type", str("string"));
    file.add("minLength", JsonValue::makeNumber(1));
    file.add("description", str("Image path, relative to the document's folder."));
    JsonValue& region = p.add("region", object());
    region.add("description", str("Atlas rectangle in pixels: [x, y, width, height]."));
    region.add("type", str("array"));
    JsonValue& items = region.add("prefixItems", JsonValue::makeArray());
    for (int i = 0; i < 4; ++i) {
        JsonValue n = object();
        n.add("type", str("integer"));
        n.add("minimum", JsonValue::makeNumber(i < 2 ? 0 : 1));
        items.push(std::move(n));
    }
    region.add("items", JsonValue::makeBool(false));
    region.add("minItems", JsonValue::makeNumber(4));
    JsonValue& cs = p.add("colorSpace", object());
    cs.add("type", str("string"));
    cs.add("minLength", JsonValue::makeNumber(1));
    cs.add("description", str("Input colour space; omitted: the slot's default."));
    JsonValue& uv = p.add("uv", closedObject());
    uv.add("description", str("UV transform before sampling: uv' = R(rotation) (scale * uv) + "
                              "offset (KHR_texture_transform)."));
    JsonValue& uvp = uv.add("properties", object());
    const auto pairSchema = [&](std::string_view description, double limit) {
        JsonValue a = object();
        a.add("description", str(description));
        a.add("type", str("array"));
        JsonValue n = object();
        n.add("type", str("number"));
        n.add("minimum", JsonValue::makeNumber(-limit));
        n.add("maximum", JsonValue::makeNumber(limit));
        a.add("items", std::move(n));
        a.add("minItems", JsonValue::makeNumber(2));
        a.add("maxItems", JsonValue::makeNumber(2));
        return a;
    };
    uvp.add("scale", pairSchema("Tiling in u and v (not 0).", kUvScaleLimit));
    uvp.add("offset", pairSchema("Offset in UV units, after scale and rotation.", kUvOffsetLimit));
    JsonValue& rot = uvp.add("rotation", object());
    rot.add("description", str("Degrees, counter-clockwise in UV space, after scale."));
    rot.add("type", str("number"));
    rot.add("minimum", JsonValue::makeNumber(-kUvRotationLimit));
    rot.add("maximum", JsonValue::makeNumber(kUvRotationLimit));
    return o;
}

JsonValue tagsSchema() {
    JsonValue o = object();
    o.add("type", str("array"));
    JsonValue& items = o.add("items", object());
    items.add("type", str("string"));
    items.add("minLength", JsonValue::makeNumber(1));
    return o;
}

/// The material graph (core/graph/graph_json.h). Only the shape is described here: node types,
/// port names and link rules are checked by the reader, which names the JSON path of a problem.
JsonValue graphSchema() {
    JsonValue o = closedObject();
    o.add("description", str("The node graph feeding the material's inputs (node editor)."));
    JsonValue& p = o.add("properties", object());
    JsonValue& nodes = p.add("nodes", object());
    nodes.add("type", str("array"));
    JsonValue& node = nodes.add("items", object());
    node.add("type", str("object"));
    node.add("required", strings(std::array<std::string_view, 2>{"id", "type"}));
    JsonValue& np = node.add("properties", object());
    np.add("id", object()).add("type", str("integer"));
    np.add("type", object()).add("type", str("string"));
    np.add("position", object()).add("type", str("array"));
    np.add("inputs", object()).add("type", str("object"));
    np.add("settings", object()).add("type", str("object"));
    JsonValue& links = p.add("links", object());
    links.add("type", str("array"));
    JsonValue& link = links.add("items", object());
    link.add("type", str("object"));
    link.add("required", strings(std::array<std::string_view, 4>{"from", "output", "to", "input"}));
    return o;
}

JsonValue materialV2Schema() {
    JsonValue o = closedObject();
    o.add("description", str("A material, version 2: parameters nested by their ids."));
    JsonValue& p = o.add("properties", object());
    p.add("format", formatSchema(kMaterialFormat));
    p.add("version", versionSchema(kMaterialVersion));
    p.add("name", object()).add("type", str("string"));
    p.add("tags", tagsSchema());
    addParamProperties(paramTree(), p);
    JsonValue& textures = p.add("textures", closedObject());
    JsonValue& slots = textures.add("properties", object());
    for (const TextureSlotMeta& slot : textureSlotMetas()) {
        JsonValue ref = object();
        ref.add("$ref", str("#/$defs/texture"));
        ref.add("description", str(slot.tooltip));
        slots.add(std::string(slot.id), std::move(ref));
    }
    p.add("graph", graphSchema());
    return o;
}

JsonValue materialV1Schema() {
    JsonValue o = closedObject();
    o.add("description",
          str("The seed documents' flat material, version 1; migrated to version 2 on load."));
    JsonValue& p = o.add("properties", object());
    p.add("format", formatSchema(kMaterialFormat));
    p.add("version", object()).add("const", JsonValue::makeNumber(1));
    p.add("name", object()).add("type", str("string"));
    p.add("albedo", vectorSchema(3, closedRange(0, 1)));
    for (std::string_view key : {"specular", "roughness", "metallic"})
        p.add(std::string(key), numberSchema(closedRange(0, 1)));
    return o;
}

/// Chooses the version-1 or version-2 shape by the "version" key.
void addMaterialDispatch(JsonValue& o) {
    JsonValue& ifs = o.add("if", object());
    ifs.add("required", strings(std::array<std::string_view, 1>{"version"}));
    ifs.add("properties", object()).add("version", object()).add("const", JsonValue::makeNumber(1));
    o.add("then", object()).add("$ref", str("#/$defs/materialV1"));
    o.add("else", object()).add("$ref", str("#/$defs/material"));
}

void addMaterialDefs(JsonValue& defs) {
    defs.add("material", materialV2Schema());
    defs.add("materialV1", materialV1Schema());
    defs.add("texture", textureSchema());
}

JsonValue header(std::string_view title, std::string_view description) {
    JsonValue o = object();
    o.add("$schema", str("https://json-schema.org/draft/2020-12/schema"));
    o.add("title", str(title));
    o.add("description", str(description));
    return o;
}

JsonValue materialSchema() {
    JsonValue o = header("Velvet material preset",
                         "A physically based material (docs/file-formats.md). Colours are "
                         "scene-linear Rec.709.");
    o.add("type", str("object"));
    o.add("required", strings(std::array<std::string_view, 3>{"format", "version", "name"}));
    addMaterialDispatch(o);
    addMaterialDefs(o.add("$defs", object()));
    return o;
}

template <class S>
JsonValue fieldsSchema(std::span<const Field<S>> fields) {
    static const S def{};
    JsonValue o = closedObject();
    JsonValue required = JsonValue::makeArray();
    JsonValue& props = o.add("properties", object());
    for (const Field<S>& f : fields) {
        JsonValue p = object();
        p.add("description", str(f.description));
        switch (f.kind) {
        case FieldKind::Number:
            p.add("type", str("number"));
            addRange(p, f.range);
            p.add("default", JsonValue::makeFloat(def.*f.number));
            break;
        case FieldKind::Vec2:
        case FieldKind::Vec3: {
            const bool three = f.kind == FieldKind::Vec3;
            JsonValue v = vectorSchema(three ? 3 : 2, f.range);
            for (JsonMember& m : v.members)
                p.add(m.key, std::move(m.value));
            p.add("default",
                  three ? floats(def.*f.vec3, 3) : floats(glm::vec3(def.*f.vec2, 0.0f), 2));
            break;
        }
        case FieldKind::Bool:
            p.add("type", str("boolean"));
            p.add("default", JsonValue::makeBool(def.*f.flag));
            break;
        case FieldKind::Text:
        case FieldKind::Path:
            p.add("type", str("string"));
            break;
        case FieldKind::Choice:
            p.add("enum", strings(f.choices));
            if (!f.required)
                p.add("default", str(f.choices[static_cast<size_t>(f.getChoice(def))]));
            break;
        }
        if (f.required)
            required.push(str(f.key));
        props.add(std::string(f.key), std::move(p));
    }
    if (!required.items.empty())
        o.add("required", std::move(required));
    return o;
}

JsonValue postSchema() {
    JsonValue o = closedObject();
    o.add("properties", object()).add("effects", postEffectsSchema());
    return o;
}

JsonValue sceneSchema() {
    JsonValue o =
        header("Velvet scene", "Camera, lights, environment, preview mesh, material and post chain "
                               "(docs/file-formats.md). Colours are scene-linear Rec.709.");
    o.add("type", str("object"));
    o.add("required", strings(std::array<std::string_view, 2>{"format", "version"}));
    o.add("additionalProperties", JsonValue::makeBool(false));
    JsonValue& p = o.add("properties", object());
    p.add("format", formatSchema(kSceneFormat));
    p.add("version", versionSchema(kSceneVersion));
    p.add("camera", fieldsSchema(cameraFields()));
    JsonValue& lights = p.add("lights", object());
    lights.add("type", str("array"));
    lights.add("items", fieldsSchema(lightFields()));
    p.add("environment", fieldsSchema(environmentFields()));
    p.add("mesh", fieldsSchema(meshFields()));
    JsonValue& material = p.add("material", object());
    material.add("description", str("A preset file path (relative to the scene) or an inline "
                                    "material (format, version and name optional)."));
    JsonValue& oneOf = material.add("oneOf", JsonValue::makeArray());
    JsonValue& path = oneOf.push(object());
    path.add("type", str("string"));
    path.add("minLength", JsonValue::makeNumber(1));
    oneOf.push(object()).add("$ref", str("#/$defs/inlineMaterial"));
    JsonValue& preset = p.add("materialPreset", object());
    preset.add("type", str("string"));
    preset.add("description", str("The preset an inline material came from (informational)."));
    p.add("post", postSchema());
    JsonValue& atlases = p.add("atlases", object());
    atlases.add("type", str("string"));
    atlases.add("minLength", JsonValue::makeNumber(1));
    atlases.add("description", str("The scene's atlas document (velvet.atlas, "
                                   "resources/schemas/atlas.schema.json), relative to the scene. "
                                   "Version 2 and later."));

    JsonValue& defs = o.add("$defs", object());
    JsonValue& inlineMaterial = defs.add("inlineMaterial", object());
    inlineMaterial.add("type", str("object"));
    addMaterialDispatch(inlineMaterial);
    addMaterialDefs(defs);
    return o;
}

} // namespace

std::string jsonSchema(DocumentKind kind) {
    switch (kind) {
    case DocumentKind::Material:
        return writeJson(materialSchema());
    case DocumentKind::Scene:
        return writeJson(sceneSchema());
    case DocumentKind::Unknown:
        break;
    }
    return {};
}

} // namespace velvet
