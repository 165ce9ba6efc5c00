// Tone mapping as a chain stage: post_tonemap() in resources/shaders/post_tonemap.glsl
// (exposure, a curve, then OCIO's display encoding), fused with its pointwise neighbours; the
// "display" operator is instead drawn by the OpenColorIO display transform
// (render/display_transform.cpp) as a step of its own, run by render/post_chain.cpp through
// PostRunInputs::displayTransform.
#include "render/post_effect.h"

namespace velvet::render {
namespace {

/// Tone mapping: exposure, then PBR Neutral, ACES fitted, Reinhard, Filmic (Hable 2010), AgX or
/// linear; uniforms: uParams[base + TONEMAP_EXPOSURE], uParams[base + TONEMAP_OPERATOR].
class ToneMapEffect final : public FusableEffect {
public:
    ToneMapEffect() : FusableEffect("tonemap") {}

    bool displayEncodes() const override { return true; }
};

} // namespace

std::unique_ptr<PostEffect> makeToneMapEffect() {
    return std::make_unique<ToneMapEffect>();
}

} // namespace velvet::render
