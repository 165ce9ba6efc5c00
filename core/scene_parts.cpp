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

} // namespace velvet
