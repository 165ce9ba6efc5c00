// FXAA: one pass of resources/shaders/post_fxaa.frag.
#include "render/post_effect.h"

namespace velvet::render {
namespace {

/// FXAA (Lottes 2009, "FXAA", NVIDIA white paper): an edge direction from the local luma
/// gradient, taps along it blend the edge. Runs on display-encoded colour.
/// Uniforms: uParams[FXAA_EDGETHRESHOLD], uParams[FXAA_SUBPIXEL].
class FxaaEffect final : public SinglePassEffect {
public:
    FxaaEffect() : SinglePassEffect("fxaa") {}
};

} // namespace

std::unique_ptr<PostEffect> makeFxaaEffect() {
    return std::make_unique<FxaaEffect>();
}

} // namespace velvet::render
