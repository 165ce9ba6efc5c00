// Depth of field: two half-resolution gaussian copies, a narrow one (blur radius maxBlur / 2 in
// full-resolution pixels) and a wide one (maxBlur), blended with the sharp image by the circle of
// confusion: the blur radius grows with the CoC.
#include "render/post_effect.h"

#include <algorithm>
#include <cmath>
#include <epoxy/gl.h>

namespace velvet::render {
namespace {

/// Depth of field: the blurs (ctx.blur, so it depends on "gaussian_blur") at half resolution,
/// then post_depth_of_field.frag interpolates sharp, narrow and wide by the circle of confusion;
/// uniforms: the DoF parameters at slot 0, the narrow copy on kPostAuxUnit, the wide one on
/// kPostAux2Unit.
class DepthOfFieldEffect final : public PostEffect {
public:
    DepthOfFieldEffect() : PostEffect("depth_of_field") {}

    std::vector<PostPassInfo> passes() const override {
        return {{"narrow gaussian copy", "post_gaussian_blur.frag", 2},
                {"wide gaussian copy", "post_gaussian_blur.frag", 2},
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
        const int w = std::max(input.width / 2, 1), h = std::max(input.height / 2, 1);
        const PostTarget narrow = ctx.pool->acquire(w, h);
        const PostTarget wide = ctx.pool->acquire(w, h);
        // Sigmas at half resolution: a full-resolution radius r is ~2 sigma, i.e. sigma = r / 4
        // here. The wide copy blurs the narrow one further: gaussians add their variances, so
        // sqrt(wide^2 - narrow^2) more gives the wide sigma with fewer taps.
        const float narrowSigma = std::max(maxBlur * 0.125f, 0.3f);
        const float wideSigma = std::max(maxBlur * 0.25f, 0.3f);
        const float extra = std::max(
            std::sqrt(std::max(wideSigma * wideSigma - narrowSigma * narrowSigma, 0.0f)), 0.3f);
        ctx.blur(input, narrow, narrowSigma, int(std::ceil(2.5f * narrowSigma)));
        ctx.blur(narrow, wide, extra, int(std::ceil(2.5f * extra)));
        glBindTextureUnit(kPostAux2Unit, wide.texture);
        drawPostPass(ctx, m_program.id(), input, output, 0, 0, narrow.texture);
        glBindTextureUnit(kPostAux2Unit, 0);
        ctx.pool->release(wide);
        ctx.pool->release(narrow);
    }

private:
    ShaderProgram m_program;
};

} // namespace

std::unique_ptr<PostEffect> makeDepthOfFieldEffect() {
    return std::make_unique<DepthOfFieldEffect>();
}

} // namespace velvet::render
