// glTF 2.0 import. References: the glTF 2.0 specification (Khronos, 2021; section numbers
// below), KHR_materials_clearcoat, _sheen, _specular, _ior, _emissive_strength, _anisotropy,
// KHR_texture_transform and the archived KHR_materials_pbrSpecularGlossiness
// (github.com/KhronosGroup/glTF, extensions/2.0/). Every mapping, and what is not mapped, is
// tabled in docs/interchange.md ("Import").
#include "core/gltf_import.h"

#include "core/gltf_asset_files.h"
#include "core/gltf_spec_gloss.h"
#include "core/import_text.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>

namespace velvet {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

using gltf::at;
using gltf::fail;
using gltf::Failure;
using gltf::formatValue;
using gltf::wrapName;

constexpr double kPi = 3.14159265358979323846;

class Reader {
public:
    Reader(fs::path file, fs::path imageFolder, std::string imageStem)
        : m_files(std::move(file), std::move(imageFolder), std::move(imageStem), m_warnings) {}

    /// Reads the container (glTF 2.0 section 4.4 for GLB) and the JSON, checks the asset.
    void load() {
        const std::string text = m_files.load();
        // A hostile file nested a million deep must not exhaust the stack: glTF needs a few
        // levels (extensions inside textureInfos inside materials), 64 is plenty.
        struct TooDeep {};
        const Json::parser_callback_t depthLimit = [](int depth, Json::parse_event_t, Json&) {
            if (depth > 64)
                throw TooDeep{};
            return true;
        };
        try {
            m_doc = Json::parse(text, depthLimit);
        } catch (const TooDeep&) {
            fail("", "JSON nested deeper than 64 levels");
        } catch (const Json::parse_error& e) {
            std::string what = e.what();
            if (const size_t p = what.find("parse error"); p != std::string::npos)
                what = what.substr(p);
            fail(lineColumn(text, e.byte == 0 ? 0 : e.byte - 1), "broken JSON: " + what);
        } catch (const Json::out_of_range& e) { // 1e999: beyond a double (found by fuzz_gltf)
            std::string what = e.what();
            if (const size_t p = what.find("number overflow"); p != std::string::npos)
                what = what.substr(p);
            fail("", "broken JSON: " + what);
        }
        if (!m_doc.is_object())
            fail("", "the top level is not a JSON object");
        const Json* asset = find(m_doc, "asset");
        if (!asset || !asset->is_object())
            fail("asset", "required object is missing (glTF 2.0 section 5.2)");
        const Json* version = find(*asset, "version");
        if (!version || !version->is_string())
            fail("asset.version", "required string is missing");
        const std::string v = version->get<std::string>();
        if (v.rfind("2.", 0) != 0)
            fail("asset.version", "\"" + v + "\": Velvet reads glTF 2.x");
        for (const Json& e : arrayOf(m_doc, "extensionsRequired", "extensionsRequired")) {
            const std::string name = e.is_string() ? e.get<std::string>() : std::string("?");
            if (name != "KHR_texture_transform" && name != "KHR_materials_pbrSpecularGlossiness")
                warn("extensionsRequired: " + name +
                     " is not read by Velvet; the material is imported without it");
        }
        checkBuffers();
    }

    std::vector<std::string> materialNames() const {
        std::vector<std::string> names;
        for (const Json& m : arrayOf(m_doc, "materials", "materials"))
            names.push_back(m.is_object() && m.contains("name") && m["name"].is_string()
                                ? m["name"].get<std::string>()
                                : std::string());
        return names;
    }

