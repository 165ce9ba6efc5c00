// Sharpen: one pass of resources/shaders/post_sharpen.frag.
#include "render/post_effect.h"

namespace velvet::render {
namespace {

/// Sharpen: unsharp mask against the mean of the four direct neighbours.
/// Uniforms: uParams[SHARPEN_AMOUNT].
class SharpenEffect final : public SinglePassEffect {
public:
    SharpenEffect() : SinglePassEffect("sharpen") {}
};

} // namespace

std::unique_ptr<PostEffect> makeSharpenEffect() {
    return std::make_unique<SharpenEffect>();
}

} // namespace velvet::render
