// Vaporwave: one pass of resources/shaders/post_vaporwave.frag.
#include "render/post_effect.h"

namespace velvet::render {
namespace {

/// Vaporwave (seed 004): green channel shifted horizontally, desaturation and a purple tint, a
/// checker floor replacing the far background (reads depth), TV static and scanlines.
/// Uniforms: uParams[VAPORWAVE_*], time from the PostFrame block.
class VaporwaveEffect final : public SinglePassEffect {
public:
    VaporwaveEffect() : SinglePassEffect("vaporwave") {}
};

} // namespace

std::unique_ptr<PostEffect> makeVaporwaveEffect() {
    return std::make_unique<VaporwaveEffect>();
}

} // namespace velvet::render
