// glTF 2.0 export. References: the glTF 2.0 specification (Khronos, 2021; section numbers
// below), KHR_materials_clearcoat, _sheen, _specular, _ior, _emissive_strength, _anisotropy and
// KHR_texture_transform (github.com/KhronosGroup/glTF, extensions/2.0/Khronos/). The mapping of
// each parameter is tabled in docs/interchange.md.
#include "core/gltf_export.h"

#include "core/gltf_textures.h"
#include "core/mapping_warnings.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

namespace velvet {
namespace {

using Json = nlohmann::ordered_json;

// glTF enumerations (section 5): component types, buffer-view targets, sampler filters.
constexpr int kFloat = 5126, kUnsignedShort = 5123, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kLinear = 9729, kLinearMipmapLinear = 9987, kRepeat = 10497;

/// @p f as the double nearest its shortest decimal form, so files say 0.8, not
/// 0.800000011920929, and read back as the same float.
double num(float f) {
    char text[32];
    const auto r = std::to_chars(text, text + sizeof text, f);
    *r.ptr = '\0';
    return std::strtod(text, nullptr);
}

Json vec3Json(glm::vec3 v) {
    return Json::array({num(v.x), num(v.y), num(v.z)});
}

/// One binary buffer: every chunk 4-byte aligned (section 3.6.2.4: an accessor's offset is a
/// multiple of its component size; GLB chunks are 4-aligned).
struct BinaryBuffer {
    std::string bytes;
    Json views = Json::array();

    int add(const void* data, size_t size, int target) {
        while (bytes.size() % 4)
            bytes.push_back('\0');
        Json v{{"buffer", 0}, {"byteOffset", bytes.size()}, {"byteLength", size}};
        if (target)
            v["target"] = target;
        bytes.append(static_cast<const char*>(data), size);
        views.push_back(std::move(v));
        return int(views.size()) - 1;
    }
};

/// Unit normals and tangents with w = ±1, as glTF requires of NORMAL and TANGENT (section
/// 3.7.2.1; the validator checks both): generated frames can hold a zero or slightly off vector
/// at a pole or a degenerate triangle.
void cleanFrame(Vertex& v) {
    const float nl = glm::length(v.normal);
    v.normal = nl > 1e-8f ? v.normal / nl : glm::vec3(0, 1, 0);
    glm::vec3 t(v.tangent);
    t -= v.normal * glm::dot(v.normal, t);
    float tl = glm::length(t);
    if (tl <= 1e-8f) {
        t = std::abs(v.normal.x) < 0.9f ? glm::cross(v.normal, glm::vec3(1, 0, 0))
                                        : glm::cross(v.normal, glm::vec3(0, 1, 0));
        tl = glm::length(t);
    }
    t /= tl;
    v.tangent = glm::vec4(t, v.tangent.w < 0.0f ? -1.0f : 1.0f);
}

/// The mesh as one primitive: POSITION (with min/max, section 3.6.2.5), NORMAL, TANGENT,
/// TEXCOORD_0 and indices, each attribute its own tightly packed buffer view.
Json meshPrimitive(const MeshData& mesh, BinaryBuffer& buffer, Json& accessors) {
    std::vector<Vertex> vertices = mesh.vertices;
    for (Vertex& v : vertices)
        cleanFrame(v);
    const size_t n = vertices.size();
    std::vector<float> pos(n * 3), nor(n * 3), tan(n * 4), uv(n * 2);
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (size_t i = 0; i < n; ++i) {
        const Vertex& v = vertices[i];
        std::memcpy(&pos[i * 3], &v.position, sizeof(float) * 3);
        std::memcpy(&nor[i * 3], &v.normal, sizeof(float) * 3);
        std::memcpy(&tan[i * 4], &v.tangent, sizeof(float) * 4);
        std::memcpy(&uv[i * 2], &v.uv, sizeof(float) * 2);
        lo = glm::min(lo, v.position);
        hi = glm::max(hi, v.position);
    }
    auto accessor = [&](int view, int componentType, size_t count, const char* type) {
        accessors.push_back(Json{{"bufferView", view},
                                 {"componentType", componentType},
                                 {"count", count},
                                 {"type", type}});
        return int(accessors.size()) - 1;
    };
    Json attributes;
    const int p = accessor(buffer.add(pos.data(), pos.size() * 4, kArrayBuffer), kFloat, n, "VEC3");
    // Exact float values: the validator compares them with the data bit for bit.
    accessors[size_t(p)]["min"] = {double(lo.x), double(lo.y), double(lo.z)};
    accessors[size_t(p)]["max"] = {double(hi.x), double(hi.y), double(hi.z)};
    attributes["POSITION"] = p;
    attributes["NORMAL"] =
        accessor(buffer.add(nor.data(), nor.size() * 4, kArrayBuffer), kFloat, n, "VEC3");
    attributes["TANGENT"] =
        accessor(buffer.add(tan.data(), tan.size() * 4, kArrayBuffer), kFloat, n, "VEC4");
    attributes["TEXCOORD_0"] =
        accessor(buffer.add(uv.data(), uv.size() * 4, kArrayBuffer), kFloat, n, "VEC2");
    int indices;
    if (n <= 65535) { // 16-bit indices where they suffice (half the bytes)
        std::vector<std::uint16_t> i16(mesh.indices.begin(), mesh.indices.end());
        indices = accessor(buffer.add(i16.data(), i16.size() * 2, kElementArrayBuffer),
                           kUnsignedShort, i16.size(), "SCALAR");
    } else {
        indices =
            accessor(buffer.add(mesh.indices.data(), mesh.indices.size() * 4, kElementArrayBuffer),
                     kUnsignedInt, mesh.indices.size(), "SCALAR");
    }
    return Json{{"attributes", attributes}, {"indices", indices}, {"material", 0}, {"mode", 4}};
}

class MaterialWriter {
public:
    MaterialWriter(const GltfTexturePlan& plan, Json& textures)
        : m_plan(plan), m_textures(textures) {}

