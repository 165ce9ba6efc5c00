// Engine texture sets' lobe maps. References: glTF 2.0's KHR_materials_clearcoat (clearcoatTexture
// R, clearcoatRoughnessTexture G), KHR_materials_sheen (sheenColorTexture RGB sRGB,
// sheenRoughnessTexture A), KHR_materials_specular (specularTexture A, specularColorTexture RGB
// sRGB) and KHR_materials_anisotropy (anisotropyTexture RG direction, B strength); Unreal Engine's
// material inputs (Clear Coat and Clear Coat Roughness of the Clear Coat shading model, Fuzz
// Color and Cloth of the Cloth shading model, Specular with F0 = 0.08 x Specular, Anisotropy);
// HDRP Lit's Coat Mask and Anisotropy Map; Godot's BaseMaterial3D (clearcoat_texture: R
// clearcoat, G clearcoat roughness; anisotropy_flowmap: RG direction, A strength — its
// generated shader reads .rga).
#include "core/texture_set_lobes.h"

#include "core/color_management.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace velvet {
namespace {

enum class Lobe { Coat, Sheen, Specular, Anisotropy };

struct LobeFile {
    TextureSetTarget target;
    Lobe lobe;
    std::string_view suffix;
    std::string_view role;
    std::string_view colorSpace; ///< "srgb": the colour channels are sRGB-encoded (not in EXR)
    std::array<std::string_view, 4> channels;
};

using T = TextureSetTarget;
constexpr std::string_view kUnrealSpecular = "specular (F0 / 0.08)";

constexpr LobeFile kFiles[] = {
    {T::Gltf, Lobe::Coat, "_clearcoat", "clearcoat", "linear", {"clearcoat", "clearcoatRoughness"}},
    {T::Gltf,
     Lobe::Sheen,
     "_sheen",
     "sheen",
     "srgb",
     {"sheenColor.r", "sheenColor.g", "sheenColor.b", "sheenRoughness"}},
    {T::Gltf,
     Lobe::Specular,
     "_specular",
     "specular",
     "srgb",
     {"specularColor.r", "specularColor.g", "specularColor.b", "specular"}},
    {T::Gltf,
     Lobe::Anisotropy,
     "_anisotropy",
     "anisotropy",
     "linear",
     {"anisotropyDirection.x", "anisotropyDirection.y", "anisotropyStrength"}},
    {T::Unreal, Lobe::Coat, "_CC", "clearcoat", "linear", {"clearCoat", "clearCoatRoughness"}},
    {T::Unreal,
     Lobe::Sheen,
     "_Fuzz",
     "sheen",
     "srgb",
     {"fuzzColor.r", "fuzzColor.g", "fuzzColor.b", "cloth"}},
    {T::Unreal, Lobe::Specular, "_S", "specular", "linear", {kUnrealSpecular}},
    {T::Unreal, Lobe::Anisotropy, "_Aniso", "anisotropy", "linear", {"anisotropyStrength"}},
    {T::UnityHdrp, Lobe::Coat, "_CoatMask", "clearcoat", "linear", {"coatMask"}},
    {T::UnityHdrp, Lobe::Anisotropy, "_Anisotropy", "anisotropy", "linear", {"anisotropyStrength"}},
    {T::Godot,
     Lobe::Coat,
     "_clearcoat",
     "clearcoat",
     "linear",
     {"clearcoat", "clearcoatRoughness"}},
    {T::Godot,
     Lobe::Anisotropy,
     "_flowmap",
     "anisotropy",
     "linear",
     {"anisotropyDirection.x", "anisotropyDirection.y", "", "anisotropyStrength"}},
};

std::string_view prefixOf(TextureSetTarget t) {
    return t == T::Unreal ? "T_" : "";
}

/// "….r" / "….g" / "….b" -> 0, 1, 2.
int rgbIndex(const std::string& name) {
    return name.back() == 'r' ? 0 : name.back() == 'g' ? 1 : 2;
}

bool carries(const LobePresence& p, Lobe lobe) {
    switch (lobe) {
    case Lobe::Coat:
        return p.coat;
    case Lobe::Sheen:
        return p.sheen;
    case Lobe::Specular:
        return p.specular;
    case Lobe::Anisotropy:
        return p.anisotropy;
    }
    return false;
}

bool any(const Image& image, auto&& test) {
    if (image.empty())
        return false;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (test(image.at(x, y)))
                return true;
    return false;
}

} // namespace

