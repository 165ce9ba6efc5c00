// Toon: a pointwise shader function, post_toon() in resources/shaders/post_toon.frag, fused with
// its pointwise neighbours by render/post_chain.cpp.
#include "render/post_effect.h"

namespace velvet::render {
namespace {

/// Toon shading (seed 002): luminance cut into `bands` flat levels keeping hue, an outline where
/// depth or normals change (reads the G-buffer, not neighbouring colour, so it stays fusable).
/// Uniforms: uParams[base + TOON_*].
class ToonEffect final : public FusableEffect {
public:
    ToonEffect() : FusableEffect("toon") {}
};

} // namespace

std::unique_ptr<PostEffect> makeToonEffect() {
    return std::make_unique<ToonEffect>();
}

} // namespace velvet::render