    /// A textureInfo (section 5.22) for @p slot, or null when the slot has no texture.
    Json textureInfo(TextureSlot slot) {
        const auto& use = m_plan.uses[size_t(slot)];
        if (!use)
            return nullptr;
        // One glTF texture per (image, transform) pair would also do; one per image is enough
        // because the transform lives on the textureInfo.
        Json info{{"index", textureFor(use->image)}};
        if (use->transformed) {
            Json t{{"offset", {num(use->offset.x), num(use->offset.y)}}};
            if (use->rotation != 0.0f)
                t["rotation"] = num(use->rotation);
            t["scale"] = {num(use->scale.x), num(use->scale.y)};
            info["extensions"]["KHR_texture_transform"] = t;
            usesTransform = true;
        }
        return info;
    }
    bool usesTransform = false;

private:
    int textureFor(int image) {
        for (size_t i = 0; i < m_textures.size(); ++i)
            if (m_textures[i]["source"] == image)
                return int(i);
        m_textures.push_back(Json{{"sampler", 0}, {"source", image}});
        return int(m_textures.size()) - 1;
    }
    const GltfTexturePlan& m_plan;
    Json& m_textures;
};

/// Sets key to @p info when the slot has a texture.
void putTexture(Json& object, const char* key, Json info) {
    if (!info.is_null())
        object[key] = std::move(info);
}

Json materialJson(const Material& m, const GltfTexturePlan& plan, bool doubleSided, Json& textures,
                  std::vector<std::string>& extensions, bool& transform) {
    MaterialWriter w(plan, textures);
    Json mat{{"name", m.name}};
    // Core metallic-roughness (section 3.9.2): factors times textures, as Velvet's G-buffer
    // pass multiplies them (resources/shaders/gbuffer.frag).
    Json pbr;
    const glm::vec3 base = m.color(ParamId::BaseColor);
    pbr["baseColorFactor"] = {num(base.x), num(base.y), num(base.z), 1.0};
    pbr["metallicFactor"] = num(m.scalar(ParamId::Metallic));
    pbr["roughnessFactor"] = num(m.scalar(ParamId::Roughness));
    putTexture(pbr, "baseColorTexture", w.textureInfo(TextureSlot::BaseColor));
    putTexture(pbr, "metallicRoughnessTexture", w.textureInfo(TextureSlot::MetallicRoughness));
    mat["pbrMetallicRoughness"] = pbr;
    if (Json n = w.textureInfo(TextureSlot::Normal); !n.is_null()) {
        n["scale"] = num(m.scalar(ParamId::NormalScale));
        mat["normalTexture"] = n;
    }
    if (Json o = w.textureInfo(TextureSlot::Occlusion); !o.is_null()) {
        o["strength"] = num(m.scalar(ParamId::OcclusionStrength));
        mat["occlusionTexture"] = o;
    }
    const glm::vec3 emissive = m.color(ParamId::EmissiveColor);
    if (emissive != glm::vec3(0.0f) || plan.uses[size_t(TextureSlot::Emissive)]) {
        mat["emissiveFactor"] = vec3Json(emissive);
        putTexture(mat, "emissiveTexture", w.textureInfo(TextureSlot::Emissive));
    }
    if (plan.alphaCutout) {
        mat["alphaMode"] = "MASK"; // alphaCutoff's default, 0.5, is Velvet's cut-out threshold
    }
    if (doubleSided)
        mat["doubleSided"] = true;

    Json ext = Json::object();
    // KHR_materials_emissive_strength: the factor above stays in [0, 1], the strength scales it.
    const float strength = m.scalar(ParamId::EmissiveStrength);
    if (strength != 1.0f && mat.contains("emissiveFactor"))
        ext["KHR_materials_emissive_strength"] = {{"emissiveStrength", num(strength)}};
    // KHR_materials_ior: present when it differs from the extension's default, 1.5.
    if (m.scalar(ParamId::Ior) != 1.5f)
        ext["KHR_materials_ior"] = {{"ior", num(m.scalar(ParamId::Ior))}};
    // KHR_materials_specular: dielectric F0 = min(F0(ior) * specularColor, 1) * specular.
    {
        Json s;
        if (m.scalar(ParamId::SpecularWeight) != 1.0f)
            s["specularFactor"] = num(m.scalar(ParamId::SpecularWeight));
        if (m.color(ParamId::SpecularColor) != glm::vec3(1.0f))
            s["specularColorFactor"] = vec3Json(m.color(ParamId::SpecularColor));
        putTexture(s, "specularTexture", w.textureInfo(TextureSlot::Specular));
        putTexture(s, "specularColorTexture", w.textureInfo(TextureSlot::SpecularColor));
        if (!s.is_null())
            ext["KHR_materials_specular"] = s;
    }
    // KHR_materials_clearcoat: only when the coat is on (a weight of 0 switches it off whatever
    // its textures say).
    if (m.scalar(ParamId::ClearcoatWeight) > 0.0f) {
        Json c{{"clearcoatFactor", num(m.scalar(ParamId::ClearcoatWeight))},
               {"clearcoatRoughnessFactor", num(m.scalar(ParamId::ClearcoatRoughness))}};
        putTexture(c, "clearcoatTexture", w.textureInfo(TextureSlot::Clearcoat));
        putTexture(c, "clearcoatRoughnessTexture", w.textureInfo(TextureSlot::ClearcoatRoughness));
        if (Json n = w.textureInfo(TextureSlot::ClearcoatNormal); !n.is_null()) {
            n["scale"] = num(m.scalar(ParamId::ClearcoatNormalScale));
            c["clearcoatNormalTexture"] = n;
        }
        ext["KHR_materials_clearcoat"] = c;
    }
    // KHR_materials_sheen has no weight: Velvet's weight scales the colour (sheenColorFactor =
    // weight x colour); the sheen colour texture multiplies it as in Velvet.
    if (m.scalar(ParamId::SheenWeight) > 0.0f) {
        Json s{{"sheenColorFactor",
                vec3Json(m.scalar(ParamId::SheenWeight) * m.color(ParamId::SheenColor))},
               {"sheenRoughnessFactor", num(m.scalar(ParamId::SheenRoughness))}};
        putTexture(s, "sheenColorTexture", w.textureInfo(TextureSlot::SheenColor));
        putTexture(s, "sheenRoughnessTexture", w.textureInfo(TextureSlot::SheenRoughness));
        ext["KHR_materials_sheen"] = s;
    }
    // KHR_materials_anisotropy: the same strength and texture (RG direction, B strength); the
    // rotation in radians where Velvet keeps degrees. Written when the strength is above 0 or a
    // direction texture is set (the extension's defaults are strength 0, rotation 0).
    {
        const float strength = m.scalar(ParamId::AnisotropyStrength);
        Json a;
        putTexture(a, "anisotropyTexture", w.textureInfo(TextureSlot::Anisotropy));
        if (strength > 0.0f || !a.is_null()) {
            a["anisotropyStrength"] = num(strength);
            if (const float r = m.scalar(ParamId::AnisotropyRotation); r != 0.0f)
                a["anisotropyRotation"] = num(glm::radians(r));
            ext["KHR_materials_anisotropy"] = a;
        }
    }
    for (auto it = ext.begin(); it != ext.end(); ++it)
        extensions.push_back(it.key());
    if (!ext.empty())
        mat["extensions"] = ext;
    transform = w.usesTransform;
    return mat;
}

/// GLB container (section 4.4): 12-byte header, a JSON chunk padded with spaces, a BIN chunk
/// padded with zeros, each chunk 4-aligned.
std::string glbBytes(std::string json, std::string bin) {
    while (json.size() % 4)
        json.push_back(' ');
    while (bin.size() % 4)
        bin.push_back('\0');
    std::string out;
    auto u32 = [&out](std::uint32_t v) {
        for (int i = 0; i < 4; ++i)
            out.push_back(char((v >> (8 * i)) & 0xff));
    };
    const size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
    u32(0x46546C67); // "glTF"
    u32(2);
    u32(std::uint32_t(total));
    u32(std::uint32_t(json.size()));
    u32(0x4E4F534A); // "JSON"
    out += json;
    if (!bin.empty()) {
        u32(std::uint32_t(bin.size()));
        u32(0x004E4942); // "BIN\0"
        out += bin;
    }
    return out;
}

} // namespace

bool buildGltf(const Material& source, const MeshData& mesh, std::string_view baseName,
               GltfContainer container, TextureCache& textures, GltfExportResult& out,
               std::string* error, const BakedMaterialMaps* baked) {
    out = {};
    if (mesh.vertices.empty() || mesh.indices.empty()) {
        *error = "the mesh has no triangles";
        return false;
    }
    GltfTexturePlan plan;
    if (!planGltfTextures(source, textures, plan, error))
        return false;
    std::vector<std::string> bakeWarnings;
    // The exported material: the graph-driven inputs' factors neutral, their slots the bake's.
    const Material material = baked ? applyBakedMaps(source, *baked, plan, bakeWarnings) : source;
    const std::string base(baseName);
    const bool glb = container == GltfContainer::Glb;

    Json doc;
    doc["asset"] = {{"version", "2.0"}, {"generator", "Velvet"}};
    BinaryBuffer buffer;
    Json accessors = Json::array();
    const Json primitive = meshPrimitive(mesh, buffer, accessors);

    Json gltfTextures = Json::array();
    std::vector<std::string> extensions;
    bool transform = false;
    const Json mat =
        materialJson(material, plan, mesh.doubleSided, gltfTextures, extensions, transform);

    // Images: PNG, embedded in the binary chunk (.glb) or files beside the .gltf.
    Json images = Json::array();
    std::vector<ExportFile> imageFiles;
    for (const GltfImage& image : plan.images) {
        std::string png;
        if (!encodeImage(image.pixels, ".png", PixelFormat::UInt8, png, error))
            return false;
        Json entry{{"name", image.label}};
        if (glb) {
            entry["bufferView"] = buffer.add(png.data(), png.size(), 0);
            entry["mimeType"] = "image/png";
        } else {
            const std::string file = base + "_" + image.label + ".png";
            entry["uri"] = file; // a safe stem and label: no character needs percent-encoding
            imageFiles.push_back({file, std::move(png)});
        }
        images.push_back(std::move(entry));
    }

    if (transform)
        extensions.push_back("KHR_texture_transform");
    std::sort(extensions.begin(), extensions.end());
    if (!extensions.empty())
        doc["extensionsUsed"] = extensions;
    // An atlas region shown whole would be wrong, not merely plainer: a viewer without
    // KHR_texture_transform must refuse the file rather than show the whole atlas.
    if (transform)
        doc["extensionsRequired"] = {"KHR_texture_transform"};
    doc["scene"] = 0;
    doc["scenes"] = Json::array({Json{{"name", material.name}, {"nodes", {0}}}});
    doc["nodes"] = Json::array({Json{{"name", material.name}, {"mesh", 0}}});
    doc["meshes"] = Json::array({Json{{"name", material.name}, {"primitives", {primitive}}}});
    doc["materials"] = Json::array({mat});
    if (!gltfTextures.empty()) {
        // Trilinear, repeating: what the viewport's texture slots use.
        doc["samplers"] = Json::array({Json{{"magFilter", kLinear},
                                            {"minFilter", kLinearMipmapLinear},
                                            {"wrapS", kRepeat},
                                            {"wrapT", kRepeat}}});
        doc["textures"] = gltfTextures;
        doc["images"] = images;
    }
    doc["accessors"] = accessors;
    doc["bufferViews"] = buffer.views;
    Json bufferJson{{"byteLength", buffer.bytes.size()}};
    if (!glb)
        bufferJson["uri"] = base + ".bin";
    doc["buffers"] = Json::array({bufferJson});

    out.warnings = mappingWarnings(material, "glTF 2.0");
    out.warnings.insert(out.warnings.end(), bakeWarnings.begin(), bakeWarnings.end());
    out.warnings.insert(out.warnings.end(), plan.warnings.begin(), plan.warnings.end());
    if (glb) {
        out.files.push_back({base + ".glb", glbBytes(doc.dump(), std::move(buffer.bytes))});
    } else {
        out.files = std::move(imageFiles);
        out.files.push_back({base + ".bin", std::move(buffer.bytes)});
        out.files.push_back({base + ".gltf", doc.dump(2) + "\n"});
    }
    return true;
}

} // namespace velvet
