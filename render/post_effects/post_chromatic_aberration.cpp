// Chromatic aberration: one pass of resources/shaders/post_chromatic_aberration.frag.
#include "render/post_effect.h"

namespace velvet::render {
namespace {

/// Radial chromatic aberration: red sampled outwards and blue inwards, `amount` pixels at the
/// corners. Uniforms: uParams[CHROMATIC_ABERRATION_AMOUNT].
class ChromaticAberrationEffect final : public SinglePassEffect {
public:
    ChromaticAberrationEffect() : SinglePassEffect("chromatic_aberration") {}
};

} // namespace

std::unique_ptr<PostEffect> makeChromaticAberrationEffect() {
    return std::make_unique<ChromaticAberrationEffect>();
}

} // namespace velvet::render