    void read(size_t index, ImportedMaterial& out) {
        m_out = &out;
        const std::string place = at("materials", index);
        const Json& m = m_doc["materials"][index];
        if (!m.is_object())
            fail(place, "expected a material object");
        Material& mat = out.material;
        mat = Material();
        mat.name = m.contains("name") && m["name"].is_string()
                       ? m["name"].get<std::string>()
                       : "Material " + std::to_string(index);
        out.hasMesh = !arrayOf(m_doc, "meshes", "meshes").empty();
        checkKeys(m, place,
                  {"name", "pbrMetallicRoughness", "normalTexture", "occlusionTexture",
                   "emissiveTexture", "emissiveFactor", "alphaMode", "alphaCutoff", "doubleSided",
                   "extensions", "extras"});
        const Json* ext = find(m, "extensions");
        const Json* sg = ext ? find(*ext, "KHR_materials_pbrSpecularGlossiness") : nullptr;
        if (sg)
            readSpecGloss(*sg, at(at(place, "extensions"), "KHR_materials_pbrSpecularGlossiness"),
                          find(m, "pbrMetallicRoughness") != nullptr);
        else // absent: glTF's defaults (white, metallic 1, roughness 1), not Velvet's
            readPbr(find(m, "pbrMetallicRoughness") ? m["pbrMetallicRoughness"] : Json::object(),
                    at(place, "pbrMetallicRoughness"));
        if (const Json* n = find(m, "normalTexture")) {
            const std::string p = at(place, "normalTexture");
            texture(*n, p, TextureSlot::Normal, {"scale"});
            setScalar(ParamId::NormalScale, number(*n, "scale", p, -1e9, 1e9, 1.0), p + ".scale");
        }
        if (const Json* o = find(m, "occlusionTexture")) {
            const std::string p = at(place, "occlusionTexture");
            texture(*o, p, TextureSlot::Occlusion, {"strength"});
            setScalar(ParamId::OcclusionStrength, number(*o, "strength", p, 0, 1, 1.0),
                      p + ".strength");
        }
        if (const Json* e = find(m, "emissiveTexture"))
            texture(*e, at(place, "emissiveTexture"), TextureSlot::Emissive, {});
        if (find(m, "emissiveFactor"))
            setColor(ParamId::EmissiveColor,
                     vec3(m, "emissiveFactor", place, 0, 1, glm::vec3(0.0f)),
                     at(place, "emissiveFactor"));
        readAlpha(m, place);
        if (const Json* e = find(m, "extras"); e && !e->empty())
            warn(at(place, "extras") + ": application data, not read");
        if (ext) {
            if (!ext->is_object())
                fail(at(place, "extensions"), "expected an object");
            for (auto it = ext->begin(); it != ext->end(); ++it)
                readExtension(it.key(), it.value(), at(at(place, "extensions"), it.key()));
        }
    }

private:
    // ---- JSON access with places --------------------------------------------------------------
    static const Json* find(const Json& o, std::string_view key) {
        if (!o.is_object())
            return nullptr;
        const auto it = o.find(std::string(key));
        return it == o.end() ? nullptr : &*it;
    }
    /// The array @p key of @p o (empty when absent); not an array is malformed.
    const Json& arrayOf(const Json& o, std::string_view key, const std::string& place) const {
        static const Json empty = Json::array();
        const Json* a = find(o, key);
        if (!a)
            return empty;
        if (!a->is_array())
            fail(place, "expected an array");
        return *a;
    }
    double number(const Json& o, std::string_view key, const std::string& place, double lo,
                  double hi, double fallback) const {
        const Json* v = find(o, key);
        if (!v)
            return fallback;
        const std::string p = at(place, key);
        if (!v->is_number())
            fail(p, "expected a number, got " + v->dump());
        const double d = v->get<double>();
        if (!std::isfinite(d) || d < lo || d > hi)
            fail(p, v->dump() + " is outside the glTF range [" + std::to_string(lo) + ", " +
                        (hi > 1e8 ? std::string("inf") : std::to_string(hi)) + "]");
        return d;
    }
    /// An array of N numbers in [@p lo, @p hi] (a colour factor, baseColorFactor's RGBA).
    template <int N>
    glm::vec<N, float> numbers(const Json& o, std::string_view key, const std::string& place,
                               double lo, double hi, glm::vec<N, float> fallback) const {
        const Json* v = find(o, key);
        if (!v)
            return fallback;
        const std::string p = at(place, key);
        if (!v->is_array() || v->size() != size_t(N))
            fail(p, "expected an array of " + std::to_string(N) + " numbers, got " + v->dump());
        for (int i = 0; i < N; ++i) {
            const Json& c = (*v)[size_t(i)];
            if (!c.is_number() || c.get<double>() < lo || c.get<double>() > hi)
                fail(at(p, size_t(i)),
                     c.dump() + " is outside the glTF range [" + std::to_string(lo) + ", " +
                         (hi > 1e8 ? std::string("inf") : std::to_string(hi)) + "]");
            fallback[i] = c.get<float>();
        }
        return fallback;
    }
    glm::vec3 vec3(const Json& o, std::string_view key, const std::string& place, double lo,
                   double hi, glm::vec3 fallback) const {
        return numbers<3>(o, key, place, lo, hi, fallback);
    }
    /// An index into the top-level array @p array: a dangling one is malformed.
    size_t index(const Json& o, std::string_view key, const std::string& place,
                 std::string_view array) const {
        const Json* v = find(o, key);
        const std::string p = at(place, key);
        if (!v)
            fail(p, "required index is missing");
        if (!v->is_number_integer() || v->get<long long>() < 0)
            fail(p, "expected an index, got " + v->dump());
        const size_t i = v->get<size_t>();
        const size_t count = find(m_doc, array) ? m_doc[std::string(array)].size() : 0;
        if (i >= count)
            fail(p, "refers to " + std::string(array) + "[" + std::to_string(i) + "], but there " +
                        (count == 1 ? "is 1" : "are " + std::to_string(count)));
        return i;
    }
    void checkKeys(const Json& o, const std::string& place,
                   std::initializer_list<std::string_view> known) {
        if (!o.is_object())
            fail(place, "expected an object");
        for (auto it = o.begin(); it != o.end(); ++it)
            if (std::find(known.begin(), known.end(), it.key()) == known.end())
                warn(at(place, it.key()) + ": not a property Velvet maps; ignored");
    }
    void warn(std::string line) { m_warnings.push_back(std::move(line)); }

