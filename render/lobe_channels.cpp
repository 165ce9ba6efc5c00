#include "render/lobe_channels.h"

#include <algorithm>

namespace velvet::render {
namespace {

struct ValueInfo {
    int channels;
    std::string_view label;
    std::string_view macro;
};

constexpr std::array<ValueInfo, kLobeValueCount> kValues{{
    {2, "anisotropy", "LOBE_ANISOTROPY"},
    {3, "sheen colour", "LOBE_SHEEN_COLOR"},
    {1, "sheen roughness", "LOBE_SHEEN_ROUGHNESS"},
    {1, "clearcoat", "LOBE_CLEARCOAT"},
    {1, "clearcoat roughness", "LOBE_CLEARCOAT_ROUGHNESS"},
    {2, "clearcoat normal", "LOBE_CLEARCOAT_NORMAL"},
    {1, "specular", "LOBE_SPECULAR_WEIGHT"},
    {3, "specular colour", "LOBE_SPECULAR_COLOR"},
    {1, "IOR", "LOBE_IOR"},
}};
// The first eight values' entries fill terms2.w; the IOR's has its own slot (iorEntry()).
constexpr int kPackedValues = 8;
static_assert(kLobeValueCount == kPackedValues + 1, "the map is 4 bits a value in one int, + IOR");

bool has(std::uint32_t slots, TextureSlot s) {
    return (slots >> int(s)) & 1u;
}

bool connected(const std::vector<std::string>& fields,
               std::initializer_list<std::string_view> any) {
    for (const std::string& f : fields)
        if (std::find(any.begin(), any.end(), f) != any.end())
            return true;
    return false;
}

} // namespace

int lobeValueChannels(LobeValue value) {
    return kValues[size_t(value)].channels;
}

std::string_view lobeValueLabel(LobeValue value) {
    return kValues[size_t(value)].label;
}

std::string_view lobeValueMacro(LobeValue value) {
    return kValues[size_t(value)].macro;
}

bool perturbsNormal(std::uint32_t presentSlots, const std::vector<std::string>& graphFields) {
    return has(presentSlots, TextureSlot::Normal) || connected(graphFields, {"normal"});
}

LobeValueSet varyingLobeValues(const Material& m, std::uint32_t presentSlots,
                               const std::vector<std::string>& graphFields) {
    LobeValueSet set = 0;
    const auto vary = [&](LobeValue v, bool when) {
        if (when)
            set |= lobeBit(v);
    };
    // KHR_materials_anisotropy: the direction follows the tangent frame, so it varies over any
    // curved surface as soon as there is a strength (or a map or graph that may give one).
    vary(LobeValue::Anisotropy,
         m.scalar(ParamId::AnisotropyStrength) > 0.0f ||
             has(presentSlots, TextureSlot::Anisotropy) ||
             connected(graphFields,
                       {"anisotropyStrength", "anisotropyRotation", "anisotropyDirection"}));
    vary(LobeValue::SheenColor, has(presentSlots, TextureSlot::SheenColor) ||
                                    connected(graphFields, {"sheenWeight", "sheenColor"}));
    vary(LobeValue::SheenRoughness, has(presentSlots, TextureSlot::SheenRoughness) ||
                                        connected(graphFields, {"sheenRoughness"}));
    vary(LobeValue::Clearcoat,
         has(presentSlots, TextureSlot::Clearcoat) || connected(graphFields, {"clearcoatWeight"}));
    vary(LobeValue::ClearcoatRoughness, has(presentSlots, TextureSlot::ClearcoatRoughness) ||
                                            connected(graphFields, {"clearcoatRoughness"}));
    // The coat has its own normal (KHR_materials_clearcoat): its map, or the geometric normal
    // when only the base is normal-mapped. Either differs from the base normal per pixel.
    const bool coat = m.scalar(ParamId::ClearcoatWeight) > 0.0f ||
                      has(presentSlots, TextureSlot::Clearcoat) ||
                      connected(graphFields, {"clearcoatWeight"});
    const bool baseBumped =
        has(presentSlots, TextureSlot::Normal) || connected(graphFields, {"normal"});
    const bool coatBumped = has(presentSlots, TextureSlot::ClearcoatNormal) ||
                            connected(graphFields, {"clearcoatNormal"});
    vary(LobeValue::ClearcoatNormal, coat && (baseBumped || coatBumped));
    vary(LobeValue::SpecularWeight, has(presentSlots, TextureSlot::Specular) ||
                                        has(presentSlots, TextureSlot::SpecRoughMetal) ||
                                        connected(graphFields, {"specularWeight"}));
    vary(LobeValue::SpecularColor, has(presentSlots, TextureSlot::SpecularColor) ||
                                       connected(graphFields, {"specularColor"}));
    // KHR_materials_ior has no texture; a graph may drive it.
    vary(LobeValue::Ior, connected(graphFields, {"ior"}));
    return set;
}

std::int32_t LobeChannelMap::packed() const {
    std::uint32_t bits = 0;
    for (int i = 0; i < kPackedValues; ++i)
        bits |= std::uint32_t(firstChannel[size_t(i)] & 15) << (4 * i);
    return std::int32_t(bits);
}

LobeChannelMap assignLobeChannels(LobeValueSet varying, int channels) {
    LobeChannelMap map;
    map.firstChannel.fill(kLobePerMaterial);
    for (int i = 0; i < kLobeValueCount; ++i) {
        const LobeValue v = LobeValue(i);
        if (!(varying & lobeBit(v)))
            continue;
        const int need = lobeValueChannels(v);
        if (map.channelsUsed + need > channels) {
            map.overflow |= lobeBit(v);
            continue;
        }
        map.firstChannel[size_t(i)] = map.channelsUsed;
        map.channelsUsed += need;
    }
    return map;
}

std::string lobeValueNames(LobeValueSet set) {
    std::string s;
    for (int i = 0; i < kLobeValueCount; ++i)
        if (set & lobeBit(LobeValue(i))) {
            if (!s.empty())
                s += ", ";
            s += lobeValueLabel(LobeValue(i));
        }
    return s;
}

std::string lobeChannelsGlsl() {
    std::string s = "#define LOBE_CHANNEL_COUNT " + std::to_string(kLobeChannelCount) + "\n" +
                    "#define LOBE_PER_MATERIAL " + std::to_string(kLobePerMaterial) + "\n";
    for (int i = 0; i < kLobeValueCount; ++i)
        s +=
            "#define " + std::string(lobeValueMacro(LobeValue(i))) + " " + std::to_string(i) + "\n";
    return s;
}

} // namespace velvet::render
