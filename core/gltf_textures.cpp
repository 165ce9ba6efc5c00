#include "core/gltf_textures.h"

#include "core/channel_packing.h"
#include "core/color_management.h"
#include "core/image_ops.h"
#include "core/texture_cache.h"

#include <algorithm>
#include <map>
#include <memory>
#include <tuple>

namespace velvet {
namespace {

bool isSet(const Material& m, TextureSlot s) {
    return !m.texture(s).empty();
}

/// A slot's pixels as the renderer sees them: colour slots scene-linear, data slots as stored.
bool loadSlot(const Material& m, TextureSlot slot, TextureCache& cache,
              std::shared_ptr<const Image>& out, std::string* error) {
    const TextureRef& ref = m.texture(slot);
    Texture t = cache.get(ref, slot);
    if (!t.image) {
        std::string why = t.problems.empty() ? "cannot be read" : t.problems.front().toString();
        *error = "textures." + std::string(textureSlotMeta(slot).id) + ": " + why;
        return false;
    }
    if (ref.useRegion) {
        const AtlasRegion& r = ref.region;
        if (r.width <= 0 || r.height <= 0 || r.x < 0 || r.y < 0 || r.x + r.width > t.image->width ||
            r.y + r.height > t.image->height) {
            *error = "textures." + std::string(textureSlotMeta(slot).id) + ": region " +
                     std::to_string(r.x) + "," + std::to_string(r.y) + " " +
                     std::to_string(r.width) + "x" + std::to_string(r.height) + " lies outside " +
                     ref.file + " (" + std::to_string(t.image->width) + "x" +
                     std::to_string(t.image->height) + ")";
            return false;
        }
    }
    out = t.image;
    return true;
}

/// The slot's region cut out of its image (the whole image without a region), as RGBA read
/// the way the shader reads it (Image::rgba: grey -> RRR, missing alpha -> 1).
Image cutOut(const Image& image, const TextureRef& ref) {
    const AtlasRegion r = ref.useRegion ? ref.region : AtlasRegion{0, 0, image.width, image.height};
    Image out(r.width, r.height, 4);
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            const glm::vec4 p = image.rgba(r.x + x, r.y + y);
            std::copy(&p.x, &p.x + 4, out.at(x, y));
        }
    return out;
}

/// One channel of @p rgba as a one-channel image of @p w x @p h (resampled when the sizes
/// differ; @p resampled is set then).
Image channelOf(const Image& rgba, int channel, int w, int h, bool& resampled) {
    Image src(rgba.width, rgba.height, 1);
    for (size_t i = 0; i < src.pixels.size(); ++i)
        src.pixels[i] = rgba.pixels[i * 4 + size_t(channel)];
    if (src.width == w && src.height == h)
        return src;
    resampled = true;
    std::string ignored;
    return resize(src, w, h, &ignored);
}

void multiplyInto(Image& target, const Image& factor) {
    if (target.empty()) {
        target = factor;
        return;
    }
    for (size_t i = 0; i < target.pixels.size(); ++i)
        target.pixels[i] *= factor.pixels[i];
}

/// A colour image (scene-linear) encoded with the sRGB transfer function (IEC 61966-2-1),
/// alpha kept linear as glTF reads it. Counts values that 8 bits cannot hold (above 1).
Image encodeSrgb(const Image& linear, long& clamped) {
    Image out = linear;
    const int colourChannels = linear.channels >= 3 ? 3 : 1;
    for (size_t i = 0; i < out.pixels.size(); ++i) {
        float& v = out.pixels[i];
        if (int(i % size_t(out.channels)) >= colourChannels)
            continue; // alpha
        if (v > 1.0f)
            ++clamped;
        v = linearToSrgb(std::clamp(v, 0.0f, 1.0f));
    }
    return out;
}

/// The slot's own UV transform as KHR_texture_transform: the same scale and offset, and
/// rotation = -radians(degrees), glTF's rotation matrix being the transpose of Velvet's
/// (texture_ref.h).
GltfTextureUse uvUse(int image, const TextureRef& ref) {
    GltfTextureUse u;
    u.image = image;
    if (!ref.uv.isIdentity()) {
        u.transformed = true;
        u.scale = ref.uv.scale;
        u.offset = ref.uv.offset;
        u.rotation = -ref.uv.rotation * 3.14159265358979323846f / 180.0f;
    }
    return u;
}

GltfTextureUse useOf(int image, const TextureRef& ref, const Image& pixels) {
    GltfTextureUse u = uvUse(image, ref);
    if (ref.useRegion && ref.uv.isIdentity()) {
        // KHR_texture_transform: uv' = offset + scale * uv (no rotation). glTF's UV origin is
        // the image's top-left corner, as Velvet's regions count rows from the top.
        u.transformed = true;
        u.offset = {float(ref.region.x) / float(pixels.width),
                    float(ref.region.y) / float(pixels.height)};
        u.scale = {float(ref.region.width) / float(pixels.width),
                   float(ref.region.height) / float(pixels.height)};
    }
    return u;
}

} // namespace