    // ---- Values into the material (clamped to Velvet's ranges, said when clamped) -------------
    void setScalar(ParamId id, double v, const std::string& place) {
        gltf::setScalar(m_out->material, id, v, place, m_warnings);
    }
    void setColor(ParamId id, glm::vec3 c, const std::string& place) {
        gltf::setColor(m_out->material, id, c, place, m_warnings);
    }

    /// @p key of @p o (glTF range [@p lo, @p hi], default @p fallback) into @p id.
    void scalarInto(ParamId id, const Json& o, std::string_view key, const std::string& place,
                    double lo, double hi, double fallback) {
        setScalar(id, number(o, key, place, lo, hi, fallback), at(place, key));
    }
    /// The textureInfo @p key of @p o, when present, into @p slot.
    void textureInto(TextureSlot slot, const Json& o, std::string_view key,
                     const std::string& place) {
        if (const Json* t = find(o, key))
            texture(*t, at(place, key), slot, {});
    }

    // ---- Buffers and images -------------------------------------------------------------------
    /// The buffers and views as gltf::AssetFiles checks them (glTF 2.0 sections 5.10, 5.11).
    void checkBuffers() {
        const Json& buffers = arrayOf(m_doc, "buffers", "buffers");
        for (size_t i = 0; i < buffers.size(); ++i) {
            const std::string p = at("buffers", i);
            const Json& b = buffers[i];
            gltf::BufferDesc buffer;
            buffer.byteLength = number(b, "byteLength", p, 1, 1e15, -1);
            if (buffer.byteLength < 0)
                fail(at(p, "byteLength"), "required number is missing");
            if (const Json* uri = find(b, "uri")) {
                if (!uri->is_string())
                    fail(at(p, "uri"), "expected a string");
                buffer.uri = uri->get<std::string>();
            }
            m_files.addBuffer(i, std::move(buffer));
        }
        const Json& views = arrayOf(m_doc, "bufferViews", "bufferViews");
        for (size_t i = 0; i < views.size(); ++i) {
            const std::string p = at("bufferViews", i);
            gltf::ViewDesc view;
            view.buffer = index(views[i], "buffer", p, "buffers");
            view.byteOffset = number(views[i], "byteOffset", p, 0, 1e15, 0);
            view.byteLength = number(views[i], "byteLength", p, 1, 1e15, -1);
            if (view.byteLength < 0)
                fail(at(p, "byteLength"), "required number is missing");
            m_files.addView(i, view);
        }
    }
    /// images[@p i] as gltf::AssetFiles reads it.
    gltf::ImageDesc imageDesc(size_t i) const {
        const std::string p = at("images", i);
        const Json& image = m_doc["images"][i];
        gltf::ImageDesc desc;
        if (const Json* uri = find(image, "uri"); uri && uri->is_string()) {
            desc.uri = uri->get<std::string>();
        } else if (find(image, "bufferView")) {
            desc.bufferView = index(image, "bufferView", p, "bufferViews");
            if (const Json* mime = find(image, "mimeType"); mime && mime->is_string())
                desc.mimeType = mime->get<std::string>();
        }
        if (image.contains("name") && image["name"].is_string())
            desc.name = image["name"].get<std::string>();
        return desc;
    }
    /// The file a slot reads for images[@p i] (embedded ones planned in the image folder).
    std::string imageFile(size_t i) {
        if (const std::string* planned = m_files.plannedImageFile(i))
            return *planned;
        return m_files.imageFile(i, imageDesc(i), m_out->images);
    }

