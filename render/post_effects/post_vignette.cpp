// Vignette: a pointwise shader function, post_vignette() in resources/shaders/post_vignette.frag,
// fused with its pointwise neighbours by render/post_chain.cpp.
#include "render/post_effect.h"

namespace velvet::render {
namespace {

/// Vignette with seed 001's six controls (centre, roundness, intensity, smoothness, blend,
/// colour); corners are darkened by exactly `intensity`. Uniforms: uParams[base + VIGNETTE_*].
class VignetteEffect final : public FusableEffect {
public:
    VignetteEffect() : FusableEffect("vignette") {}
};

} // namespace

std::unique_ptr<PostEffect> makeVignetteEffect() {
    return std::make_unique<VignetteEffect>();
}

} // namespace velvet::render
