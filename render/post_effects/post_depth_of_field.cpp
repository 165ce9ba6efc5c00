// Depth of field: a half-resolution gaussian copy (sigma = maxBlur / 2 at half resolution, so
// maxBlur full-resolution pixels), blended with the sharp image by the circle of confusion.
#include "render/post_effect.h"

#include <algorithm>
#include <cmath>

namespace velvet::render {
namespace {

/// Depth of field: the blur (ctx.blur, so it depends on "gaussian_blur") at half resolution,
/// then post_depth_of_field.frag blends it by the circle of confusion; uniforms: the DoF
/// parameters at slot 0, the blurred copy on kPostAuxUnit.
class DepthOfFieldEffect final : public PostEffect {
public:
    DepthOfFieldEffect() : PostEffect("depth_of_field") {}

    std::vector<PostPassInfo> passes() const override {
        return {{"gaussian copy", "post_gaussian_blur.frag", 2},
                {"circle-of-confusion blend", "post_depth_of_field.frag", 1}};
    }
    std::vector<std::string_view> dependencies() const override { return {"gaussian_blur"}; }

    bool build(PostContext& ctx, std::string* error) override {
        return buildPostProgram(m_program, "post_depth_of_field.frag", {}, error, ctx.compileCount);
    }

    void run(PostContext& ctx, const EffectInstance& effect, const PostTarget& input,
             const PostTarget& output) override {
        setEffectParams(m_program.id(), meta(), effect, 0);
        const float maxBlur = effectFloat(effect, "maxBlur");
        const PostTarget blurred =
            ctx.pool->acquire(std::max(input.width / 2, 1), std::max(input.height / 2, 1));
        const float sigma = std::max(maxBlur * 0.25f, 0.3f); // radius maxBlur ~ 2 sigma
        ctx.blur(input, blurred, sigma, int(std::ceil(2.5f * sigma)));
        drawPostPass(ctx, m_program.id(), input, output, 0, 0, blurred.texture);
        ctx.pool->release(blurred);
    }

private:
    ShaderProgram m_program;
};

} // namespace

std::unique_ptr<PostEffect> makeDepthOfFieldEffect() {
    return std::make_unique<DepthOfFieldEffect>();
}

} // namespace velvet::render
