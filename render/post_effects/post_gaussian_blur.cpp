// Gaussian blur: two 1-D passes with CPU-normalised weights (gaussianWeights); sigma >= 3 runs
// at half resolution (box downsample, blur with sigma / 2, bilinear upsample), which costs a
// quarter of the taps for a visually identical result on wide kernels.
#include "render/post_effect.h"

#include <algorithm>
#include <cmath>
#include <epoxy/gl.h>

namespace velvet::render {
namespace {

/// Separable gaussian (seed 001): post_gaussian_blur.frag, uPass.x 0 horizontal, 1 vertical,
/// 2 box downsample / bilinear resample, 3 bilinear upsample; uniforms: the weights
/// (kPostWeightsLocation) and the tap count (uPass.y). Also serves ctx.blur for other effects.
class GaussianBlurEffect final : public PostEffect {
public:
    GaussianBlurEffect() : PostEffect("gaussian_blur") {}

    std::vector<PostPassInfo> passes() const override {
        return {{"downsample (sigma >= 3)", "post_gaussian_blur.frag", 2},
                {"horizontal", "post_gaussian_blur.frag", 1},
                {"vertical", "post_gaussian_blur.frag", 1},
                {"upsample (sigma >= 3)", "post_gaussian_blur.frag", 1}};
    }

    bool build(PostContext& ctx, std::string* error) override {
        if (!buildPostProgram(m_program, "post_gaussian_blur.frag", {}, error, ctx.compileCount))
            return false;
        ctx.blur = [this, &ctx](const PostTarget& in, const PostTarget& out, float sigma,
                                int radius) { blur(ctx, in, out, sigma, radius); };
        return true;
    }

    void run(PostContext& ctx, const EffectInstance& effect, const PostTarget& input,
             const PostTarget& output) override {
        const float sigma = effectFloat(effect, "sigma");
        const int radius = int(std::lround(effectFloat(effect, "radius")));
        if (sigma < 3.0f) {
            blur(ctx, input, output, sigma, radius);
            return;
        }
        const PostTarget half =
            ctx.pool->acquire(std::max(input.width / 2, 1), std::max(input.height / 2, 1));
        drawPostPass(ctx, m_program.id(), input, half, 2);
        const PostTarget blurred = ctx.pool->acquire(half.width, half.height);
        blur(ctx, half, blurred, sigma * 0.5f, std::max((radius + 1) / 2, 1));
        drawPostPass(ctx, m_program.id(), blurred, output, 3);
        ctx.pool->release(half);
        ctx.pool->release(blurred);
    }

    /// Separable blur of @p in into @p out at out's size (a bilinear resample first when sizes
    /// differ).
    void blur(PostContext& ctx, const PostTarget& in, const PostTarget& out, float sigma,
              int radius) {
        const unsigned p = m_program.id();
        const std::vector<float> w = gaussianWeights(sigma, radius);
        glProgramUniform1fv(p, kPostWeightsLocation, GLsizei(w.size()), w.data());
        PostTarget source = in;
        PostTarget resized;
        if (in.width != out.width || in.height != out.height) {
            resized = ctx.pool->acquire(out.width, out.height);
            drawPostPass(ctx, p, in, resized, 2);
            source = resized;
        }
        const PostTarget tmp = ctx.pool->acquire(out.width, out.height);
        drawPostPass(ctx, p, source, tmp, 0, int(w.size()) - 1);
        drawPostPass(ctx, p, tmp, out, 1, int(w.size()) - 1);
        ctx.pool->release(tmp);
        if (resized.texture)
            ctx.pool->release(resized);
    }

private:
    ShaderProgram m_program;
};

} // namespace

std::unique_ptr<PostEffect> makeGaussianBlurEffect() {
    return std::make_unique<GaussianBlurEffect>();
}

} // namespace velvet::render
