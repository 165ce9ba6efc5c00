// Motion blur: one pass of resources/shaders/post_motion_blur.frag (seed 002; Rosado 2007, "Motion
// Blur as a Post-Processing Effect", GPU Gems 3 ch. 27), with optional frame blending.
#include "render/post_effect.h"

namespace velvet::render {
namespace {

/// Camera motion blur from depth and the previous view-projection: the pixel's world position is
/// reprojected with last frame's matrix and the image averaged along the difference. With
/// `frameBlend` > 0 the result is also blended with last frame's input to this effect (frame
/// blending as in Unity's post-processing stack v1 / Kino Motion, one frame of history), which
/// the chain keeps in a pooled target while this instance asks for it (readsPreviousFrame).
/// Uniforms: uParams[MOTION_BLUR_*]; the history on kPostAuxUnit with uPass.y = 1 when bound.
class MotionBlurEffect final : public SinglePassEffect {
public:
    MotionBlurEffect() : SinglePassEffect("motion_blur") {}

    bool readsPreviousFrame(const EffectInstance& effect) const override {
        return effectFloat(effect, "frameBlend") > 0.0f;
    }

protected:
    unsigned bindInputs(PostContext& ctx, const EffectInstance& effect, int& level) override {
        const bool history = ctx.previousFrame.texture != 0 && readsPreviousFrame(effect);
        level = history ? 1 : 0;
        return history ? ctx.previousFrame.texture : 0;
    }
};

} // namespace

std::unique_ptr<PostEffect> makeMotionBlurEffect() {
    return std::make_unique<MotionBlurEffect>();
}

} // namespace velvet::render