LobePresence lobePresence(const MaterialMaps& maps) {
    LobePresence p;
    p.coat = any(maps.coat, [](const float* c) { return c[0] > 0.0f; });
    p.sheen = any(maps.sheen, [](const float* s) { return std::max({s[0], s[1], s[2]}) > 0.0f; });
    p.specular = any(maps.specular, [](const float* s) {
        return std::abs(s[3] - 1.0f) > 1e-6f || std::abs(s[0] - 1.0f) > 1e-6f ||
               std::abs(s[1] - 1.0f) > 1e-6f || std::abs(s[2] - 1.0f) > 1e-6f;
    });
    p.anisotropy = any(maps.anisotropy, [](const float* a) { return a[2] > 0.0f; });
    return p;
}

std::vector<TextureSetFile> planLobeMaps(const TextureSetOptions& options, std::string_view base,
                                         const LobePresence& present) {
    std::string ext(1, '.');
    ext += textureFileTypeId(options.fileType);
    const bool exr = options.fileType == TextureFileType::Exr;
    std::vector<TextureSetFile> files;
    for (const LobeFile& f : kFiles) {
        if (f.target != options.target || !carries(present, f.lobe))
            continue;
        TextureSetFile file;
        file.name.assign(prefixOf(f.target));
        file.name.append(base).append(f.suffix).append(ext);
        file.role = f.role;
        file.colorSpace = exr ? "linear" : std::string(f.colorSpace);
        for (int c = 0; c < 4; ++c)
            file.channels[c] = f.channels[size_t(c)];
        files.push_back(std::move(file));
    }
    return files;
}

bool packLobeMap(const TextureSetFile& file, const MaterialMaps& maps, bool exr, Image& out,
                 std::string* error) {
    int count = 0;
    for (int c = 0; c < 4; ++c)
        if (!file.channels[c].empty())
            count = c + 1;
    const Image* size = !maps.coat.empty() ? &maps.coat : &maps.baseColor;
    out = Image(size->width, size->height, std::max(count, 1));
    const bool srgb = !exr && file.colorSpace == "srgb";
    const auto colour = [&](float v) { return srgb ? linearToSrgb(std::clamp(v, 0.0f, 1.0f)) : v; };
    for (int c = 0; c < count; ++c) {
        const std::string& name = file.channels[c];
        for (int y = 0; y < out.height; ++y)
            for (int x = 0; x < out.width; ++x) {
                const auto at = [&](const Image& m, int channel) {
                    return m.empty() ? 0.0f : m.at(x, y)[channel];
                };
                const float sheenMax =
                    std::max({at(maps.sheen, 0), at(maps.sheen, 1), at(maps.sheen, 2)});
                float v = 0.0f;
                if (name.empty())
                    v = 0.0f;
                else if (name == "clearcoat" || name == "clearCoat" || name == "coatMask")
                    v = at(maps.coat, 0);
                else if (name == "clearcoatRoughness" || name == "clearCoatRoughness")
                    v = at(maps.coat, 1);
                else if (name.rfind("sheenColor.", 0) == 0)
                    v = colour(at(maps.sheen, rgbIndex(name)));
                else if (name == "sheenRoughness")
                    v = at(maps.sheen, 3);
                else if (name.rfind("fuzzColor.", 0) == 0) // Unreal: colour and amount apart
                    v = colour(sheenMax > 0.0f ? at(maps.sheen, rgbIndex(name)) / sheenMax : 1.0f);
                else if (name == "cloth")
                    v = sheenMax;
                else if (name.rfind("specularColor.", 0) == 0)
                    v = colour(at(maps.specular, rgbIndex(name)));
                else if (name == "specular")
                    v = at(maps.specular, 3);
                else if (name == kUnrealSpecular) // F0 = 0.04 x weight x colour at IOR 1.5
                    v = std::clamp(
                        0.5f * at(maps.specular, 3) *
                            (at(maps.specular, 0) + at(maps.specular, 1) + at(maps.specular, 2)) /
                            3.0f,
                        0.0f, 1.0f);
                else if (name == "anisotropyDirection.x")
                    v = std::clamp(at(maps.anisotropy, 0) * 0.5f + 0.5f, 0.0f, 1.0f);
                else if (name == "anisotropyDirection.y")
                    v = std::clamp(at(maps.anisotropy, 1) * 0.5f + 0.5f, 0.0f, 1.0f);
                else if (name == "anisotropyStrength")
                    v = at(maps.anisotropy, 2);
                else {
                    if (error)
                        *error = file.name + ": no lobe value \"" + name + "\"";
                    return false;
                }
                out.at(x, y)[c] = v;
            }
    }
    return true;
}

