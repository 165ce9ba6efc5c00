#include "render/post_effect.h"

#include "render/display_encoding.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <epoxy/gl.h>
#include <sstream>

namespace velvet::render {
namespace {

std::string upper(std::string_view s) {
    std::string out;
    for (char c : s)
        out += c == '-' ? '_' : char(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

} // namespace

std::string postParamsGlsl() {
    std::ostringstream s;
    s << "// Generated from core/post_effects.cpp and render/post_effect.h; do not edit.\n"
      << "#define POST_INPUT_UNIT " << kPostInputUnit << "\n"
      << "#define POST_AUX_UNIT " << kPostAuxUnit << "\n"
      << "#define POST_AUX2_UNIT " << kPostAux2Unit << "\n"
      << "#define POST_FRAME_UBO " << kPostFrameUbo << "\n"
      << "#define POST_MAX_SLOTS " << kPostMaxSlots << "\n"
      << "#define POST_PASS_LOCATION " << kPostPassLocation << "\n"
      << "#define POST_TEXEL_LOCATION " << kPostTexelLocation << "\n"
      << "#define POST_WEIGHTS_LOCATION " << kPostWeightsLocation << "\n"
      << "#define POST_MAX_TAPS " << kPostMaxTaps << "\n";
    for (const EffectMeta& m : postEffectCatalogue()) {
        const std::string prefix = upper(m.type) + "_";
        for (size_t k = 0; k < m.params.size(); ++k) {
            const ParamMeta& p = m.params[k];
            s << "#define " << prefix << upper(p.id) << " " << k << "\n";
            for (size_t c = 0; c < p.choices.size(); ++c)
                s << "#define " << prefix << upper(p.id) << "_" << upper(p.choices[c]) << " " << c
                  << "\n";
        }
    }
    return s.str();
}

std::vector<float> gaussianWeights(float sigma, int radius) {
    radius = std::clamp(radius, 0, kPostMaxTaps - 1);
    sigma = std::max(sigma, 1e-3f);
    std::vector<float> w(size_t(radius) + 1);
    const double norm = 1.0 / std::sqrt(2.0 * M_PI * double(sigma) * sigma);
    double sum = 0.0;
    for (int i = 0; i <= radius; ++i) {
        w[size_t(i)] = float(norm * std::exp(-double(i) * i / (2.0 * double(sigma) * sigma)));
        sum += (i == 0 ? 1.0 : 2.0) * w[size_t(i)];
    }
    // The truncated kernel loses the tails; renormalise so a flat image stays flat.
    for (float& x : w)
        x = float(x / sum);
    return w;
}

PostTargetPool::~PostTargetPool() {
    for (Entry& e : m_entries) {
        glDeleteFramebuffers(1, &e.target.fbo);
        glDeleteTextures(1, &e.target.texture);
    }
}

PostTarget PostTargetPool::acquire(int width, int height) {
    for (Entry& e : m_entries)
        if (!e.inUse && e.target.width == width && e.target.height == height) {
            e.inUse = true;
            e.idleFrames = 0;
            return e.target;
        }
    Entry e;
    e.target.width = width;
    e.target.height = height;
    glCreateTextures(GL_TEXTURE_2D, 1, &e.target.texture);
    glTextureStorage2D(e.target.texture, 1, GL_RGBA16F, width, height);
    glTextureParameteri(e.target.texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(e.target.texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(e.target.texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(e.target.texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glCreateFramebuffers(1, &e.target.fbo);
    glNamedFramebufferTexture(e.target.fbo, GL_COLOR_ATTACHMENT0, e.target.texture, 0);
    glNamedFramebufferDrawBuffer(e.target.fbo, GL_COLOR_ATTACHMENT0);
    e.inUse = true;
    ++m_allocations;
    m_entries.push_back(e);
    return e.target;
}

void PostTargetPool::release(const PostTarget& target) {
    for (Entry& e : m_entries)
        if (e.target.texture == target.texture)
            e.inUse = false;
}

void PostTargetPool::trim() {
    constexpr int kKeepFrames = 8;
    std::erase_if(m_entries, [](Entry& e) {
        if (e.inUse || ++e.idleFrames <= kKeepFrames)
            return false;
        glDeleteFramebuffers(1, &e.target.fbo);
        glDeleteTextures(1, &e.target.texture);
        return true;
    });
}

void setEffectParams(unsigned program, const EffectMeta& meta, const EffectInstance& effect,
                     int base) {
    float slots[kPostMaxSlots * 4] = {};
    const int n = std::min(int(meta.params.size()), kPostMaxSlots - base);
    for (int k = 0; k < n; ++k) {
        const glm::vec3 v = effectValue(effect, meta.params[size_t(k)]);
        slots[k * 4 + 0] = v.x;
        slots[k * 4 + 1] = v.y;
        slots[k * 4 + 2] = v.z;
    }
    if (n > 0)
        glProgramUniform4fv(program, base, n, slots);
}

void drawPostPass(const PostContext& ctx, unsigned program, const PostTarget& input,
                  const PostTarget& output, int pass, int level, unsigned aux) {
    glBindFramebuffer(GL_FRAMEBUFFER, output.fbo);
    glViewport(0, 0, output.width, output.height);
    glBindTextureUnit(kPostInputUnit, input.texture);
    glBindTextureUnit(kPostAuxUnit, aux);
    glProgramUniform4i(program, kPostPassLocation, pass, level, 0, 0);
    glProgramUniform4f(program, kPostTexelLocation, 1.0f / float(std::max(input.width, 1)),
                       1.0f / float(std::max(input.height, 1)), float(output.width),
                       float(output.height));
    glUseProgram(program);
    glBindVertexArray(ctx.vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

bool buildPostProgram(ShaderProgram& program, const std::string& fragment,
                      const GeneratedSources& extra, std::string* error, int* compileCount,
                      int pass) {
    GeneratedSources sources = extra;
    sources.emplace_back("post_params.glsl", postParamsGlsl());
    if (std::none_of(sources.begin(), sources.end(),
                     [](const auto& s) { return s.first == DisplayEncoding::kInclude; }))
        for (auto& fallback : DisplayEncoding().sources(""))
            sources.push_back(std::move(fallback));
    std::vector<std::string> defines;
    if (pass >= 0)
        defines.push_back("POST_PASS " + std::to_string(pass));
    if (!program.build("fullscreen.vert", fragment, defines, sources, error))
        return false;
    if (compileCount)
        ++*compileCount;
    return true;
}

PostEffect::PostEffect(std::string_view type) : m_meta(findPostEffect(type)) {}

SinglePassEffect::SinglePassEffect(std::string_view type)
    : PostEffect(type), m_shader("post_" + std::string(type) + ".frag") {}

std::vector<PostPassInfo> SinglePassEffect::passes() const {
    return {{meta().label, m_shader, 1}};
}

bool SinglePassEffect::build(PostContext& ctx, std::string* error) {
    return buildPostProgram(m_program, m_shader, {}, error, ctx.compileCount);
}

unsigned SinglePassEffect::bindInputs(PostContext& /*ctx*/, const EffectInstance& /*effect*/,
                                      int& /*level*/) {
    return 0;
}

void SinglePassEffect::run(PostContext& ctx, const EffectInstance& effect, const PostTarget& input,
                           const PostTarget& output) {
    setEffectParams(m_program.id(), meta(), effect, 0);
    int level = 0;
    const unsigned aux = bindInputs(ctx, effect, level);
    drawPostPass(ctx, m_program.id(), input, output, 0, level, aux);
}

FusableEffect::FusableEffect(std::string_view type, std::string glslFile)
    : PostEffect(type),
      m_glslFile(glslFile.empty() ? "post_" + std::string(type) + ".glsl" : std::move(glslFile)) {}

std::vector<PostPassInfo> FusableEffect::passes() const {
    return {{"fused pointwise pass", m_glslFile, 1}};
}

std::string FusableEffect::glslFunction() const {
    return "post_" + std::string(meta().type);
}

void FusableEffect::upload(unsigned program, const EffectInstance& effect, int base) const {
    setEffectParams(program, meta(), effect, base);
}

bool FusableEffect::build(PostContext& ctx, std::string* error) {
    // The chain compiles fused passes; run() compiles the effect alone when used. A reload
    // rebuilds that program only if it exists (the last good one stays on failure).
    if (!m_program.id())
        return true;
    return buildPostProgram(m_program, "post_fused.frag",
                            {{"post_fused.frag", fusedPassSource({this})}}, error,
                            ctx.compileCount);
}

void FusableEffect::run(PostContext& ctx, const EffectInstance& effect, const PostTarget& input,
                        const PostTarget& output) {
    if (!m_program.id() && !buildPostProgram(m_program, "post_fused.frag",
                                             {{"post_fused.frag", fusedPassSource({this})}},
                                             nullptr, ctx.compileCount))
        return; // the same sources compile as part of every fused pass
    upload(m_program.id(), effect, 0);
    drawPostPass(ctx, m_program.id(), input, output, 0);
}

std::string fusedPassSource(const std::vector<const FusableEffect*>& effects) {
    // Include each effect's file once (a chain may repeat an effect), call them in chain order.
    std::string main = "#version 450 core\n#include \"post_common.glsl\"\n";
    std::vector<std::string> included;
    for (const FusableEffect* e : effects)
        if (std::find(included.begin(), included.end(), e->glslFile()) == included.end()) {
            included.push_back(e->glslFile());
            main += "#include \"" + e->glslFile() + "\"\n";
        }
    main += "layout(location = 0) out vec4 outColor;\nvoid main() {\n"
            "    ivec2 px = ivec2(gl_FragCoord.xy);\n"
            "    vec4 c = texelFetch(uInput, px, 0);\n";
    int base = 0;
    for (const FusableEffect* e : effects) {
        main += "    c = " + e->glslFunction() + "(c, px, " + std::to_string(base) + ");\n";
        base += e->slotCount();
    }
    main += "    outColor = c;\n}\n";
    return main;
}

std::unique_ptr<PostEffect> makePostEffect(std::string_view type) {
    const EffectMeta* meta = findPostEffect(type);
    if (!meta)
        return nullptr;
    // Effects with passes or inputs of their own; every other effect is built from its
    // catalogue entry: a pointwise one is a shader function fused with its neighbours
    // (post_<type>.glsl), any other one a single pass of post_<type>.frag.
    using Factory = std::unique_ptr<PostEffect> (*)();
    static constexpr std::pair<std::string_view, Factory> kClasses[] = {
        {"bloom", makeBloomEffect},
        {"motion_blur", makeMotionBlurEffect},
        {"depth_of_field", makeDepthOfFieldEffect},
        {"paintbrush", makePaintbrushEffect},
        {"tonemap", makeToneMapEffect},
        {"gaussian_blur", makeGaussianBlurEffect},
    };
    for (const auto& [name, factory] : kClasses)
        if (name == type)
            return factory();
    if (meta->pointwise)
        return std::make_unique<FusableEffect>(type);
    return std::make_unique<SinglePassEffect>(type);
}

} // namespace velvet::render
