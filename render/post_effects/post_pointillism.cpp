// Pointillism: one pass of resources/shaders/post_pointillism.frag.
#include "render/post_effect.h"

namespace velvet::render {
namespace {

/// Pointillism (seed 004): dots of each grid cell's centre colour, larger in darker cells, on
/// paper; a pixel looks at the 3x3 cells around it. Deterministic (no time).
/// Uniforms: uParams[POINTILLISM_*].
class PointillismEffect final : public SinglePassEffect {
public:
    PointillismEffect() : SinglePassEffect("pointillism") {}
};

} // namespace

std::unique_ptr<PostEffect> makePointillismEffect() {
    return std::make_unique<PointillismEffect>();
}

} // namespace velvet::render
