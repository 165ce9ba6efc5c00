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

void copyParts(Scene& to, const Scene& from, ScenePart parts) {
    if (touches(parts, ScenePart::Camera))
        to.camera = from.camera;
    if (touches(parts, ScenePart::Material)) {
        to.material = from.material;
        to.materialPreset = from.materialPreset;
    }
    if (touches(parts, ScenePart::Mesh))
        to.mesh = from.mesh;
    if (touches(parts, ScenePart::Environment))
        to.environment = from.environment;
    if (touches(parts, ScenePart::Lights))
        to.lights = from.lights;
    if (touches(parts, ScenePart::PostChain))
        to.post = from.post;
    if (touches(parts, ScenePart::Atlases))
        to.atlases = from.atlases;
}

} // namespace velvet
