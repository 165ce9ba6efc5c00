// Effects that are one fullscreen pass of their own shader (resources/shaders/post_<type>.frag):
// pixelation, motion blur, pointillism, vaporwave, chromatic aberration, sharpen, FXAA. They read
// neighbouring pixels of their input, so they cannot be fused with their neighbours.
#include "render/post_effect.h"

namespace velvet::render {
namespace {

class SinglePassEffect final : public PostEffect {
public:
    explicit SinglePassEffect(const EffectMeta& meta) : m_meta(meta) {}

    bool build(PostContext& ctx, std::string* error) override {
        return buildPostProgram(m_program, "post_" + std::string(m_meta.type) + ".frag", {}, error,
                                ctx.compileCount);
    }

    void run(PostContext& ctx, const EffectInstance& effect, const PostTarget& input,
             const PostTarget& output) override {
        setEffectParams(m_program.id(), m_meta, effect, 0);
        drawPostPass(ctx, m_program.id(), input, output, 0);
    }

private:
    const EffectMeta& m_meta;
    ShaderProgram m_program;
};

} // namespace

std::unique_ptr<PostEffect> makeSinglePassEffect(std::string_view type) {
    const EffectMeta* meta = findPostEffect(type);
    if (!meta)
        return nullptr;
    return std::make_unique<SinglePassEffect>(*meta);
}

} // namespace velvet::render
