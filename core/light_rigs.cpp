#include "core/light_rigs.h"

#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <string>

namespace velvet {
namespace {

constexpr std::array kRigs = {
    LightRig{"key", "Key light",
             "One warm directional key light from the upper left; the HDRI fills the shadows"},
    LightRig{"three-point", "Studio three-point",
             "Warm key, cool fill and a rim light from behind, as in a photo studio; all three "
             "cast shadows"},
    LightRig{"softboxes", "Softboxes",
             "Two rectangular area lights left and right and a rim: soft, broad highlights"},
    LightRig{"sun", "Sun", "One strong, slightly warm sun high in the sky"},
    LightRig{"stage-spot", "Stage spot",
             "A spot light from above in front, a dim ambient: judges the falloff of sheen"},
    LightRig{"coloured-points", "Coloured points",
             "64 small coloured point lights in a ring: many highlights, the tiled light path"},
    LightRig{"environment", "Environment only", "No lights: the HDRI alone"},
};

Light directional(std::string name, glm::vec3 color, float lux, glm::vec3 direction,
                  bool castShadows = false) {
    Light light;
    light.castShadows = castShadows;
    light.type = LightType::Directional;
    light.name = std::move(name);
    light.color = color;
    light.intensity = lux;
    light.direction = direction; // the renderer normalises
    return light;
}

Light rectangle(std::string name, glm::vec3 position, glm::vec2 size, float nits) {
    Light light;
    light.type = LightType::Area;
    light.shape = AreaShape::Rectangle;
    light.name = std::move(name);
    light.position = position;
    light.direction = glm::normalize(-position); // facing the mesh at the origin
    light.size = size;
    light.intensity = nits;
    light.range = 12.0f;
    return light;
}

std::vector<Light> rigLights(std::string_view id) {
    if (id == "key") // the default scene's light (core/document_io.cpp)
        return {directional("Key", {1.0f, 0.93f, 0.85f}, 3.0f, {0.5f, -0.6f, -0.62f}, true)};
    if (id == "three-point") // every light shadows, as in a studio and in the path tracer: a
        // shadowless fill and rim lit the shader ball under its rings (BENCHMARKS.md)
        return {directional("Key", {1.0f, 0.92f, 0.82f}, 3.0f, {0.55f, -0.55f, -0.63f}, true),
                directional("Fill", {0.78f, 0.86f, 1.0f}, 0.9f, {-0.7f, -0.2f, -0.68f}, true),
                directional("Rim", {1.0f, 1.0f, 1.0f}, 2.5f, {-0.25f, -0.45f, 0.86f}, true)};
    if (id == "softboxes")
        return {[] {
                    // The key of the rig: its shadow is soft from the box's size.
                    Light key = rectangle("Softbox left", {-2.2f, 1.2f, 1.8f}, {1.2f, 1.6f}, 9.0f);
                    key.castShadows = true;
                    return key;
                }(),
                rectangle("Softbox right", {2.2f, 0.8f, 1.8f}, {1.2f, 1.6f}, 5.0f),
                directional("Rim", {1.0f, 1.0f, 1.0f}, 1.5f, {0.2f, -0.4f, 0.9f})};
    if (id == "sun")
        return {directional("Sun", {1.0f, 0.95f, 0.88f}, 6.0f, {0.3f, -0.85f, -0.43f}, true)};
    if (id == "stage-spot") {
        Light spot;
        spot.type = LightType::Spot;
        spot.name = "Spot";
        spot.position = {0.6f, 3.0f, 2.2f};
        spot.direction = glm::normalize(-spot.position);
        spot.intensity = 40.0f;
        spot.range = 8.0f;
        spot.innerConeDeg = 8.0f;
        spot.outerConeDeg = 14.0f;
        spot.castShadows = true;
        Light ambient;
        ambient.type = LightType::Ambient;
        ambient.name = "Ambient";
        ambient.intensity = 0.05f;
        return {spot, ambient};
    }
    if (id == "coloured-points") {
        // A ring of 64 lights around the mesh at two heights; hues around the colour wheel.
        std::vector<Light> lights;
        constexpr int kCount = 64;
        for (int i = 0; i < kCount; ++i) {
            const float t = float(i) / float(kCount);
            const float angle = t * 6.2831853f;
            Light point;
            point.type = LightType::Point;
            point.name = "Point " + std::to_string(i + 1);
            point.position = {1.6f * std::cos(angle), (i % 2 == 0) ? 0.6f : -0.4f,
                              1.6f * std::sin(angle)};
            // Hue to RGB (the HSV hexcone with full saturation and value).
            const glm::vec3 hue = glm::clamp(
                glm::abs(glm::mod(t * 6.0f + glm::vec3(0.0f, 4.0f, 2.0f), 6.0f) - 3.0f) - 1.0f,
                0.0f, 1.0f);
            point.color = hue;
            point.intensity = 0.35f;
            point.range = 1.4f;
            lights.push_back(point);
        }
        return lights;
    }
    return {}; // "environment"
}

} // namespace

std::span<const LightRig> lightRigs() {
    return kRigs;
}

std::optional<std::vector<Light>> lightRigLights(std::string_view id) {
    for (const LightRig& rig : kRigs)
        if (rig.id == id)
            return rigLights(id);
    return std::nullopt;
}

std::optional<std::string_view> matchingLightRig(const std::vector<Light>& lights) {
    for (const LightRig& rig : kRigs)
        if (rigLights(rig.id) == lights)
            return rig.id;
    return std::nullopt;
}

} // namespace velvet
