// Depth of field: a half-resolution gaussian copy (sigma = maxBlur / 2 at half resolution, so
// maxBlur full-resolution pixels), blended with the sharp image by the circle of confusion.
#include "render/post_effect.h"

#include <algorithm>
#include <cmath>

namespace velvet::render {
namespace {

class DepthOfFieldEffect final : public PostEffect {
public:
    bool build(PostContext& ctx, std::string* error) override {
        return buildPostProgram(m_program, "post_depth_of_field.frag", {}, error, ctx.compileCount);
    }

    void run(PostContext& ctx, const EffectInstance& effect, const PostTarget& input,
             const PostTarget& output) override {
        setEffectParams(m_program.id(), *findPostEffect("depth_of_field"), effect, 0);
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
