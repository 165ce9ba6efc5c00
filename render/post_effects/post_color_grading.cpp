// Colour grading: a pointwise shader function, post_color_grading() in
// resources/shaders/post_color_grading.frag, fused with its pointwise neighbours.
#include "render/post_effect.h"

namespace velvet::render {
namespace {

/// Colour grading in scene-linear: exposure, white balance, contrast around 18 % grey in log2
/// (ACEScct-style), saturation, ASC-CDL-like lift / gamma / gain.
/// Uniforms: uParams[base + COLOR_GRADING_*].
class ColorGradingEffect final : public FusableEffect {
public:
    ColorGradingEffect() : FusableEffect("color_grading") {}
};

} // namespace

std::unique_ptr<PostEffect> makeColorGradingEffect() {
    return std::make_unique<ColorGradingEffect>();
}

} // namespace velvet::render