    /// A textureInfo (section 5.22) into @p slot: texture, image, sampler, texCoord and
    /// KHR_texture_transform. @p extra: the keys the caller reads (scale, strength).
    void texture(const Json& info, const std::string& place, TextureSlot slot,
                 std::initializer_list<std::string_view> extra) {
        std::vector<std::string_view> known{"index", "texCoord", "extensions", "extras"};
        known.insert(known.end(), extra.begin(), extra.end());
        if (!info.is_object())
            fail(place, "expected a textureInfo object");
        for (auto it = info.begin(); it != info.end(); ++it)
            if (std::find(known.begin(), known.end(), it.key()) == known.end())
                warn(at(place, it.key()) + ": not a property Velvet maps; ignored");
        const size_t t = index(info, "index", place, "textures");
        const std::string tp = at("textures", t);
        const Json& tex = m_doc["textures"][t];
        TextureRef ref;
        if (!find(tex, "source")) {
            std::string exts;
            if (const Json* e = find(tex, "extensions"))
                for (auto it = e->begin(); it != e->end(); ++it)
                    exts += (exts.empty() ? "" : ", ") + it.key();
            warn(place + ": " + tp + " has no PNG or JPEG source" +
                 (exts.empty() ? std::string()
                               : " (only " + exts + ", which Velvet does not read)") +
                 "; textures." + std::string(textureSlotMeta(slot).id) + " left empty");
            return;
        }
        ref.file = imageFile(index(tex, "source", tp, "images"));
        if (const Json* e = find(tex, "extensions"))
            for (auto it = e->begin(); it != e->end(); ++it)
                warn(at(at(tp, "extensions"), it.key()) + ": not read (the PNG/JPEG source is)");
        if (find(tex, "sampler")) {
            const size_t s = index(tex, "sampler", tp, "samplers");
            const Json& sampler = m_doc["samplers"][s];
            const std::string sp = at("samplers", s);
            for (const char* key : {"wrapS", "wrapT"}) {
                const int mode = int(number(sampler, key, sp, 0, 1e6, 10497));
                if (mode != 10497)
                    warn(at(sp, key) + ": " + wrapName(mode) +
                         " is not mapped; Velvet's texture slots repeat");
            }
            if (number(sampler, "magFilter", sp, 0, 1e6, 9729) == 9728)
                warn(at(sp, "magFilter") + ": NEAREST is not mapped; Velvet filters linearly");
        }
        if (number(info, "texCoord", place, 0, 1e6, 0) != 0)
            warn(at(place, "texCoord") + ": Velvet reads TEXCOORD_0 only; TEXCOORD_" +
                 std::to_string(int(number(info, "texCoord", place, 0, 1e6, 0))) + " is not used");
        if (const Json* e = find(info, "extensions")) {
            for (auto it = e->begin(); it != e->end(); ++it) {
                const std::string ep = at(at(place, "extensions"), it.key());
                if (it.key() != "KHR_texture_transform") {
                    warn(ep + ": not mapped");
                    continue;
                }
                const Json& x = it.value();
                checkKeys(x, ep, {"offset", "rotation", "scale", "texCoord"});
                const auto pair = [&](std::string_view key, glm::vec2 fallback) {
                    const Json* v = find(x, key);
                    if (!v)
                        return fallback;
                    if (!v->is_array() || v->size() != 2 || !(*v)[0].is_number() ||
                        !(*v)[1].is_number())
                        fail(at(ep, key), "expected an array of 2 numbers, got " + v->dump());
                    return glm::vec2((*v)[0].get<float>(), (*v)[1].get<float>());
                };
                ref.uv.offset = pair("offset", glm::vec2(0.0f));
                ref.uv.scale = pair("scale", glm::vec2(1.0f));
                // glTF's rotation matrix is the transpose of Velvet's (texture_ref.h).
                ref.uv.rotation = float(-number(x, "rotation", ep, -1e6, 1e6, 0) * 180.0 / kPi);
                if (std::abs(ref.uv.rotation) > kUvRotationLimit)
                    ref.uv.rotation = std::fmod(ref.uv.rotation, 360.0f);
                if (ref.uv.scale.x == 0.0f || ref.uv.scale.y == 0.0f)
                    fail(at(ep, "scale"), "a scale of 0 collapses the texture to one texel");
                if (find(x, "texCoord") && number(x, "texCoord", ep, 0, 1e6, 0) != 0)
                    warn(at(ep, "texCoord") + ": Velvet reads TEXCOORD_0 only");
            }
        }
        m_out->material.setTexture(slot, std::move(ref));
    }

