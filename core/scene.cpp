#include "core/scene.h"

#include "core/post_effects.h"

#include <array>

namespace velvet {
namespace {

constexpr std::array<std::string_view, 5> kLightTypes{"directional", "point", "spot", "area",
                                                      "ambient"};
constexpr std::array<std::string_view, 2> kAreaShapes{"sphere", "rectangle"};
constexpr std::array<std::string_view, 4> kBackgroundModes{"sharp", "blurred", "solid-color",
                                                           "procedural-fbm"};
constexpr std::array<std::string_view, 7> kMeshKinds{
    "sphere", "cube", "rounded-cube", "plane", "cloth-drape", "shader-ball", "custom"};

constexpr std::array<std::string_view, 3> kGroundModes{"off", "shadow-catcher", "plain"};
static_assert(kGroundModes.size() == static_cast<size_t>(GroundMode::Plain) + 1);

bool standsOnGround(PreviewMeshKind kind) {
    return kind == PreviewMeshKind::ClothDrape || kind == PreviewMeshKind::ShaderBall;
}

static_assert(kLightTypes.size() == static_cast<size_t>(LightType::Ambient) + 1);
static_assert(kAreaShapes.size() == static_cast<size_t>(AreaShape::Rectangle) + 1);
static_assert(kBackgroundModes.size() == static_cast<size_t>(BackgroundMode::ProceduralFbm) + 1);
static_assert(kMeshKinds.size() == static_cast<size_t>(PreviewMeshKind::Custom) + 1);

} // namespace

std::span<const std::string_view> lightTypeNames() {
    return kLightTypes;
}
std::span<const std::string_view> areaShapeNames() {
    return kAreaShapes;
}
std::span<const std::string_view> backgroundModeNames() {
    return kBackgroundModes;
}
std::span<const std::string_view> previewMeshKindNames() {
    return kMeshKinds;
}

std::span<const std::string_view> groundModeNames() {
    return kGroundModes;
}

void applyStageDefaults(Environment& environment, PreviewMeshKind kind) {
    const bool stand = standsOnGround(kind);
    environment.ground = stand ? GroundMode::ShadowCatcher : GroundMode::Off;
    environment.ambientOcclusion = stand;
}

bool hasStageDefaults(const Environment& environment, PreviewMeshKind kind) {
    Environment expected = environment;
    applyStageDefaults(expected, kind);
    return expected == environment;
}

bool sceneReadsTime(const Scene& scene) {
    return scene.environment.background == BackgroundMode::ProceduralFbm ||
           postChainReadsTime(scene.post);
}

} // namespace velvet
