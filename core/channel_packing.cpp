#include "core/channel_packing.h"

#include <array>

namespace velvet {
namespace {

enum class Map { Occlusion, Roughness, Metallic, Specular, DetailMask, None };

/// What each channel of a layout holds, and whether it is stored inverted (1 - x).
struct Channel {
    Map map = Map::None;
    bool inverted = false;
};
struct LayoutInfo {
    std::string_view id;
    std::string_view label;
    int channels;
    std::array<Channel, 4> channel;
};

const LayoutInfo& info(PackLayout layout) {
    static const LayoutInfo kLayouts[] = {
        {"gltf-mr",
         "glTF metallic-roughness (R occlusion, G roughness, B metallic)",
         3,
         {{{Map::Occlusion}, {Map::Roughness}, {Map::Metallic}, {}}}},
        {"unreal-orm",
         "Unreal ORM (R occlusion, G roughness, B metallic)",
         3,
         {{{Map::Occlusion}, {Map::Roughness}, {Map::Metallic}, {}}}},
        {"hdrp-mask",
         "Unity HDRP mask map (R metallic, G occlusion, B detail mask, A smoothness)",
         4,
         {{{Map::Metallic}, {Map::Occlusion}, {Map::DetailMask}, {Map::Roughness, true}}}},
        {"srm",
         "Specular / roughness / metallic atlas (R specular, G roughness, B metallic)",
         3,
         {{{Map::Specular}, {Map::Roughness}, {Map::Metallic}, {}}}},
    };
    return kLayouts[static_cast<int>(layout)];
}

const char* mapName(Map map) {
    switch (map) {
    case Map::Occlusion:
        return "occlusion";
    case Map::Roughness:
        return "roughness";
    case Map::Metallic:
        return "metallic";
    case Map::Specular:
        return "specular";
    case Map::DetailMask:
        return "detail mask";
    case Map::None:
        break;
    }
    return "none";
}

const Image& mapOf(const ChannelMaps& maps, Map map) {
    static const Image kNone;
    switch (map) {
    case Map::Occlusion:
        return maps.occlusion;
    case Map::Roughness:
        return maps.roughness;
    case Map::Metallic:
        return maps.metallic;
    case Map::Specular:
        return maps.specular;
    case Map::DetailMask:
        return maps.detailMask;
    case Map::None:
        break;
    }
    return kNone;
}
Image& mapOf(ChannelMaps& maps, Map map) {
    return const_cast<Image&>(mapOf(static_cast<const ChannelMaps&>(maps), map));
}

float defaultOf(const ChannelDefaults& d, Map map) {
    switch (map) {
    case Map::Occlusion:
        return d.occlusion;
    case Map::Roughness:
        return d.roughness;
    case Map::Metallic:
        return d.metallic;
    case Map::Specular:
        return d.specular;
    case Map::DetailMask:
        return d.detailMask;
    case Map::None:
        break;
    }
    return 0.0f;
}

std::string sizeText(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

bool setError(std::string* error, const std::string& what) {
    if (error)
        *error = what;
    return false;
}

} // namespace

std::string_view packLayoutId(PackLayout layout) {
    return info(layout).id;
}
std::string_view packLayoutLabel(PackLayout layout) {
    return info(layout).label;
}

std::optional<PackLayout> packLayoutFromId(std::string_view id) {
    for (int i = 0; i < static_cast<int>(PackLayout::Count); ++i)
        if (info(static_cast<PackLayout>(i)).id == id)
            return static_cast<PackLayout>(i);
    return std::nullopt;
}

bool packChannels(PackLayout layout, const ChannelMaps& maps, Image& out, std::string* error,
                  const ChannelDefaults& defaults) {
    const LayoutInfo& li = info(layout);
    const Image* first = nullptr;
    Map firstMap = Map::None;
    for (const Channel& ch : li.channel) {
        if (ch.map == Map::None)
            continue;
        const Image& img = mapOf(maps, ch.map);
        if (img.empty())
            continue;
        if (img.channels < 1 || img.channels > 4 ||
            img.pixels.size() != size_t(img.width) * img.height * img.channels)
            return setError(error, std::string("the ") + mapName(ch.map) +
                                       " map is inconsistent (pixels do not match its size)");
        if (!first) {
            first = &img;
            firstMap = ch.map;
        } else if (img.width != first->width || img.height != first->height) {
            return setError(error, std::string("cannot pack maps of different sizes: ") +
                                       mapName(firstMap) + " is " + sizeText(*first) + ", " +
                                       mapName(ch.map) + " is " + sizeText(img));
        }
    }
    if (!first)
        return setError(error, std::string("nothing to pack: ") + std::string(li.label) +
                                   " needs at least one of its maps");

    Image packed(first->width, first->height, li.channels);
    const size_t count = size_t(packed.width) * packed.height;
    for (int c = 0; c < li.channels; ++c) {
        const Channel& ch = li.channel[size_t(c)];
        const Image& src = mapOf(maps, ch.map);
        const float fill = defaultOf(defaults, ch.map);
        for (size_t i = 0; i < count; ++i) {
            const float v = src.empty() ? fill : src.pixels[i * size_t(src.channels)];
            packed.pixels[i * size_t(li.channels) + size_t(c)] = ch.inverted ? 1.0f - v : v;
        }
    }
    out = std::move(packed);
    return true;
}

bool unpackChannels(PackLayout layout, const Image& packed, ChannelMaps& out, std::string* error) {
    const LayoutInfo& li = info(layout);
    if (packed.empty())
        return setError(error, "nothing to unpack: the image is empty");
    if (packed.pixels.size() != size_t(packed.width) * packed.height * packed.channels)
        return setError(error, "the packed image is inconsistent (pixels do not match its size)");
    if (packed.channels < li.channels)
        return setError(error, std::string(li.label) + " needs " + std::to_string(li.channels) +
                                   " channels, the image has " + std::to_string(packed.channels));
    ChannelMaps maps;
    const size_t count = size_t(packed.width) * packed.height;
    for (int c = 0; c < li.channels; ++c) {
        const Channel& ch = li.channel[size_t(c)];
        if (ch.map == Map::None)
            continue;
        Image map(packed.width, packed.height, 1);
        for (size_t i = 0; i < count; ++i) {
            const float v = packed.pixels[i * size_t(packed.channels) + size_t(c)];
            map.pixels[i] = ch.inverted ? 1.0f - v : v;
        }
        mapOf(maps, ch.map) = std::move(map);
    }
    out = std::move(maps);
    return true;
}

} // namespace velvet
