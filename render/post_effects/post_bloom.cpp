// Bloom: bright pass + 13-tap downsample chain from half resolution, tent upsample chain added
// level by level, additive composite (resources/shaders/post_bloom.frag cites the method).
#include "render/post_effect.h"

#include <algorithm>
#include <cmath>
#include <epoxy/gl.h>

namespace velvet::render {
namespace {

/// Bloom (Jimenez 2014, "Next Generation Post Processing in Call of Duty: Advanced Warfare"):
/// four programs of post_bloom.frag (POST_PASS 0–3); uniforms: the bloom parameters at slot 0,
/// uPass.y the level count of the composite.
class BloomEffect final : public PostEffect {
public:
    BloomEffect() : PostEffect("bloom") {}

    std::vector<PostPassInfo> passes() const override {
        return {{"bright pass + 13-tap downsample", "post_bloom.frag", 2},
                {"13-tap downsample", "post_bloom.frag", 0},
                {"tent upsample, additive", "post_bloom.frag", 0},
                {"composite", "post_bloom.frag", 1}};
    }

    bool build(PostContext& ctx, std::string* error) override {
        for (int pass = 0; pass < 4; ++pass)
            if (!buildPostProgram(m_programs[pass], "post_bloom.frag", {}, error, ctx.compileCount,
                                  pass))
                return false;
        return true;
    }

    void run(PostContext& ctx, const EffectInstance& effect, const PostTarget& input,
             const PostTarget& output) override {
        unsigned p[4];
        for (int pass = 0; pass < 4; ++pass) {
            p[pass] = m_programs[pass].id();
            setEffectParams(p[pass], meta(), effect, 0);
        }
        const int wanted = std::clamp(int(std::lround(effectFloat(effect, "radius"))), 1, 8);
        std::vector<PostTarget> levels;
        int w = std::max(input.width / 2, 1), h = std::max(input.height / 2, 1);
        for (int i = 0; i < wanted && (i == 0 || (w >= 2 && h >= 2)); ++i) {
            levels.push_back(ctx.pool->acquire(w, h));
            w = std::max(w / 2, 1);
            h = std::max(h / 2, 1);
        }
        drawPostPass(ctx, p[0], input, levels[0], 0);
        for (size_t i = 1; i < levels.size(); ++i)
            drawPostPass(ctx, p[1], levels[i - 1], levels[i], 1);
        // Upsample: each level gets the tent-filtered level below it added (Jimenez 2014).
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        for (size_t i = levels.size() - 1; i > 0; --i)
            drawPostPass(ctx, p[2], levels[i], levels[i - 1], 2);
        glDisable(GL_BLEND);
        drawPostPass(ctx, p[3], input, output, 3, int(levels.size()), levels[0].texture);
        for (const PostTarget& t : levels)
            ctx.pool->release(t);
    }

private:
    ShaderProgram m_programs[4]; ///< one per pass (POST_PASS)
};

} // namespace

std::unique_ptr<PostEffect> makeBloomEffect() {
    return std::make_unique<BloomEffect>();
}

} // namespace velvet::render
