#include "render/post_chain.h"

#include "core/post_effects.h"
#include "render/gbuffer_layout.h"
#include "render/post_effect.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <epoxy/gl.h>
#include <glm/matrix.hpp>
#include <map>

namespace velvet::render {
namespace {

/// Mirrors PostFrame in post_common.glsl (std140).
struct PostFrameBlock {
    glm::mat4 viewProj, invViewProj, prevViewProj, invProj;
    glm::vec4 viewport;
    glm::vec4 misc;
};

std::string pointwiseFile(std::string_view type) {
    return type == "tonemap" ? "post_tonemap_curve.frag" : "post_" + std::string(type) + ".frag";
}

/// One pass of the plan: a fused group of pointwise effects, or one effect with its own class.
struct Step {
    std::vector<const EffectInstance*> fused;
    const EffectInstance* single = nullptr;
    bool displayToneMap = false; ///< a tone map drawn by the OCIO display transform
    std::string name() const {
        if (single)
            return single->type + (displayToneMap ? " (display)" : "");
        std::string n;
        for (const EffectInstance* e : fused)
            n += (n.empty() ? "" : "+") + e->type;
        return n;
    }
};

GLuint makeTexture(GLenum format, const Image& img, int channels) {
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, format, img.width, img.height);
    std::vector<float> rows(size_t(img.width) * img.height * channels, 0.0f);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float* src = img.at(x, y);
            float* dst = rows.data() + (size_t(img.height - 1 - y) * img.width + x) * channels;
            for (int c = 0; c < channels; ++c)
                dst[c] = c < img.channels ? src[c] : (c == 3 ? 1.0f : src[0]);
        }
    const GLenum layout = channels == 4 ? GL_RGBA : channels == 2 ? GL_RG : GL_RED;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glTextureSubImage2D(tex, 0, 0, 0, img.width, img.height, layout, GL_FLOAT, rows.data());
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return tex;
}

} // namespace

struct PostChainRenderer::Impl {
    PostTargetPool pool;
    PostContext ctx;
    std::map<std::string, std::unique_ptr<PostEffect>> effects;
    std::map<std::string, std::unique_ptr<ShaderProgram>> fusedPrograms;
    int compiles = 0;
    GLuint ubo = 0, vao = 0, sampler = 0;
    std::vector<PostTarget> held; ///< targets owned by the last run until endFrame()
    int lastSteps = 0;
    bool profiling = false;
    std::vector<PostStepTiming> timings;

    ~Impl() {
        if (ubo)
            glDeleteBuffers(1, &ubo);
        if (vao)
            glDeleteVertexArrays(1, &vao);
        if (sampler)
            glDeleteSamplers(1, &sampler);
    }