std::vector<std::string> lobeGaps(const Material& m, TextureSetTarget target) {
    std::vector<std::string> w;
    const std::string engine(textureSetTargetId(target));
    auto add = [&](ParamId id, const std::string& what) {
        w.push_back(std::string(paramMeta(id).id) + ": " + what + " (the " + engine +
                    " texture set); set it in the engine's material");
    };
    const bool coat = m.scalar(ParamId::ClearcoatWeight) > 0.0f;
    const bool sheen = m.scalar(ParamId::SheenWeight) > 0.0f;
    const bool specular = m.scalar(ParamId::SpecularWeight) != 1.0f ||
                          m.color(ParamId::SpecularColor) != glm::vec3(1.0f) ||
                          !m.texture(TextureSlot::Specular).empty() ||
                          !m.texture(TextureSlot::SpecularColor).empty();
    const bool anisotropy = m.scalar(ParamId::AnisotropyStrength) > 0.0f;
    const bool turned = m.scalar(ParamId::AnisotropyRotation) != 0.0f ||
                        !m.texture(TextureSlot::Anisotropy).empty();
    switch (target) {
    case T::Gltf:
        break; // KHR_materials_* read every lobe map
    case T::Unreal: {
        const glm::vec3 c = m.color(ParamId::SpecularColor);
        if (specular &&
            (c.r != c.g || c.g != c.b || !m.texture(TextureSlot::SpecularColor).empty()))
            add(ParamId::SpecularColor, "Unreal's Specular is one value, not a colour: the "
                                        "colour's mean is written");
        if (anisotropy && turned)
            add(ParamId::AnisotropyRotation, "Unreal takes the anisotropy direction from its "
                                             "Tangent input, which the set does not write");
        break;
    }
    case T::UnityHdrp:
        if (coat && (m.scalar(ParamId::ClearcoatRoughness) > 0.0f ||
                     !m.texture(TextureSlot::ClearcoatRoughness).empty()))
            add(ParamId::ClearcoatRoughness, "HDRP Lit's coat has a mask only, no roughness input");
        if (sheen)
            add(ParamId::SheenWeight, "HDRP Lit has no sheen input (HDRP's Fabric shader has)");
        if (specular)
            add(ParamId::SpecularWeight, "HDRP Lit's metallic workflow has no specular input "
                                         "(its Specular Color type replaces metallic)");
        if (anisotropy && turned)
            add(ParamId::AnisotropyRotation, "HDRP Lit takes the anisotropy direction from its "
                                             "Tangent Map, which the set does not write");
        break;
    case T::Godot:
        if (sheen)
            add(ParamId::SheenWeight,
                "Godot's StandardMaterial3D has no sheen input (its rim is another effect)");
        if (specular)
            add(ParamId::SpecularWeight,
                "Godot's specular is one value per material (metallic_specular), no map");
        break;
    case T::Count:
        break;
    }
    return w;
}

} // namespace velvet
