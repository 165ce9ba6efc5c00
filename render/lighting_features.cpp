#include "render/lighting_features.h"

#include "render/lobe_channels.h"

#include <algorithm>

namespace velvet::render {
namespace {

/// Whether the record's lobe-channel map (GpuMaterial::terms2.w, 4 bits per LobeValue) carries
/// @p value per pixel.
bool perPixel(const GpuMaterial& m, LobeValue value) {
    if (value == LobeValue::Ior)
        return iorLobeEntry(m) != kLobePerMaterial;
    const auto map = static_cast<std::uint32_t>(m.terms2.w);
    return ((map >> (4 * static_cast<int>(value))) & 0xFu) != std::uint32_t(kLobePerMaterial);
}

/// The one value @p term takes over @p records, or kAnyTerm when they differ.
template <typename Term>
int commonTerm(std::span<const GpuMaterial> records, Term term) {
    if (records.empty())
        return LightingFeatures::kAnyTerm;
    const int first = term(records.front());
    for (const GpuMaterial& m : records)
        if (term(m) != first)
            return LightingFeatures::kAnyTerm;
    return first;
}

} // namespace

std::vector<std::string> LightingFeatures::defines() const {
    std::vector<std::string> out;
    auto fixed = [&](const char* name, int value) {
        if (value != kAnyTerm)
            out.push_back(std::string(name) + " " + std::to_string(value));
    };
    fixed("FIXED_DISTRIBUTION", distribution);
    fixed("FIXED_VISIBILITY", visibility);
    fixed("FIXED_FRESNEL", fresnel);
    fixed("FIXED_DIFFUSE", diffuse);
    fixed("FIXED_SHEEN_MODEL", sheenModel);
    fixed("FIXED_DIRECTIONAL_LIGHTS", directionalLights);
    fixed("FIXED_MATERIAL_ID", materialId);
    // Compiled out only when absent (lighting.frag's defaults are 1: the generic program).
    auto without = [&](const char* name, bool present) {
        if (!present)
            out.push_back(std::string(name) + " 0");
    };
    without("WITH_SHEEN", sheen);
    without("WITH_CLEARCOAT", clearcoat);
    without("WITH_ANISOTROPY", anisotropy);
    without("WITH_LOBE_CHANNELS", lobeChannels);
    without("WITH_DIRECTIONAL_SHADOWS", directionalShadows);
    without("WITH_SHADOW_MASK", shadowMask);
    without("WITH_LOCAL_SHADOWS", localShadows);
    without("WITH_OCCLUSION", occlusion);
    without("WITH_GEOMETRIC_HORIZON", geometricHorizon);
    without("WITH_GBUFFER_VALUES", gbufferValues);
    without("WITH_SAMPLED_REFLECTIONS", sampledReflections);
    without("WITH_IRRADIANCE_MAP", irradianceMap);
    if (screenSpaceReflections) // off by default (lighting.frag's default is 0)
        out.push_back("WITH_SCREEN_SPACE_REFLECTIONS 1");
    fixed("FIXED_IBL_BAKED", iblBaked);
    fixed("FIXED_MULTIPLE_SCATTERING", multipleScattering);
    fixed("FIXED_OCCLUSION_IN_MASK", occlusionInMask);
    return out;
}

LightingFeatures lightingFeaturesOf(std::span<const GpuMaterial> records, bool directionalShadows,
                                    bool occlusion, bool iblBaked, bool multipleScattering) {
    LightingFeatures f;
    f.distribution = commonTerm(records, [](const GpuMaterial& m) { return m.terms.x; });
    f.visibility = commonTerm(records, [](const GpuMaterial& m) { return m.terms.y; });
    f.fresnel = commonTerm(records, [](const GpuMaterial& m) { return m.terms.z; });
    f.diffuse = commonTerm(records, [](const GpuMaterial& m) { return m.terms.w; });
    f.sheenModel = commonTerm(records, [](const GpuMaterial& m) { return m.terms2.x; });
    auto any = [&](auto&& has) { return std::any_of(records.begin(), records.end(), has); };
    // gbuffer_read.glsl: sheen colour = colour x weight unless a lobe channel carries it.
    f.sheen = any([](const GpuMaterial& m) {
        const glm::vec3 c = glm::vec3(m.sheenColorRoughness) * m.sheenWeightAnisotropy.x;
        return std::max({c.r, c.g, c.b}) > 0.0f || perPixel(m, LobeValue::SheenColor);
    });
    f.clearcoat = any([](const GpuMaterial& m) {
        return m.clearcoat.x > 0.0f || perPixel(m, LobeValue::Clearcoat);
    });
    // common_brdf.glsl's usesAnisotropy(): GGX only (core/material.h: Distribution::GGX is 0).
    f.anisotropy = any([](const GpuMaterial& m) {
        return m.terms.x == 0 &&
               (m.sheenWeightAnisotropy.y > 0.0f || perPixel(m, LobeValue::Anisotropy));
    });
    f.lobeChannels = any([](const GpuMaterial& m) { return hasLobeMap(m); });
    f.geometricHorizon = any([](const GpuMaterial& m) { return m.sheenWeightAnisotropy.w > 0.5f; });
    f.gbufferValues =
        any([](const GpuMaterial& m) { return (m.terms2.y & kRecordValuesPerMaterial) == 0; });
    f.directionalShadows = directionalShadows;
    f.occlusion = occlusion;
    f.iblBaked = iblBaked ? 1 : 0;
    f.multipleScattering = multipleScattering ? 1 : 0;
    return f;
}

} // namespace velvet::render
