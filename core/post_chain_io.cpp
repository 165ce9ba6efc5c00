// Chain presets and the effects array of scenes: read (validate everything, then build), write,
// and the schema, all from the effect catalogue.
#include "core/post_chain_io.h"

#include "core/atomic_file.h"
#include "core/document_io.h"
#include "core/material_json.h"
#include "core/post_chain_json.h"
#include "core/post_effects.h"

#include <array>
#include <cmath>

namespace velvet {
namespace {

constexpr std::array<std::string_view, 3> kEffectKeys{"type", "enabled", "params"};
constexpr std::array<std::string_view, 4> kPresetKeys{"format", "version", "name", "effects"};

std::vector<std::string_view> typeNames() {
    std::vector<std::string_view> names;
    for (const EffectMeta& m : postEffectCatalogue())
        names.push_back(m.type);
    return names;
}

/// A Float parameter: a number or a one-element array (scenes have always written arrays).
std::optional<float> readScalar(JsonReader& r, const JsonValue& v, const std::string& path,
                                const NumberRange& range) {
    if (v.isArray()) {
        if (v.items.size() != 1) {
            r.error(path, "expected a number or an array of one number, got " +
                              std::to_string(v.items.size()) + " items");
            return std::nullopt;
        }
        if (auto x = r.number(v.items[0], jsonPathIndex(path, 0), range))
            return float(*x);
        return std::nullopt;
    }
    if (auto x = r.number(v, path, range))
        return float(*x);
    return std::nullopt;
}

void readParams(JsonReader& r, const JsonValue& params, const std::string& path,
                const EffectMeta& meta, EffectInstance& effect) {
    if (params.kind == JsonValue::Kind::Invalid)
        return;
    if (!params.isObject()) {
        r.error(path, "expected an object of parameters, got " + describeValue(params));
        return;
    }
    std::vector<std::string_view> ids;
    for (const ParamMeta& p : meta.params)
        ids.push_back(p.id);
    r.expectObject(params, path, ids);
    for (const ParamMeta& p : meta.params) {
        const JsonValue* v = params.find(p.id);
        if (!v)
            continue;
        const std::string pPath = jsonPathKey(path, p.id);
        const NumberRange range = closedRange(p.min, p.max);
        switch (p.type) {
        case ParamType::Float:
            if (auto x = readScalar(r, *v, pPath, range))
                effect.params[std::string(p.id)] = {*x};
            break;
        case ParamType::Color:
            if (auto c = r.vec3(*v, pPath, range))
                effect.params[std::string(p.id)] = {c->x, c->y, c->z};
            break;
        case ParamType::Choice:
            if (v->isArray()) { // an index, as the first scene files wrote choices
                if (v->items.size() == 1)
                    if (auto i =
                            r.integer(v->items[0], jsonPathIndex(pPath, 0), closedRange(0, p.max)))
                        effect.params[std::string(p.id)] = {float(*i)};
                if (v->items.size() != 1)
                    r.error(pPath, "expected one of " + listNames(p.choices));
            } else if (auto i = r.choice(*v, pPath, p.choices)) {
                effect.params[std::string(p.id)] = {float(*i)};
            }
            break;
        }
    }
}

JsonValue str(std::string_view s) {
    return JsonValue::makeString(std::string(s));
}

JsonValue numberSchema(float lo, float hi, bool integer = false) {
    JsonValue o = JsonValue::makeObject();
    o.add("type", str(integer ? "integer" : "number"));
    o.add("minimum", JsonValue::makeFloat(lo));
    o.add("maximum", JsonValue::makeFloat(hi));
    return o;
}

JsonValue arraySchema(JsonValue item, int n) {
    JsonValue o = JsonValue::makeObject();
    o.add("type", str("array"));
    o.add("items", std::move(item));
    o.add("minItems", JsonValue::makeNumber(n));
    o.add("maxItems", JsonValue::makeNumber(n));
    return o;
}

JsonValue paramSchema(const ParamMeta& p) {
    JsonValue o = JsonValue::makeObject();
    std::string description(p.tooltip);
    if (!p.unit.empty())
        description += " Unit: " + std::string(p.unit) + ".";
    o.add("description", JsonValue::makeString(description));
    switch (p.type) {
    case ParamType::Float: {
        JsonValue& any = o.add("anyOf", JsonValue::makeArray());
        any.push(numberSchema(p.min, p.max));
        any.push(arraySchema(numberSchema(p.min, p.max), 1));
        o.add("default", JsonValue::makeFloat(p.defaultValue.x));
        break;
    }
    case ParamType::Color: {
        JsonValue a = arraySchema(numberSchema(p.min, p.max), 3);
        for (JsonMember& m : a.members)
            o.add(m.key, std::move(m.value));
        JsonValue& def = o.add("default", JsonValue::makeArray());
        for (int k = 0; k < 3; ++k)
            def.push(JsonValue::makeFloat(p.defaultValue[k]));
        break;
    }
    case ParamType::Choice: {
        JsonValue& any = o.add("anyOf", JsonValue::makeArray());
        JsonValue& names = any.push(JsonValue::makeObject()).add("enum", JsonValue::makeArray());
        for (std::string_view c : p.choices)
            names.push(str(c));
        any.push(arraySchema(numberSchema(0, p.max, true), 1));
        o.add("default", str(p.choices[size_t(p.defaultValue.x)]));
        break;
    }
    }
    return o;
}

JsonValue effectSchema(const EffectMeta& m) {
    JsonValue o = JsonValue::makeObject();
    o.add("title", str(m.label));
    o.add("description", JsonValue::makeString(std::string(m.description) +
                                               " Stage: " + std::string(postStageName(m.stage)) +
                                               "; reads " + describeReads(m.reads) + "."));
    o.add("type", str("object"));
    o.add("additionalProperties", JsonValue::makeBool(false));
    JsonValue& required = o.add("required", JsonValue::makeArray());
    required.push(str("type"));
    JsonValue& props = o.add("properties", JsonValue::makeObject());
    props.add("type", JsonValue::makeObject()).add("const", str(m.type));
    JsonValue& enabled = props.add("enabled", JsonValue::makeObject());
    enabled.add("type", str("boolean"));
    enabled.add("default", JsonValue::makeBool(true));
    JsonValue& params = props.add("params", JsonValue::makeObject());
    params.add("type", str("object"));
    params.add("additionalProperties", JsonValue::makeBool(false));
    JsonValue& pp = params.add("properties", JsonValue::makeObject());
    for (const ParamMeta& p : m.params)
        pp.add(std::string(p.id), paramSchema(p));
    return o;
}

} // namespace

void readPostEffects(JsonReader& r, const JsonValue& v, const std::string& path, PostChain& chain) {
    if (v.kind == JsonValue::Kind::Invalid)
        return;
    if (!v.isArray()) {
        r.error(path, "expected an array of effects, got " + describeValue(v));
        return;
    }
    const size_t before = r.errorCount();
    const std::vector<std::string_view> types = typeNames();
    for (size_t i = 0; i < v.items.size(); ++i) {
        const JsonValue& e = v.items[i];
        const std::string ePath = jsonPathIndex(path, i);
        if (!r.expectObject(e, ePath, kEffectKeys))
            continue;
        EffectInstance effect;
        const EffectMeta* meta = nullptr;
        if (const JsonValue* type = r.require(e, ePath, "type"))
            if (auto t = r.string(*type, jsonPathKey(ePath, "type"), false)) {
                effect.type = *t;
                meta = findPostEffect(*t);
                if (!meta)
                    r.error(jsonPathKey(ePath, "type"), "unknown effect type \"" + *t + "\"" +
                                                            didYouMean(*t, types) +
                                                            "; known: " + listNames(types));
            }
        if (const JsonValue* enabled = e.find("enabled"))
            if (auto b = r.boolean(*enabled, jsonPathKey(ePath, "enabled")))
                effect.enabled = *b;
        if (const JsonValue* params = e.find("params"); params && meta)
            readParams(r, *params, jsonPathKey(ePath, "params"), *meta, effect);
        chain.effects.push_back(std::move(effect));
    }
    // The order is meaningful only once every effect is known.
    if (r.errorCount() == before)
        for (const ChainIssue& issue : checkStageOrder(chain))
            r.error(jsonPathIndex(path, issue.index), issue.message);
}

JsonValue postEffectsToJson(const PostChain& chain) {
    JsonValue effects = JsonValue::makeArray();
    for (const EffectInstance& e : chain.effects) {
        JsonValue& je = effects.push(JsonValue::makeObject());
        je.add("type", JsonValue::makeString(e.type));
        je.add("enabled", JsonValue::makeBool(e.enabled));
        JsonValue& params = je.add("params", JsonValue::makeObject());
        const EffectMeta* meta = findPostEffect(e.type);
        auto writeRaw = [&](const std::string& key, const std::vector<float>& values) {
            JsonValue& a = params.add(key, JsonValue::makeArray());
            for (float x : values)
                a.push(JsonValue::makeFloat(x));
        };
        if (!meta) { // not loadable, but never lose data when saving
            for (const auto& [key, values] : e.params)
                writeRaw(key, values);
            continue;
        }
        for (const ParamMeta& p : meta->params) {
            const auto it = e.params.find(std::string(p.id));
            if (it == e.params.end())
                continue;
            const int index = it->second.empty() ? 0 : int(std::lround(it->second[0]));
            if (p.type == ParamType::Choice && index >= 0 && size_t(index) < p.choices.size())
                params.add(std::string(p.id), str(p.choices[size_t(index)]));
            else
                writeRaw(it->first, it->second);
        }
    }
    return effects;
}

JsonValue postEffectsSchema() {
    JsonValue o = JsonValue::makeObject();
    o.add("type", str("array"));
    o.add("description",
          str("Effects in the order they run. Stage order (checked by Velvet, not expressible "
              "here): pre-passes, HDR effects, paintbrush, tone mapping, LDR effects; effects of "
              "stage \"any\" may sit anywhere; at most one tone mapping."));
    JsonValue& oneOf = o.add("items", JsonValue::makeObject()).add("oneOf", JsonValue::makeArray());
    for (const EffectMeta& m : postEffectCatalogue())
        oneOf.push(effectSchema(m));
    return o;
}

std::optional<PostChainPreset> parsePostChain(std::string_view text, const std::string& fileName,
                                              Problems& problems) {
    const size_t before = problems.items.size();
    auto root = parseJson(text, fileName, problems, kMaxJsonDepth);
    if (!root)
        return std::nullopt;
    JsonReader r(fileName, problems);
    PostChainPreset preset;
    if (root->kind == JsonValue::Kind::Invalid)
        return std::nullopt;
    if (!root->isObject()) {
        r.error("", "expected a post-chain object, got " + describeValue(*root));
        return std::nullopt;
    }
    if (!readFormatAndVersion(r, *root, "", kPostChainFormat, kPostChainVersion, true))
        return std::nullopt;
    r.expectObject(*root, "", kPresetKeys);
    if (const JsonValue* name = root->find("name"))
        if (auto n = r.string(*name, "name"))
            preset.name = *n;
    if (const JsonValue* effects = r.require(*root, "", "effects"))
        readPostEffects(r, *effects, "effects", preset.chain);
    for (size_t i = before; i < problems.items.size(); ++i)
        if (problems.items[i].severity == Problem::Severity::Error)
            return std::nullopt;
    return preset;
}

std::optional<PostChainPreset> loadPostChainFile(const std::filesystem::path& file,
                                                 Problems& problems) {
    std::string reason;
    const auto text = readFileWithLimit(file, kMaxDocumentBytes, &reason);
    if (!text) {
        problems.error(file.string(), "", reason);
        return std::nullopt;
    }
    return parsePostChain(*text, file.string(), problems);
}

std::string postChainToJson(const PostChainPreset& preset) {
    JsonValue o = JsonValue::makeObject();
    o.add("format", str(kPostChainFormat));
    o.add("version", JsonValue::makeNumber(kPostChainVersion));
    if (!preset.name.empty())
        o.add("name", JsonValue::makeString(preset.name));
    o.add("effects", postEffectsToJson(preset.chain));
    return writeJson(o);
}

bool savePostChainFile(const PostChainPreset& preset, const std::filesystem::path& file,
                       std::string* error) {
    return writeFileAtomically(file, postChainToJson(preset), error);
}

std::string postChainJsonSchema() {
    JsonValue o = JsonValue::makeObject();
    o.add("$schema", str("https://json-schema.org/draft/2020-12/schema"));
    o.add("title", str("Velvet post-effect chain"));
    o.add("description", str("An ordered post-effect chain preset (core/post_effects.h). Colours "
                             "are scene-linear Rec.709."));
    o.add("type", str("object"));
    JsonValue& required = o.add("required", JsonValue::makeArray());
    for (std::string_view k : {"format", "version", "effects"})
        required.push(str(k));
    o.add("additionalProperties", JsonValue::makeBool(false));
    JsonValue& p = o.add("properties", JsonValue::makeObject());
    p.add("format", JsonValue::makeObject()).add("const", str(kPostChainFormat));
    JsonValue& version = p.add("version", JsonValue::makeObject());
    version.add("type", str("integer"));
    version.add("minimum", JsonValue::makeNumber(1));
    version.add("maximum", JsonValue::makeNumber(kPostChainVersion));
    JsonValue& name = p.add("name", JsonValue::makeObject());
    name.add("type", str("string"));
    name.add("description", str("Shown in the preset list."));
    p.add("effects", postEffectsSchema());
    return writeJson(o);
}

} // namespace velvet