    // ---- The material's parts -------------------------------------------------------------------
    void readPbr(const Json& pbr, const std::string& p) {
        checkKeys(pbr, p,
                  {"baseColorFactor", "baseColorTexture", "metallicFactor", "roughnessFactor",
                   "metallicRoughnessTexture", "extensions", "extras"});
        const glm::vec4 c = numbers<4>(pbr, "baseColorFactor", p, 0, 1, glm::vec4(1.0f));
        setColor(ParamId::BaseColor, glm::vec3(c), at(p, "baseColorFactor"));
        m_baseAlpha = c.a;
        textureInto(TextureSlot::BaseColor, pbr, "baseColorTexture", p);
        scalarInto(ParamId::Metallic, pbr, "metallicFactor", p, 0, 1, 1.0);
        scalarInto(ParamId::Roughness, pbr, "roughnessFactor", p, 0, 1, 1.0);
        textureInto(TextureSlot::MetallicRoughness, pbr, "metallicRoughnessTexture", p);
    }

    void readAlpha(const Json& m, const std::string& place) {
        const std::string mode = m.value("alphaMode", std::string("OPAQUE"));
        if (mode != "OPAQUE" && mode != "MASK" && mode != "BLEND")
            fail(at(place, "alphaMode"), "\"" + mode + "\": expected OPAQUE, MASK or BLEND");
        const double cutoff = number(m, "alphaCutoff", place, 0, 1e9, 0.5);
        if (mode == "BLEND")
            warn(at(place, "alphaMode") + ": BLEND is not mapped; Velvet cuts the base colour "
                                          "alpha out below 0.5 (no transparency)");
        if (mode == "MASK" && cutoff != 0.5)
            warn(at(place, "alphaCutoff") + ": " + formatValue(float(cutoff)) +
                 " is not mapped; Velvet's cut-out threshold is 0.5");
        if (mode == "OPAQUE" && baseTextureHasAlpha())
            warn(at(place, "alphaMode") + ": OPAQUE ignores the base colour texture's alpha; "
                                          "Velvet cuts out where it is below 0.5");
        if (m_baseAlpha < 1.0f)
            warn(at(place, "pbrMetallicRoughness.baseColorFactor") + "[3]: alpha " +
                 formatValue(m_baseAlpha) + " is not mapped (Velvet has no opacity factor)");
    }

    bool baseTextureHasAlpha() const {
        return m_files.hasAlpha(m_out->material.texture(TextureSlot::BaseColor).file,
                                m_out->images);
    }

