#include "render/post_effect.h"

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
    std::vector<std::string> defines;
    if (pass >= 0)
        defines.push_back("POST_PASS " + std::to_string(pass));
    if (!program.build("fullscreen.vert", fragment, defines, sources, error))
        return false;
    if (compileCount)
        ++*compileCount;
    return true;
}

} // namespace velvet::render
