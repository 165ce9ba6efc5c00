#pragma once
/// @file scene_parts.h
/// Which parts of a Scene an edit changed, as a bit mask (../shared/DESIGN.md, "Changes"). The
/// document controller says what each edit touched; the renderer and the panels update only
/// those parts (an orbit is a per-frame camera, not a scene edit, so it uploads nothing).

#include <cstdint>

namespace velvet {

struct Scene;

enum class ScenePart : std::uint32_t {
    None = 0,
    Camera = 1u << 0,            ///< Scene::camera (the document's saved view)
    MaterialValues = 1u << 1,    ///< parameter values and BRDF terms of Scene::material
    MaterialStructure = 1u << 2, ///< texture slots (files, colour spaces, atlas regions)
    Graph = 1u << 3,             ///< Material::graph (its structure or its node values)
    Mesh = 1u << 4,              ///< Scene::mesh
    Environment = 1u << 5,       ///< Scene::environment (HDRI, intensity, rotation, background)
    Lights = 1u << 6,            ///< Scene::lights
    PostChain = 1u << 7,         ///< Scene::post
    Atlases = 1u << 8,           ///< Scene::atlases and the atlas documents it names
    /// A material replaced as a whole (a preset applied): every material part.
    Material = MaterialValues | MaterialStructure | Graph,
    All = (1u << 9) - 1,
};

/// A set of ScenePart bits.
using SceneParts = ScenePart;

constexpr ScenePart operator|(ScenePart a, ScenePart b) {
    return ScenePart(std::uint32_t(a) | std::uint32_t(b));
}
constexpr ScenePart operator&(ScenePart a, ScenePart b) {
    return ScenePart(std::uint32_t(a) & std::uint32_t(b));
}
constexpr ScenePart operator~(ScenePart a) {
    return ScenePart(~std::uint32_t(a) & std::uint32_t(ScenePart::All));
}
constexpr ScenePart& operator|=(ScenePart& a, ScenePart b) {
    return a = a | b;
}
constexpr ScenePart& operator&=(ScenePart& a, ScenePart b) {
    return a = a & b;
}
/// Whether @p parts holds any bit of @p part.
constexpr bool touches(ScenePart parts, ScenePart part) {
    return (std::uint32_t(parts) & std::uint32_t(part)) != 0;
}

/// Takes into @p dst the parts of @p src that @p parts names, and nothing else: a part the mask
/// does not name keeps @p dst's own (MaterialValues, MaterialStructure and Graph each copy only
/// their share of the Material), so what the renderer draws is what it was handed.
void copyParts(Scene& dst, const Scene& src, ScenePart parts);

/// The parts in which @p a and @p b differ (for callers that hold two whole scenes: the CLI's
/// batch renders, tests; the editor knows what each edit changed and never diffs).
ScenePart changedParts(const Scene& a, const Scene& b);

} // namespace velvet
