#include "render/scene_copy.h"

#include <utility>

namespace velvet::render {

void takeSceneParts(Scene& dst, const Scene& src, ScenePart parts) {
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

} // namespace velvet::render
