// Night vision: a pointwise shader function, post_night_vision() in
// resources/shaders/post_night_vision.frag, fused with its pointwise neighbours.
#include "render/post_effect.h"

namespace velvet::render {
namespace {

/// Night vision (seed 000): luminance times green-weighted channels, animated grain (time from
/// the PostFrame block), vignetting. Uniforms: uParams[base + NIGHT_VISION_*].
class NightVisionEffect final : public FusableEffect {
public:
    NightVisionEffect() : FusableEffect("night_vision") {}
};

} // namespace

std::unique_ptr<PostEffect> makeNightVisionEffect() {
    return std::make_unique<NightVisionEffect>();
}

} // namespace velvet::render