    void readSpecGloss(const Json& sg, const std::string& p, bool hasPbr) {
        checkKeys(sg, p,
                  {"diffuseFactor", "diffuseTexture", "specularFactor", "glossinessFactor",
                   "specularGlossinessTexture", "extras"});
        if (hasPbr)
            warn(p + ": converted; the material's pbrMetallicRoughness fallback is not read");
        SpecGloss f;
        const glm::vec4 diffuseFactor = numbers<4>(sg, "diffuseFactor", p, 0, 1, glm::vec4(1.0f));
        f.diffuse = glm::vec3(diffuseFactor);
        const float alpha = diffuseFactor.a;
        f.specular = vec3(sg, "specularFactor", p, 0, 1, glm::vec3(1.0f));
        f.glossiness = float(number(sg, "glossinessFactor", p, 0, 1, 1.0));
        m_baseAlpha = alpha;
        Material& mat = m_out->material;
        const Json* dt = find(sg, "diffuseTexture");
        const Json* st = find(sg, "specularGlossinessTexture");
        if (!dt && !st) {
            const MetalRough mr = specGlossToMetalRough(f);
            mat.setColor(ParamId::BaseColor, mr.baseColor);
            mat.setScalar(ParamId::Metallic, mr.metallic);
            mat.setScalar(ParamId::Roughness, mr.roughness);
            return;
        }
        // Textures: converted texel by texel into a base colour and a metallic-roughness image
        // (the conversion is not linear, so factors cannot stay apart), factors 1.
        Image diffuse, specGloss;
        if (dt)
            loadImage(*dt, at(p, "diffuseTexture"), diffuse);
        if (st)
            loadImage(*st, at(p, "specularGlossinessTexture"), specGloss);
        Image base, mr;
        specGlossImages(diffuse, specGloss, f, alpha, base, mr);
        struct Converted {
            const Image* image;
            const char* label;
            TextureSlot slot;
        };
        const Converted converted[] = {{&base, "baseColor", TextureSlot::BaseColor},
                                       {&mr, "metallicRoughness", TextureSlot::MetallicRoughness}};
        for (const auto& [image, label, slot] : converted) {
            TextureRef ref;
            ref.file = m_files.addConvertedImage(*image, label, p, m_out->images);
            mat.setTexture(slot, ref);
        }
        mat.setColor(ParamId::BaseColor, glm::vec3(1.0f));
        mat.setScalar(ParamId::Metallic, 1.0f);
        mat.setScalar(ParamId::Roughness, 1.0f);
    }

    /// Decodes the image a spec-gloss textureInfo names (through a temporary file for embedded
    /// ones: core's image reader takes files).
    void loadImage(const Json& info, const std::string& place, Image& out) {
        const size_t t = index(info, "index", place, "textures");
        const Json& tex = m_doc["textures"][t];
        const size_t i = index(tex, "source", at("textures", t), "images");
        m_files.decodeImage(i, imageDesc(i), place, m_out->images, out);
        if (number(info, "texCoord", place, 0, 1e6, 0) != 0 || find(info, "extensions"))
            warn(place + ": texCoord and extensions are not read for converted textures");
    }

