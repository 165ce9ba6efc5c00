#include "core/scene_parts.h"

#include "core/scene.h"

namespace velvet {

ScenePart changedParts(const Scene& a, const Scene& b) {
    ScenePart parts = ScenePart::None;
    if (!(a.camera == b.camera))
        parts |= ScenePart::Camera;
    const Material& ma = a.material;
    const Material& mb = b.material;
    bool values = ma.name != mb.name || ma.tags != mb.tags || a.materialPreset != b.materialPreset;
    for (int i = 0; i < kParamCount && !values; ++i)
        values = ma.value(ParamId(i)) != mb.value(ParamId(i));
    if (values)
        parts |= ScenePart::MaterialValues;
    for (int i = 0; i < kTextureSlotCount; ++i)
        if (!(ma.texture(TextureSlot(i)) == mb.texture(TextureSlot(i)))) {
            parts |= ScenePart::MaterialStructure;
            break;
        }
    if (!(ma.graph == mb.graph))
        parts |= ScenePart::Graph;
    if (!(a.mesh == b.mesh))
        parts |= ScenePart::Mesh;
    if (!(a.environment == b.environment))
        parts |= ScenePart::Environment;
    if (a.lights != b.lights)
        parts |= ScenePart::Lights;
    if (!(a.post == b.post))
        parts |= ScenePart::PostChain;
    if (a.atlases != b.atlases)
        parts |= ScenePart::Atlases;
    return parts;
}

void copyParts(Scene& dst, const Scene& src, ScenePart parts) {
    if (touches(parts, ScenePart::Camera))
        dst.camera = src.camera;
    if (touches(parts, ScenePart::Material)) {
        // The values (parameters, BRDF terms, names) from the side the mask names; texture slots
        // and the graph each from theirs.
        Material m = touches(parts, ScenePart::MaterialValues) ? src.material : dst.material;
        const Material& structure =
            touches(parts, ScenePart::MaterialStructure) ? src.material : dst.material;
        for (int i = 0; i < kTextureSlotCount; ++i)
            m.setTexture(TextureSlot(i), structure.texture(TextureSlot(i)));
        m.graph = touches(parts, ScenePart::Graph) ? src.material.graph : dst.material.graph;
        dst.material = std::move(m);
        if (touches(parts, ScenePart::MaterialValues))
            dst.materialPreset = src.materialPreset;
    }
    if (touches(parts, ScenePart::Mesh))
        dst.mesh = src.mesh;
    if (touches(parts, ScenePart::Environment))
        dst.environment = src.environment;
    if (touches(parts, ScenePart::Lights))
        dst.lights = src.lights;
    if (touches(parts, ScenePart::PostChain))
        dst.post = src.post;
    if (touches(parts, ScenePart::Atlases))
        dst.atlases = src.atlases;
}

} // namespace velvet