    void init() {
        if (ubo)
            return;
        glCreateBuffers(1, &ubo);
        glNamedBufferStorage(ubo, sizeof(PostFrameBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
        glCreateVertexArrays(1, &vao);
        // The lit HDR target is nearest-filtered; post passes read through this sampler.
        glCreateSamplers(1, &sampler);
        glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glSamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glSamplerParameteri(sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        ctx.pool = &pool;
        ctx.vao = vao;
        ctx.compileCount = &compiles;
    }

    PostEffect* effect(const std::string& type, std::string* error) {
        if (auto it = effects.find(type); it != effects.end())
            return it->second.get();
        if (type == "depth_of_field" && !effect("gaussian_blur", error))
            return nullptr; // DoF borrows the blur
        std::unique_ptr<PostEffect> e;
        if (type == "bloom")
            e = makeBloomEffect();
        else if (type == "gaussian_blur")
            e = makeGaussianBlurEffect();
        else if (type == "depth_of_field")
            e = makeDepthOfFieldEffect();
        else if (type == "paintbrush")
            e = makePaintbrushEffect();
        else
            e = makeSinglePassEffect(type);
        if (!e) {
            if (error)
                *error = "post chain: no renderer for effect \"" + type + "\"";
            return nullptr;
        }
        if (!e->build(ctx, error))
            return nullptr;
        return (effects[type] = std::move(e)).get();
    }

    ShaderProgram* fused(const Step& step, std::string* error) {
        const std::string key = step.name();
        if (auto it = fusedPrograms.find(key); it != fusedPrograms.end())
            return it->second.get();
        // Generated main: include each effect's function once, call them in chain order.
        std::string main = "#version 450 core\n#include \"post_common.glsl\"\n";
        for (const EffectInstance* e : step.fused)
            main += "#include \"" + pointwiseFile(e->type) + "\"\n";
        main += "layout(location = 0) out vec4 outColor;\nvoid main() {\n"
                "    ivec2 px = ivec2(gl_FragCoord.xy);\n"
                "    vec4 c = texelFetch(uInput, px, 0);\n";
        int base = 0;
        for (const EffectInstance* e : step.fused) {
            main += "    c = post_" + e->type + "(c, px, " + std::to_string(base) + ");\n";
            base += int(findPostEffect(e->type)->params.size());
        }
        main += "    outColor = c;\n}\n";
        auto program = std::make_unique<ShaderProgram>();
        if (!buildPostProgram(*program, "post_fused.frag", {{"post_fused.frag", main}}, error,
                              &compiles))
            return nullptr;
        return (fusedPrograms[key] = std::move(program)).get();
    }

    bool runStep(const Step& step, const PostRunInputs& in, const PostTarget& input,
                 const PostTarget& output, std::string* error) {
        if (step.displayToneMap) {
            glBindFramebuffer(GL_FRAMEBUFFER, output.fbo);
            glViewport(0, 0, output.width, output.height);
            if (!in.displayTransform) {
                if (error)
                    *error = "post chain: the \"display\" tone map needs an OpenColorIO config";
                return false;
            }
            return in.displayTransform(input.texture, effectFloat(*step.single, "exposure"), error);
        }
        if (step.single) {
            PostEffect* e = effect(step.single->type, error);
            if (!e)
                return false;
            e->run(ctx, *step.single, input, output);
            return true;
        }
        ShaderProgram* program = fused(step, error);
        if (!program)
            return false;
        int base = 0;
        for (const EffectInstance* e : step.fused) {
            const EffectMeta& meta = *findPostEffect(e->type);
            setEffectParams(program->id(), meta, *e, base);
            base += int(meta.params.size());
        }
        drawPostPass(ctx, program->id(), input, output, 0);
        return true;
    }
};

PostChainRenderer::PostChainRenderer() : m_impl(std::make_unique<Impl>()) {}
PostChainRenderer::~PostChainRenderer() = default;

bool PostChainRenderer::hasEnabledEffects(const PostChain& chain) {
    return std::any_of(chain.effects.begin(), chain.effects.end(),
                       [](const EffectInstance& e) { return e.enabled; });
}

bool PostChainRenderer::run(const PostChain& chain, const PostRunInputs& in, PostRunResult& result,
                            std::string* error) {
    Impl& d = *m_impl;
    d.init();
    endFrame();
    result = {};
    d.timings.clear();

    // The effective list: enabled, known effects; an implicit tone map before the first LDR
    // effect when the chain has none (validation keeps explicit ones in stage order).
    std::vector<const EffectInstance*> list;
    static thread_local EffectInstance implicitToneMap;
    bool hasToneMap = false;
    for (const EffectInstance& e : chain.effects)
        if (e.enabled && findPostEffect(e.type))
            hasToneMap |= e.type == "tonemap";
    for (const EffectInstance& e : chain.effects) {
        const EffectMeta* meta = e.enabled ? findPostEffect(e.type) : nullptr;
        if (!meta)
            continue;
        if (!hasToneMap && meta->stage == PostStage::Ldr) {
            implicitToneMap = makeEffect("tonemap");
            implicitToneMap.params["operator"] = {float(in.implicitToneMapper)};
            list.push_back(&implicitToneMap);
            hasToneMap = true;
        }
        list.push_back(&e);
    }
    const float displayOp = 6.0f; // "display" in the operator choice list
    std::vector<Step> steps;
    for (const EffectInstance* e : list) {
        const EffectMeta& meta = *findPostEffect(e->type);
        const bool display = e->type == "tonemap" &&
                             (in.forceDisplayTransform || effectFloat(*e, "operator") == displayOp);
        if (meta.pointwise && !display) {
            int slots = 0;
            if (!steps.empty() && !steps.back().fused.empty())
                for (const EffectInstance* f : steps.back().fused)
                    slots += int(findPostEffect(f->type)->params.size());
            if (!steps.empty() && !steps.back().fused.empty() &&
                slots + int(meta.params.size()) <= kPostMaxSlots)
                steps.back().fused.push_back(e);
            else
                steps.push_back(Step{{e}, nullptr, false});
        } else {
            steps.push_back(Step{{}, e, display});
        }
    }
    d.lastSteps = int(steps.size());

    PostFrameBlock block{};
    block.viewProj = in.viewProj;
    block.invViewProj = glm::inverse(in.viewProj);
    block.prevViewProj = in.prevViewProj;
    block.invProj = glm::inverse(in.proj);
    block.viewport = glm::vec4(float(in.width), float(in.height), 1.0f / float(in.width),
                               1.0f / float(in.height));
    block.misc = glm::vec4(in.time, std::exp2(in.exposureEv), 0.0f, 0.0f);
    glNamedBufferSubData(d.ubo, 0, sizeof(block), &block);
    glBindBufferBase(GL_UNIFORM_BUFFER, kPostFrameUbo, d.ubo);
    glBindSampler(kPostInputUnit, d.sampler);
    glBindSampler(kPostAuxUnit, d.sampler);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    d.ctx.width = in.width;
    d.ctx.height = in.height;

    PostTarget current{in.hdrTexture, 0, in.width, in.height};
    bool currentPooled = false;
    bool ok = true;
    for (size_t i = 0; i < steps.size() && ok; ++i) {
        const bool last = i + 1 == steps.size();
        const PostTarget out = last && hasToneMap ? PostTarget{0, in.finalFbo, in.width, in.height}
                                                  : d.pool.acquire(in.width, in.height);
        const auto start = std::chrono::steady_clock::now();
        if (d.profiling)
            glFinish();
        ok = d.runStep(steps[i], in, current, out, error);
        if (d.profiling) {
            glFinish();
            d.timings.push_back({steps[i].name(), std::chrono::duration<double, std::milli>(
                                                      std::chrono::steady_clock::now() - start)
                                                      .count()});
        }
        if (currentPooled)
            d.pool.release(current);
        current = out;
        currentPooled = out.texture != 0;
    }
    glBindSampler(kPostInputUnit, 0);
    glBindSampler(kPostAuxUnit, 0);
    glBindTextureUnit(kPostInputUnit, 0);
    glBindTextureUnit(kPostAuxUnit, 0);
    glUseProgram(0);
    glBindVertexArray(0);
    if (currentPooled)
        d.held.push_back(current);
    if (!ok)
        return false;
    result.displayEncoded = hasToneMap && !steps.empty();
    result.hdrTexture = result.displayEncoded ? 0 : current.texture;
    return true;
}

void PostChainRenderer::endFrame() {
    Impl& d = *m_impl;
    for (const PostTarget& t : d.held)
        d.pool.release(t);
    d.held.clear();
    d.pool.trim();
}

bool PostChainRenderer::apply(const PostChain& chain, const PostTestInput& input, Image& output,
                              std::string* error) {
    Impl& d = *m_impl;
    d.init();
    const int w = input.color.width, h = input.color.height;
    if (w <= 0 || h <= 0) {
        if (error)
            *error = "PostChainRenderer::apply: empty input";
        return false;
    }
    GLint previousFbo = 0, viewport[4] = {};
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previousFbo);
    glGetIntegerv(GL_VIEWPORT, viewport);

    const GLuint color = makeTexture(GL_RGBA32F, input.color, 4);
    Image depth = input.depth;
    if (depth.width != w || depth.height != h) {
        depth = Image(w, h, 1);
        std::fill(depth.pixels.begin(), depth.pixels.end(), 1.0f);
    }
    Image normals(w, h, 2);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            glm::vec3 n(0, 0, 1);
            if (input.normals.width == w && input.normals.height == h)
                n = glm::vec3(input.normals.at(x, y)[0], input.normals.at(x, y)[1],
                              input.normals.at(x, y)[2]);
            const glm::uvec2 q = octEncodeUnorm16(glm::normalize(n));
            normals.at(x, y)[0] = float(q.x) / 65535.0f;
            normals.at(x, y)[1] = float(q.y) / 65535.0f;
        }
    const GLuint depthTex = makeTexture(GL_R32F, depth, 1);
    const GLuint normalTex = makeTexture(GL_RG32F, normals, 2);
    int depthUnit = 0, normalUnit = 0;
    for (size_t i = 0; i < gbufferAttachments().size(); ++i) {
        if (gbufferAttachments()[i].define == "GBUFFER_DEPTH")
            depthUnit = int(i);
        if (gbufferAttachments()[i].define == "GBUFFER_NORMAL")
            normalUnit = int(i);
    }
    glBindTextureUnit(GLuint(depthUnit), depthTex);
    glBindTextureUnit(GLuint(normalUnit), normalTex);

    GLuint outTex = 0, outFbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &outTex);
    glTextureStorage2D(outTex, 1, GL_RGBA32F, w, h);
    glCreateFramebuffers(1, &outFbo);
    glNamedFramebufferTexture(outFbo, GL_COLOR_ATTACHMENT0, outTex, 0);