bool planGltfTextures(const Material& m, TextureCache& cache, GltfTexturePlan& plan,
                      std::string* error, bool cutOutRegions) {
    plan = {};
    const bool srm = isSet(m, TextureSlot::SpecRoughMetal);
    // Occlusion and metallic-roughness with different UV transforms stay two images (glTF
    // reads them through separate textureInfos); packing needs one mapping for both.
    const bool packOrm =
        srm ||
        (isSet(m, TextureSlot::Occlusion) && isSet(m, TextureSlot::MetallicRoughness) &&
         m.texture(TextureSlot::Occlusion).uv == m.texture(TextureSlot::MetallicRoughness).uv);

    // Slots written as they are, one image per (file, colour space, colour or data[, region]).
    std::map<std::tuple<std::string, std::string, bool, int, int, int, int>, int> imageOf;
    long clamped = 0;
    for (int i = 0; i < kTextureSlotCount; ++i) {
        const auto slot = TextureSlot(i);
        const TextureRef& ref = m.texture(slot);
        if (ref.empty() || slot == TextureSlot::SpecRoughMetal)
            continue;
        if (packOrm && (slot == TextureSlot::Occlusion || slot == TextureSlot::MetallicRoughness))
            continue;
        if (srm && slot == TextureSlot::Specular)
            continue; // multiplied into the orm image's A
        std::shared_ptr<const Image> image;
        if (!loadSlot(m, slot, cache, image, error))
            return false;
        const bool colour = textureSlotMeta(slot).isColor;
        const bool cut = ref.useRegion && (cutOutRegions || !ref.uv.isIdentity());
        const AtlasRegion r = cut ? ref.region : AtlasRegion{};
        const auto key =
            std::make_tuple(ref.file, ref.colorSpace, colour, r.x, r.y, r.width, r.height);
        auto found = imageOf.find(key);
        if (found == imageOf.end()) {
            GltfImage out;
            out.label = std::string(textureSlotMeta(slot).id);
            const Image source = cut ? cutOut(*image, ref) : *image;
            out.pixels = colour ? encodeSrgb(source, clamped) : source;
            plan.images.push_back(std::move(out));
            found = imageOf.emplace(key, int(plan.images.size()) - 1).first;
        }
        plan.uses[size_t(i)] = cut ? uvUse(found->second, ref) : useOf(found->second, ref, *image);
        if (slot == TextureSlot::BaseColor && (image->channels == 2 || image->channels == 4)) {
            const Image region = cutOut(*image, ref);
            for (size_t p = 3; p < region.pixels.size(); p += 4)
                if (region.pixels[p] < 1.0f)
                    plan.alphaCutout = true;
        }
    }
    if (clamped > 0)
        plan.warnings.push_back(std::to_string(clamped) +
                                " colour texture values above 1 clamped to 1: glTF colour "
                                "textures are 8-bit sRGB (scale the factor instead)");
    if (!packOrm)
        return true;

    // The packed image: every map cut out of its region, at the largest size among them.
    struct Source {
        TextureSlot slot;
        Image rgba;
    };
    std::vector<Source> sources;
    for (TextureSlot s : {TextureSlot::Occlusion, TextureSlot::MetallicRoughness,
                          TextureSlot::SpecRoughMetal, TextureSlot::Specular}) {
        if (!isSet(m, s) || (s == TextureSlot::Specular && !srm))
            continue;
        std::shared_ptr<const Image> image;
        if (!loadSlot(m, s, cache, image, error))
            return false;
        sources.push_back({s, cutOut(*image, m.texture(s))});
    }
    int w = 0, h = 0;
    for (const Source& s : sources) {
        w = std::max(w, s.rgba.width);
        h = std::max(h, s.rgba.height);
    }
    bool resampled = false;
    ChannelMaps maps;
    Image specular;
    for (const Source& s : sources) {
        switch (s.slot) {
        case TextureSlot::Occlusion:
            maps.occlusion = channelOf(s.rgba, 0, w, h, resampled);
            break;
        case TextureSlot::MetallicRoughness:
            multiplyInto(maps.roughness, channelOf(s.rgba, 1, w, h, resampled));
            multiplyInto(maps.metallic, channelOf(s.rgba, 2, w, h, resampled));
            break;
        case TextureSlot::SpecRoughMetal:
            multiplyInto(specular, channelOf(s.rgba, 0, w, h, resampled));
            multiplyInto(maps.roughness, channelOf(s.rgba, 1, w, h, resampled));
            multiplyInto(maps.metallic, channelOf(s.rgba, 2, w, h, resampled));
            break;
        default: // Specular: its A
            multiplyInto(specular, channelOf(s.rgba, 3, w, h, resampled));
            break;
        }
    }
    // Absent maps are 1: the factor alone then applies, as the renderer reads no texture.
    ChannelDefaults ones;
    ones.occlusion = ones.roughness = ones.metallic = 1.0f;
    Image packed;
    std::string why;
    if (!packChannels(PackLayout::GltfMetallicRoughness, maps, packed, &why, ones)) {
        *error = "textures: cannot pack occlusion, roughness and metallic: " + why;
        return false;
    }
    if (!specular.empty()) {
        Image rgba(packed.width, packed.height, 4);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                std::copy(packed.at(x, y), packed.at(x, y) + 3, rgba.at(x, y));
                rgba.at(x, y)[3] = *specular.at(x, y);
            }
        packed = std::move(rgba);
    }
    if (resampled)
        plan.warnings.push_back("occlusion, metallic-roughness and specular maps of different "
                                "sizes resampled to " +
                                std::to_string(w) + "x" + std::to_string(h) +
                                " to pack them into one image");
    plan.images.push_back({"orm", std::move(packed)});
    // The packed image is read through one UV transform: the seed atlas's (or the
    // metallic-roughness slot's); a packed slot with another one is said.
    const TextureSlot mapping = srm ? TextureSlot::SpecRoughMetal : TextureSlot::MetallicRoughness;
    for (const Source& s : sources)
        if (!(m.texture(s.slot).uv == m.texture(mapping).uv))
            plan.warnings.push_back("textures." + std::string(textureSlotMeta(s.slot).id) +
                                    ": its UV transform differs from textures." +
                                    std::string(textureSlotMeta(mapping).id) +
                                    "'s, with which it is packed into one image; the packed "
                                    "image uses the latter's");
    const GltfTextureUse packedUse = uvUse(int(plan.images.size()) - 1, m.texture(mapping));
    plan.uses[size_t(TextureSlot::MetallicRoughness)] = packedUse;
    if (isSet(m, TextureSlot::Occlusion))
        plan.uses[size_t(TextureSlot::Occlusion)] = packedUse;
    if (!specular.empty())
        plan.uses[size_t(TextureSlot::Specular)] = packedUse;
    return true;
}

} // namespace velvet
