#include "render/post_chain.h"

#include "core/post_effects.h"
#include "render/display_encoding.h"
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

/// One pass of the plan: a fused group of pointwise effects, or one effect run by its class.
struct Step {
    std::vector<const EffectInstance*> fused;
    std::vector<const FusableEffect*> fusedEffects; ///< the classes of `fused`
    /// The display encoding the fused pass is built with ("" fallback; unused unless one of
    /// fusedEffects displayEncodes()).
    std::string encodingId;
    bool encodes() const {
        return std::any_of(fusedEffects.begin(), fusedEffects.end(),
                           [](const FusableEffect* f) { return f->displayEncodes(); });
    }
    const EffectInstance* single = nullptr;
    PostEffect* singleEffect = nullptr;
    bool displayToneMap = false; ///< a tone map drawn by the OCIO display transform
    size_t listIndex = 0;        ///< position of `single` among the enabled effects
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
    /// A fused pass's program and the effect classes its source was generated from (owned by
    /// `effects`), so a reload can regenerate the same source.
    struct FusedProgram {
        std::unique_ptr<ShaderProgram> program;
        std::vector<const FusableEffect*> effects;
        bool encodes = false;
        std::string encodingId;
    };
    /// The display encoding of the current run (null: the fallback; PostChainRenderer::apply).
    const DisplayEncoding* encoding = nullptr;

    GeneratedSources fusedSources(const std::vector<const FusableEffect*>& effects, bool encodes,
                                  const std::string& encodingId) const {
        GeneratedSources sources{{"post_fused.frag", fusedPassSource(effects)}};
        if (encodes && encoding)
            for (auto& s : encoding->sources(encodingId))
                sources.push_back(std::move(s));
        return sources;
    }
    std::map<std::string, FusedProgram> fusedPrograms;
    int compiles = 0;
    GLuint ubo = 0, vao = 0, sampler = 0;
    std::vector<PostTarget> held; ///< targets owned by the last run until endFrame()
    /// Last frame's input of each effect that reads the previous frame, keyed by its position
    /// among the enabled effects; pooled targets held across frames (valid: written last run).
    struct History {
        PostTarget target;
        bool valid = false;
    };
    std::map<size_t, History> history;
    GLuint copyFbo = 0; ///< reads an arbitrary texture for the history copy
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
        if (copyFbo)
            glDeleteFramebuffers(1, &copyFbo);
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

    /// The effect class of @p type, built (after its dependencies) on first use.
    PostEffect* effect(std::string_view type, std::string* error) {
        if (auto it = effects.find(std::string(type)); it != effects.end())
            return it->second.get();
        std::unique_ptr<PostEffect> e = makePostEffect(type);
        if (!e) {
            if (error)
                *error = "post chain: no renderer for effect \"" + std::string(type) + "\"";
            return nullptr;
        }
        for (std::string_view dependency : e->dependencies())
            if (!effect(dependency, error))
                return nullptr;
        if (!e->build(ctx, error))
            return nullptr;
        return (effects[std::string(type)] = std::move(e)).get();
    }

