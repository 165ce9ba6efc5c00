#include "core/texture_set_export.h"

#include "core/channel_packing.h"
#include "core/color_management.h"
#include "core/texture_set_lobes.h"

#include <algorithm>
#include <array>
#include <nlohmann/json.hpp>

namespace velvet {
namespace {

using Json = nlohmann::ordered_json;

struct TargetInfo {
    std::string_view id;
    std::string_view label;
    NormalConvention normal;
    /// File names: prefix + base + suffix; suffixes for base colour, normal, packed, emissive.
    std::string_view prefix;
    std::array<std::string_view, 4> suffix;
};

// Names follow each engine's documented conventions: Unreal's asset naming (T_ prefix, _D base
// colour, _N normal, _ORM packed occlusion-roughness-metallic, _E emissive); HDRP Lit's inputs
// (Base Map, Mask Map, Normal Map, Emissive Color); Godot's ORMMaterial3D properties
// (albedo_texture, orm_texture, normal_texture, emission_texture); glTF 2.0's material textures.
// Normal maps: Unreal expects DirectX (+Y down, its importer's "Flip Green Channel" for OpenGL
// maps); Unity, Godot and glTF expect OpenGL (+Y up; Unity's manual: "Unity uses Y+ normal maps").
constexpr TargetInfo kTargets[] = {
    {"unreal",
     "Unreal Engine (ORM, DirectX normals)",
     NormalConvention::DirectX,
     "T_",
     {"_D", "_N", "_ORM", "_E"}},
    {"unity-hdrp",
     "Unity HDRP (mask map MODS, OpenGL normals)",
     NormalConvention::OpenGl,
     "",
     {"_BaseMap", "_Normal", "_MaskMap", "_Emission"}},
    {"godot",
     "Godot (ORMMaterial3D, OpenGL normals)",
     NormalConvention::OpenGl,
     "",
     {"_albedo", "_normal", "_orm", "_emission"}},
    {"gltf",
     "glTF 2.0 (ORM, OpenGL normals)",
     NormalConvention::OpenGl,
     "",
     {"_baseColor", "_normal", "_orm", "_emissive"}},
};
constexpr std::string_view kFileTypes[] = {"png", "tga", "exr"};

const TargetInfo& info(TextureSetTarget t) {
    return kTargets[size_t(t)];
}

int bitsOf(const TextureSetOptions& o) {
    if (o.bits != 0)
        return o.bits;
    return o.fileType == TextureFileType::Exr ? 16 : 8;
}

PixelFormat pixelFormatOf(const TextureSetOptions& o) {
    const int bits = bitsOf(o);
    if (o.fileType == TextureFileType::Exr)
        return bits == 32 ? PixelFormat::Float : PixelFormat::Half;
    return bits == 16 ? PixelFormat::UInt16 : PixelFormat::UInt8;
}

Image channel(const Image& rgb, int c) {
    Image out(rgb.width, rgb.height, 1);
    for (size_t i = 0; i < out.pixels.size(); ++i)
        out.pixels[i] = rgb.pixels[i * size_t(rgb.channels) + size_t(c)];
    return out;
}

bool sameSize(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height;
}

} // namespace

std::string_view textureSetTargetId(TextureSetTarget target) {
    return info(target).id;
}
std::string_view textureSetTargetLabel(TextureSetTarget target) {
    return info(target).label;
}
std::optional<TextureSetTarget> textureSetTargetFromId(std::string_view id) {
    for (size_t i = 0; i < std::size(kTargets); ++i)
        if (kTargets[i].id == id)
            return TextureSetTarget(i);
    return std::nullopt;
}

NormalConvention defaultNormalConvention(TextureSetTarget target) {
    return info(target).normal;
}
std::string_view normalConventionId(NormalConvention convention) {
    return convention == NormalConvention::DirectX ? "directx" : "opengl";
}

std::string_view textureFileTypeId(TextureFileType type) {
    return kFileTypes[size_t(type)];
}
std::optional<TextureFileType> textureFileTypeFromId(std::string_view id) {
    for (size_t i = 0; i < std::size(kFileTypes); ++i)
        if (kFileTypes[i] == id)
            return TextureFileType(i);
    return std::nullopt;
}

std::string checkTextureSetOptions(const TextureSetOptions& o) {
    if (o.size < 1 || o.size > 8192)
        return "the size must be 1 to 8192 texels a side, got " + std::to_string(o.size);
    const int bits = bitsOf(o);
    switch (o.fileType) {
    case TextureFileType::Png:
        if (bits != 8 && bits != 16)
            return "PNG holds 8 or 16 bits per channel, not " + std::to_string(bits);
        break;
    case TextureFileType::Tga:
        if (bits != 8)
            return "TGA holds 8 bits per channel, not " + std::to_string(bits);
        break;
    case TextureFileType::Exr:
        if (bits != 16 && bits != 32)
            return "EXR holds 16 (half) or 32 (float) bits per channel, not " +
                   std::to_string(bits);
        break;
    case TextureFileType::Count:
        return "unknown file type";
    }
    return {};
}

std::vector<TextureSetFile> planTextureSet(const TextureSetOptions& o, std::string_view base,
                                           bool hasAlpha, bool hasEmission) {
    const TargetInfo& t = info(o.target);
    const std::string ext = "." + std::string(textureFileTypeId(o.fileType));
    const bool exr = o.fileType == TextureFileType::Exr;
    const std::string colour = exr ? "linear" : "srgb";
    auto name = [&](int i) {
        return std::string(t.prefix) + std::string(base) + std::string(t.suffix[size_t(i)]) + ext;
    };
    std::vector<TextureSetFile> files;
    files.push_back({name(0),
                     "baseColor",
                     colour,
                     {"baseColor.r", "baseColor.g", "baseColor.b", hasAlpha ? "alpha" : ""}});
    const NormalConvention nc = o.normal.value_or(t.normal);
    files.push_back(
        {name(1),
         "normal",
         "linear",
         {"normal.x", nc == NormalConvention::DirectX ? "-normal.y" : "normal.y", "normal.z", ""}});
    if (o.target == TextureSetTarget::UnityHdrp)
        files.push_back(
            {name(2), "maskMap", "linear", {"metallic", "occlusion", "detailMask", "smoothness"}});
    else
        files.push_back({name(2),
                         "occlusionRoughnessMetallic",
                         "linear",
                         {"occlusion", "roughness", "metallic", ""}});
    if (hasEmission)
        files.push_back(
            {name(3), "emissive", colour, {"emissive.r", "emissive.g", "emissive.b", ""}});
    return files;
}

bool buildTextureSet(const MaterialMaps& maps, std::string_view base, std::string_view materialName,
                     const TextureSetOptions& o, BuiltExport& out, std::string* error) {
    auto fail = [&](const std::string& why) {
        if (error)
            *error = why;
        return false;
    };
    if (const std::string why = checkTextureSetOptions(o); !why.empty())
        return fail(why);
    if (maps.baseColor.empty() || maps.baseColor.channels != 4 || maps.normal.channels < 3 ||
        maps.orm.channels < 3 || maps.emission.channels < 3)
        return fail("the baked maps are missing or have too few channels");
    if (!sameSize(maps.baseColor, maps.normal) || !sameSize(maps.baseColor, maps.orm) ||
        !sameSize(maps.baseColor, maps.emission))
        return fail("the baked maps differ in size");
    for (const Image* lobe : {&maps.coat, &maps.sheen, &maps.specular, &maps.anisotropy})
        if (!lobe->empty() && !sameSize(maps.baseColor, *lobe))
            return fail("the baked lobe maps differ in size from the base maps");
    const int w = maps.baseColor.width, h = maps.baseColor.height;
    const size_t count = size_t(w) * size_t(h);
    const bool exr = o.fileType == TextureFileType::Exr;

    bool hasAlpha = false;
    for (size_t i = 0; i < count; ++i)
        hasAlpha = hasAlpha || maps.baseColor.pixels[i * 4 + 3] < 1.0f;
    float emissionMax = 0.0f;
    for (size_t i = 0; i < count; ++i)
        for (int c = 0; c < 3; ++c)
            emissionMax =
                std::max(emissionMax, maps.emission.pixels[i * size_t(maps.emission.channels) + c]);
    const bool hasEmission = emissionMax > 0.0f;
    // 8/16-bit integers hold [0, 1]: emission is divided by its maximum (the manifest's scale).
    const float emissionScale = exr ? 1.0f : std::max(1.0f, emissionMax);
    const NormalConvention nc = o.normal.value_or(info(o.target).normal);
    std::vector<TextureSetFile> plan = planTextureSet(o, base, hasAlpha, hasEmission);
    const std::vector<TextureSetFile> lobes = planLobeMaps(o, base, lobePresence(maps));

    // Colour maps: sRGB-encoded where the file holds display-style integers, linear in EXR.
    auto encodeColour = [&](float v) { return exr ? v : linearToSrgb(std::clamp(v, 0.0f, 1.0f)); };
    std::vector<Image> images;
    Image baseColor(w, h, hasAlpha ? 4 : 3);
    for (size_t i = 0; i < count; ++i) {
        for (int c = 0; c < 3; ++c)
            baseColor.pixels[i * size_t(baseColor.channels) + c] =
                encodeColour(maps.baseColor.pixels[i * 4 + size_t(c)]);
        if (hasAlpha)
            baseColor.pixels[i * 4 + 3] = maps.baseColor.pixels[i * 4 + 3];
    }
    images.push_back(std::move(baseColor));

    Image normal(w, h, 3);
    for (size_t i = 0; i < count; ++i) {
        const float* n = &maps.normal.pixels[i * size_t(maps.normal.channels)];
        const float y = nc == NormalConvention::DirectX ? -n[1] : n[1];
        normal.pixels[i * 3 + 0] = std::clamp(n[0] * 0.5f + 0.5f, 0.0f, 1.0f);
        normal.pixels[i * 3 + 1] = std::clamp(y * 0.5f + 0.5f, 0.0f, 1.0f);
        normal.pixels[i * 3 + 2] = std::clamp(n[2] * 0.5f + 0.5f, 0.0f, 1.0f);
    }
    images.push_back(std::move(normal));

    ChannelMaps channels;
    channels.occlusion = channel(maps.orm, 0);
    channels.roughness = channel(maps.orm, 1);
    channels.metallic = channel(maps.orm, 2);
    // HDRP's detail mask: 1 (detail maps apply everywhere, HDRP's white default; a material
    // without detail maps ignores it).
    const PackLayout layout = o.target == TextureSetTarget::UnityHdrp ? PackLayout::HdrpMaskMap
                              : o.target == TextureSetTarget::Unreal
                                  ? PackLayout::UnrealOrm
                                  : PackLayout::GltfMetallicRoughness;
    Image packed;
    std::string why;
    if (!packChannels(layout, channels, packed, &why))
        return fail("cannot pack occlusion, roughness and metallic: " + why);
    images.push_back(std::move(packed));

    if (hasEmission) {
        Image emission(w, h, 3);
        for (size_t i = 0; i < count; ++i)
            for (int c = 0; c < 3; ++c)
                emission.pixels[i * 3 + size_t(c)] = encodeColour(
                    maps.emission.pixels[i * size_t(maps.emission.channels) + size_t(c)] /
                    emissionScale);
        images.push_back(std::move(emission));
    }

    for (const TextureSetFile& lobe : lobes) {
        Image packedLobe;
        if (!packLobeMap(lobe, maps, exr, packedLobe, &why))
            return fail(why);
        images.push_back(std::move(packedLobe));
        plan.push_back(lobe);
    }

    const std::string ext = "." + std::string(textureFileTypeId(o.fileType));
    Json files = Json::array();
    for (size_t i = 0; i < plan.size(); ++i) {
        ExportFile file;
        file.name = plan[i].name;
        if (!encodeImage(images[i], ext, pixelFormatOf(o), file.bytes, &why))
            return fail(plan[i].name + ": " + why);
        out.files.push_back(std::move(file));
        Json entry;
        entry["file"] = plan[i].name;
        entry["role"] = plan[i].role;
        entry["colorSpace"] = plan[i].colorSpace;
        Json ch = Json::object();
        for (int c = 0; c < 4; ++c)
            if (!plan[i].channels[c].empty())
                ch[std::string(1, "RGBA"[c])] = plan[i].channels[c];
        entry["channels"] = std::move(ch);
        if (plan[i].role == "normal")
            entry["convention"] = std::string(normalConventionId(nc));
        if (plan[i].role == "emissive")
            entry["scale"] = emissionScale;
        if (plan[i].role == "anisotropy" &&
            plan[i].channels[0].rfind("anisotropyDirection", 0) == 0)
            entry["rotation"] = 0; // the direction already holds the material's rotation
        files.push_back(std::move(entry));
    }
    Json manifest;
    manifest["generator"] = "Velvet";
    manifest["manifestVersion"] = 1;
    manifest["material"] = std::string(materialName);
    manifest["target"] = std::string(textureSetTargetId(o.target));
    manifest["width"] = w;
    manifest["height"] = h;
    manifest["fileType"] = std::string(textureFileTypeId(o.fileType));
    manifest["bitsPerChannel"] = bitsOf(o);
    manifest["normalConvention"] = std::string(normalConventionId(nc));
    manifest["alphaMode"] = hasAlpha ? "mask" : "opaque";
    if (hasAlpha)
        manifest["alphaCutoff"] = 0.5;
    manifest["files"] = std::move(files);
    out.files.push_back({std::string(base) + "_texture_set.json", manifest.dump(2) + "\n"});
    return true;
}

} // namespace velvet