    void readExtension(const std::string& name, const Json& e, const std::string& p) {
        Material& m = m_out->material;
        if (name == "KHR_materials_pbrSpecularGlossiness")
            return; // read first
        if (name == "KHR_materials_emissive_strength") {
            checkKeys(e, p, {"emissiveStrength"});
            scalarInto(ParamId::EmissiveStrength, e, "emissiveStrength", p, 0, 1e12, 1.0);
        } else if (name == "KHR_materials_ior") {
            checkKeys(e, p, {"ior"});
            const double ior = number(e, "ior", p, 0, 1e12, 1.5);
            if (ior != 0 && ior < 1)
                fail(at(p, "ior"), std::to_string(ior) + ": glTF allows 0 or at least 1");
            if (ior == 0)
                warn(at(p, "ior") + ": 0 (an infinite IOR, full reflection) is not mapped; "
                                    "Velvet's IOR is at most 3");
            setScalar(ParamId::Ior, ior == 0 ? 3.0 : ior, at(p, "ior"));
        } else if (name == "KHR_materials_specular") {
            checkKeys(e, p,
                      {"specularFactor", "specularTexture", "specularColorFactor",
                       "specularColorTexture"});
            scalarInto(ParamId::SpecularWeight, e, "specularFactor", p, 0, 1, 1.0);
            setColor(ParamId::SpecularColor,
                     vec3(e, "specularColorFactor", p, 0, 1e12, glm::vec3(1.0f)),
                     at(p, "specularColorFactor"));
            textureInto(TextureSlot::Specular, e, "specularTexture", p);
            textureInto(TextureSlot::SpecularColor, e, "specularColorTexture", p);
        } else if (name == "KHR_materials_clearcoat") {
            checkKeys(e, p,
                      {"clearcoatFactor", "clearcoatTexture", "clearcoatRoughnessFactor",
                       "clearcoatRoughnessTexture", "clearcoatNormalTexture"});
            scalarInto(ParamId::ClearcoatWeight, e, "clearcoatFactor", p, 0, 1, 0.0);
            scalarInto(ParamId::ClearcoatRoughness, e, "clearcoatRoughnessFactor", p, 0, 1, 0.0);
            textureInto(TextureSlot::Clearcoat, e, "clearcoatTexture", p);
            textureInto(TextureSlot::ClearcoatRoughness, e, "clearcoatRoughnessTexture", p);
            if (const Json* t = find(e, "clearcoatNormalTexture")) {
                const std::string tp = at(p, "clearcoatNormalTexture");
                texture(*t, tp, TextureSlot::ClearcoatNormal, {"scale"});
                setScalar(ParamId::ClearcoatNormalScale, number(*t, "scale", tp, -1e9, 1e9, 1.0),
                          at(tp, "scale"));
            }
        } else if (name == "KHR_materials_sheen") {
            checkKeys(e, p,
                      {"sheenColorFactor", "sheenColorTexture", "sheenRoughnessFactor",
                       "sheenRoughnessTexture"});
            // glTF's sheen has no weight: Velvet's weight is the colour's largest channel and
            // its colour the factor over it, so weight x colour is the file's factor exactly.
            const glm::vec3 c = vec3(e, "sheenColorFactor", p, 0, 1, glm::vec3(0.0f));
            const float w = std::max({c.r, c.g, c.b});
            m.setScalar(ParamId::SheenWeight, w);
            if (w > 0.0f)
                m.setColor(ParamId::SheenColor, c / w);
            scalarInto(ParamId::SheenRoughness, e, "sheenRoughnessFactor", p, 0, 1, 0.0);
            textureInto(TextureSlot::SheenColor, e, "sheenColorTexture", p);
            textureInto(TextureSlot::SheenRoughness, e, "sheenRoughnessTexture", p);
        } else if (name == "KHR_materials_anisotropy") {
            checkKeys(e, p, {"anisotropyStrength", "anisotropyRotation", "anisotropyTexture"});
            scalarInto(ParamId::AnisotropyStrength, e, "anisotropyStrength", p, 0, 1, 0.0);
            // Radians in the file, degrees in Velvet, wrapped into [-180, 180] (a whole turn
            // changes nothing).
            const double rad = number(e, "anisotropyRotation", p, -1e9, 1e9, 0.0);
            m.setScalar(ParamId::AnisotropyRotation,
                        float(std::remainder(rad * 180.0 / std::numbers::pi, 360.0)));
            textureInto(TextureSlot::Anisotropy, e, "anisotropyTexture", p);
        } else {
            // KHR_materials_transmission, _volume, _iridescence, _unlit, …: Velvet
            // has no counterpart (yet); the material is imported without it.
            warn(p + ": " + name +
                 " is not mapped (Velvet has no counterpart); imported without it");
        }
    }

public:
    std::vector<std::string> m_warnings; // before m_files, which appends to it

private:
    gltf::AssetFiles m_files;
    Json m_doc;
    ImportedMaterial* m_out = nullptr;
    float m_baseAlpha = 1.0f;
};

} // namespace

bool readGltfMaterialNames(const fs::path& file, std::vector<std::string>& names,
                           ImportProblem& problem) {
    try {
        Reader r(file, {}, "x");
        r.load();
        names = r.materialNames();
        return true;
    } catch (const Failure& f) {
        problem = f.problem;
        return false;
    } catch (const Json::exception& e) { // as importGltfMaterial: never out of the reader
        problem = {ImportProblem::Kind::Malformed, "", std::string("unexpected JSON: ") + e.what()};
        return false;
    }
}

bool importGltfMaterial(const fs::path& file, std::string_view select, const fs::path& imageFolder,
                        std::string_view imageStem, ImportedMaterial& out, ImportProblem& problem) {
    out = {};
    try {
        Reader r(file, imageFolder, std::string(imageStem));
        r.load();
        size_t index = 0;
        if (!selectMaterial(r.materialNames(), select, index, problem))
            return false;
        r.read(index, out);
        // Warnings in the order found: the container's first, then the material's.
        out.warnings.insert(out.warnings.begin(), r.m_warnings.begin(), r.m_warnings.end());
        return true;
    } catch (const Failure& f) {
        problem = f.problem;
        return false;
    } catch (const Json::exception& e) { // a type the checks above did not foresee
        problem = {ImportProblem::Kind::Malformed, "", std::string("unexpected JSON: ") + e.what()};
        return false;
    }
}

} // namespace velvet