    /// Copies @p input into the history target of the effect at @p listIndex for next frame.
    void keepHistory(size_t listIndex, const PostTarget& input) {
        History& h = history[listIndex];
        if (h.target.texture &&
            (h.target.width != input.width || h.target.height != input.height)) {
            pool.release(h.target);
            h = {};
        }
        if (!h.target.texture)
            h.target = pool.acquire(input.width, input.height);
        if (!copyFbo)
            glCreateFramebuffers(1, &copyFbo);
        glNamedFramebufferTexture(copyFbo, GL_COLOR_ATTACHMENT0, input.texture, 0);
        glNamedFramebufferReadBuffer(copyFbo, GL_COLOR_ATTACHMENT0);
        glBlitNamedFramebuffer(copyFbo, h.target.fbo, 0, 0, input.width, input.height, 0, 0,
                               input.width, input.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glNamedFramebufferTexture(copyFbo, GL_COLOR_ATTACHMENT0, 0, 0);
        h.valid = true;
    }

    ShaderProgram* fused(const Step& step, std::string* error) {
        const bool encodes = step.encodes();
        // One program per display encoding for passes that tone map (switching display compiles
        // once per encoding; exposure is a uniform and compiles nothing).
        const std::string key = step.name() + (encodes ? "@" + step.encodingId : "");
        if (auto it = fusedPrograms.find(key); it != fusedPrograms.end())
            return it->second.program.get();
        auto program = std::make_unique<ShaderProgram>();
        if (!buildPostProgram(*program, "post_fused.frag",
                              fusedSources(step.fusedEffects, encodes, step.encodingId), error,
                              &compiles))
            return nullptr;
        if (encodes && encoding)
            encoding->setUniforms(program->id(), step.encodingId);
        FusedProgram& f = fusedPrograms[key];
        f.program = std::move(program);
        f.effects = step.fusedEffects;
        f.encodes = encodes;
        f.encodingId = step.encodingId;
        return f.program.get();
    }

    /// Rebuilds every effect and fused program built so far; failures keep their last good
    /// program and add their message.
    bool reload(std::string* error) {
        std::string errors;
        const auto collect = [&](bool ok, const std::string& message) {
            if (!ok)
                errors += (errors.empty() ? "" : "\n") + message;
        };
        for (auto& [type, e] : effects) {
            std::string message;
            collect(e->build(ctx, &message), message);
        }
        for (auto& [key, f] : fusedPrograms) {
            std::string message;
            const bool ok = buildPostProgram(*f.program, "post_fused.frag",
                                             fusedSources(f.effects, f.encodes, f.encodingId),
                                             &message, &compiles);
            if (ok && f.encodes && encoding)
                encoding->setUniforms(f.program->id(), f.encodingId);
            collect(ok, message);
        }
        if (!errors.empty() && error)
            *error = errors;
        return errors.empty();
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
            const bool reads = step.singleEffect->readsPreviousFrame(*step.single);
            ctx.previousFrame = {};
            if (reads)
                if (auto it = history.find(step.listIndex);
                    it != history.end() && it->second.valid &&
                    it->second.target.width == input.width &&
                    it->second.target.height == input.height)
                    ctx.previousFrame = it->second.target;
            step.singleEffect->run(ctx, *step.single, input, output);
            ctx.previousFrame = {};
            if (reads)
                keepHistory(step.listIndex, input);
            return true;
        }
        ShaderProgram* program = fused(step, error);
        if (!program)
            return false;
        int base = 0;
        for (size_t k = 0; k < step.fused.size(); ++k) {
            step.fusedEffects[k]->upload(program->id(), *step.fused[k], base);
            base += step.fusedEffects[k]->slotCount();
        }
        const bool encodes = step.encodes() && encoding;
        if (encodes)
            encoding->bindLuts();
        drawPostPass(ctx, program->id(), input, output, 0);
        if (encodes)
            encoding->unbindLuts();
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
    d.encoding = in.encoding;
    const std::string encodingId = in.encoding ? in.encoding->cacheId() : std::string();

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
    // The plan: consecutive fusable effects share a pass while their uniforms fit.
    std::vector<Step> steps;
    std::vector<size_t> readers; ///< list positions that read the previous frame this run
    for (size_t i = 0; i < list.size(); ++i) {
        const EffectInstance* e = list[i];
        PostEffect* renderer = d.effect(e->type, error);
        if (!renderer)
            return false;
        const FusableEffect* fusable = renderer->fusable();
        if (fusable && fusable->fuses(*e, in.forceDisplayTransform)) {
            int slots = 0;
            if (!steps.empty() && !steps.back().fused.empty())
                for (const FusableEffect* f : steps.back().fusedEffects)
                    slots += f->slotCount();
            if (!steps.empty() && !steps.back().fused.empty() &&
                slots + fusable->slotCount() <= kPostMaxSlots) {
                steps.back().fused.push_back(e);
                steps.back().fusedEffects.push_back(fusable);
            } else {
                Step step;
                step.fused = {e};
                step.fusedEffects = {fusable};
                step.encodingId = encodingId;
                steps.push_back(std::move(step));
            }
        } else {
            Step step;
            step.single = e;
            step.singleEffect = renderer;
            step.displayToneMap = fusable != nullptr; // a fusable effect that does not fuse
            step.listIndex = i;
            steps.push_back(std::move(step));
            if (renderer->readsPreviousFrame(*e))
                readers.push_back(i);
        }
    }
    d.lastSteps = int(steps.size());
    // History no effect of this chain reads goes back to the pool.
    for (auto it = d.history.begin(); it != d.history.end();)
        if (std::find(readers.begin(), readers.end(), it->first) == readers.end()) {
            d.pool.release(it->second.target);
            it = d.history.erase(it);
        } else {
            ++it;
        }

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

bool PostChainRenderer::reload(std::string* error) {
    return m_impl->reload(error);
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
    in.encoding = input.encoding;
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
