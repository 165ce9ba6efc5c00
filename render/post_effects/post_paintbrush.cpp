// Paintbrush: the curl-noise pre-pass at half resolution (seed 004 found computing it once per
// pixel and sampling it in the paint pass noticeably faster than one pass), then the strokes.
#include "render/post_effect.h"

#include <algorithm>

namespace velvet::render {
namespace {

/// Paintbrush (seed 004): post_paintbrush.frag as two programs, POST_PASS 0 the half-resolution
/// curl field, 1 the strokes reading it on kPostAuxUnit; uniforms: the parameters at slot 0.
class PaintbrushEffect final : public PostEffect {
public:
    PaintbrushEffect() : PostEffect("paintbrush") {}

    std::vector<PostPassInfo> passes() const override {
        return {{"curl-noise field", "post_paintbrush.frag", 2},
                {"strokes", "post_paintbrush.frag", 1}};
    }

    bool build(PostContext& ctx, std::string* error) override {
        return buildPostProgram(m_programs[0], "post_paintbrush.frag", {}, error, ctx.compileCount,
                                0) &&
               buildPostProgram(m_programs[1], "post_paintbrush.frag", {}, error, ctx.compileCount,
                                1);
    }

    void run(PostContext& ctx, const EffectInstance& effect, const PostTarget& input,
             const PostTarget& output) override {
        for (ShaderProgram& program : m_programs)
            setEffectParams(program.id(), meta(), effect, 0);
        const PostTarget curl =
            ctx.pool->acquire(std::max(input.width / 2, 1), std::max(input.height / 2, 1));
        drawPostPass(ctx, m_programs[0].id(), input, curl, 0);
        drawPostPass(ctx, m_programs[1].id(), input, output, 1, 0, curl.texture);
        ctx.pool->release(curl);
    }

private:
    ShaderProgram m_programs[2]; ///< curl pre-pass, strokes
};

} // namespace

std::unique_ptr<PostEffect> makePaintbrushEffect() {
    return std::make_unique<PaintbrushEffect>();
}

} // namespace velvet::render