    PostRunInputs in;
    in.hdrTexture = color;
    in.width = w;
    in.height = h;
    in.viewProj = input.viewProj;
    in.prevViewProj = input.prevViewProj;
    in.proj = input.proj;
    in.time = input.time;
    in.finalFbo = outFbo;
    PostRunResult result;
    const bool ok = run(chain, in, result, error);
    if (ok) {
        const GLuint tex = result.displayEncoded ? outTex : result.hdrTexture;
        std::vector<float> rows(size_t(w) * h * 4);
        glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, GLsizei(rows.size() * sizeof(float)),
                          rows.data());
        output = Image(w, h, 4);
        for (int y = 0; y < h; ++y)
            std::copy_n(rows.data() + size_t(h - 1 - y) * w * 4, size_t(w) * 4,
                        output.pixels.data() + size_t(y) * w * 4);
    }
    endFrame();
    glBindTextureUnit(GLuint(depthUnit), 0);
    glBindTextureUnit(GLuint(normalUnit), 0);
    glDeleteTextures(1, &color);
    glDeleteTextures(1, &depthTex);
    glDeleteTextures(1, &normalTex);
    glDeleteTextures(1, &outTex);
    glDeleteFramebuffers(1, &outFbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(previousFbo));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    return ok;
}

int PostChainRenderer::compileCount() const {
    return m_impl->compiles;
}
int PostChainRenderer::textureAllocations() const {
    return m_impl->pool.allocationCount();
}
int PostChainRenderer::pooledTextures() const {
    return m_impl->pool.size();
}
int PostChainRenderer::lastStepCount() const {
    return m_impl->lastSteps;
}
void PostChainRenderer::setProfiling(bool on) {
    m_impl->profiling = on;
}
const std::vector<PostStepTiming>& PostChainRenderer::lastTimings() const {
    return m_impl->timings;
}

} // namespace velvet::render
