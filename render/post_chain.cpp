#include "render/post_chain.h"

#include "core/post_effects.h"
#include "render/display_encoding.h"
#include "render/post_effect.h"
#include "render/post_plan.h"
#include "render/render_interface.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <epoxy/gl.h>
#include <glm/matrix.hpp>
#include <map>
#include <optional>

namespace velvet::render {
namespace {} // namespace

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
        int toneMapOperator = -1;
    };
    /// The display encoding of the current run (null: the hand-written sRGB fallback).
    const DisplayEncoding* encoding = nullptr;

    GeneratedSources fusedSources(const std::vector<const FusableEffect*>& effects, bool encodes,
                                  const std::string& encodingId, int toneMapOperator) const {
        std::string main = fusedPassSource(effects);
        if (toneMapOperator >= 0) // post_tonemap.glsl's operator compiled in
            main.insert(main.find('\n') + 1,
                        "#define TONEMAP_OPERATOR_FIXED " + std::to_string(toneMapOperator) + "\n");
        GeneratedSources sources{{"post_fused.frag", std::move(main)}};
        if (encodes && encoding)
            for (auto& s : encoding->sources(encodingId))
                sources.push_back(std::move(s));
        return sources;
    }
    std::map<std::string, FusedProgram> fusedPrograms;
    PostPlanCache plans; ///< the chain's plan, kept until the chain changes
    int compiles = 0;
    bool specialiseOperators = true; ///< PostChainRenderer::setSpecialiseOperators
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

    /// The program of fused step @p step, whose effects' classes are @p classes.
    /// @p toneMapOperator: the operator every tone map of the step uses, compiled in
    /// (TONEMAP_OPERATOR_FIXED), or -1.
    ShaderProgram* fused(const PostPlanStep& step, const std::vector<const FusableEffect*>& classes,
                         const std::string& encodingId, int toneMapOperator, std::string* error) {
        const bool encodes = step.encodes;
        // One program per display encoding for passes that tone map (switching display compiles
        // once per encoding; exposure is a uniform and compiles nothing), and per tone-map
        // operator: llvmpipe runs every operator of a run-time switch, so an operator is a choice
        // like a BRDF term (switching compiles once; built programs are kept).
        const std::string key = step.name + (encodes ? "@" + encodingId : "") +
                                (toneMapOperator >= 0 ? "#" + std::to_string(toneMapOperator) : "");
        if (auto it = fusedPrograms.find(key); it != fusedPrograms.end())
            return it->second.program.get();
        auto program = std::make_unique<ShaderProgram>();
        if (!buildPostProgram(*program, "post_fused.frag",
                              fusedSources(classes, encodes, encodingId, toneMapOperator), error,
                              &compiles))
            return nullptr;
        if (encodes && encoding)
            encoding->setUniforms(program->id(), encodingId);
        FusedProgram& f = fusedPrograms[key];
        f.program = std::move(program);
        f.effects = classes;
        f.encodes = encodes;
        f.encodingId = encodingId;
        f.toneMapOperator = toneMapOperator;
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
            const bool ok = buildPostProgram(
                *f.program, "post_fused.frag",
                fusedSources(f.effects, f.encodes, f.encodingId, f.toneMapOperator), &message,
                &compiles);
            if (ok && f.encodes && encoding)
                encoding->setUniforms(f.program->id(), f.encodingId);
            collect(ok, message);
        }
        if (!errors.empty() && error)
            *error = errors;
        return errors.empty();
    }

    /// The tone-map operator of fused @p step when its tone maps agree (the usual one tone
    /// map), rounded as post_tonemap.glsl rounds it; -1 when they differ or specialising is off.
    int fixedOperator(const PostChain& chain, const PostPlan& plan,
                      const PostPlanStep& step) const {
        std::optional<int> toneMapOperator;
        bool agree = specialiseOperators;
        for (int index : step.effects) {
            const EffectInstance& e = plan.effect(chain, index);
            if (e.type != "tonemap")
                continue;
            const int op = int(effectFloat(e, "operator") + 0.5f);
            agree = agree && op >= 0 && (!toneMapOperator || *toneMapOperator == op);
            toneMapOperator = op;
        }
        return agree && toneMapOperator ? *toneMapOperator : -1;
    }

    /// The fusable classes of @p step's effects (built on first use); false + message.
    bool fusedClasses(const PostChain& chain, const PostPlan& plan, const PostPlanStep& step,
                      std::vector<const FusableEffect*>& classes, std::string* error) {
        classes.clear();
        for (int index : step.effects) {
            const std::string& type = plan.effect(chain, index).type;
            PostEffect* renderer = effect(type, error);
            if (!renderer)
                return false;
            if (!renderer->fusable()) {
                if (error)
                    *error = "post chain: \"" + type +
                             "\" is pointwise in the catalogue but its renderer cannot be fused";
                return false;
            }
            classes.push_back(renderer->fusable());
        }
        return true;
    }

    /// The PostFrame block of @p in, bound at kPostFrameUbo.
    void uploadFrameBlock(const PostRunInputs& in) {
        PostFrameBlock block{};
        block.viewProj = in.viewProj;
        block.invViewProj = glm::inverse(in.viewProj);
        block.prevViewProj = in.prevViewProj;
        block.invProj = glm::inverse(in.proj);
        block.viewport = glm::vec4(float(in.width), float(in.height), 1.0f / float(in.width),
                                   1.0f / float(in.height));
        block.misc = glm::vec4(in.time, std::exp2(in.exposureEv), 0.0f, 0.0f);
        glNamedBufferSubData(ubo, 0, sizeof(block), &block);
        glBindBufferBase(GL_UNIFORM_BUFFER, kPostFrameUbo, ubo);
    }

    bool runStep(const PostChain& chain, const PostPlan& plan, const PostPlanStep& step,
                 const PostRunInputs& in, const std::string& encodingId, const PostTarget& input,
                 const PostTarget& output, std::string* error) {
        const EffectInstance& first = plan.effect(chain, step.effects.front());
        if (step.kind == PostPlanStep::Kind::DisplayToneMap) {
            glBindFramebuffer(GL_FRAMEBUFFER, output.fbo);
            glViewport(0, 0, output.width, output.height);
            if (!in.displayTransform) {
                if (error)
                    *error = "post chain: the \"display\" tone map needs an OpenColorIO config";
                return false;
            }
            return in.displayTransform(input.texture, effectFloat(first, "exposure"), error);
        }
        if (step.kind == PostPlanStep::Kind::Single) {
            PostEffect* renderer = effect(first.type, error);
            if (!renderer)
                return false;
            const bool reads = renderer->readsPreviousFrame(first);
            ctx.previousFrame = {};
            if (reads)
                if (auto it = history.find(step.listIndex);
                    it != history.end() && it->second.valid &&
                    it->second.target.width == input.width &&
                    it->second.target.height == input.height)
                    ctx.previousFrame = it->second.target;
            renderer->run(ctx, first, input, output);
            ctx.previousFrame = {};
            if (reads)
                keepHistory(step.listIndex, input);
            return true;
        }
        std::vector<const FusableEffect*> classes;
        if (!fusedClasses(chain, plan, step, classes, error))
            return false;
        ShaderProgram* program =
            fused(step, classes, encodingId, fixedOperator(chain, plan, step), error);
        if (!program)
            return false;
        int base = 0;
        for (size_t k = 0; k < classes.size(); ++k) {
            classes[k]->upload(program->id(), plan.effect(chain, step.effects[k]), base);
            base += classes[k]->slotCount();
        }
        const bool encodes = step.encodes && encoding;
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

    const PostPlan& plan = d.plans.plan(chain, {in.implicitToneMapper, in.forceDisplayTransform});
    const std::vector<PostPlanStep>& steps = plan.steps;
    const bool hasToneMap = plan.toneMaps;
    // Build every renderer the plan needs before drawing (a missing one fails the run early).
    std::vector<size_t> readers; ///< list positions that read the previous frame this run
    for (const PostPlanStep& step : steps)
        for (int index : step.effects) {
            const EffectInstance& e = plan.effect(chain, index);
            PostEffect* renderer = d.effect(e.type, error);
            if (!renderer)
                return false;
            if (step.kind == PostPlanStep::Kind::Single && renderer->readsPreviousFrame(e))
                readers.push_back(step.listIndex);
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

    d.uploadFrameBlock(in);
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
        ok = d.runStep(chain, plan, steps[i], in, encodingId, current, out, error);
        if (d.profiling) {
            glFinish();
            d.timings.push_back({steps[i].name, std::chrono::duration<double, std::milli>(
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

bool PostChainRenderer::inlineSource(const PostChain& chain, const PostRunInputs& in,
                                     InlinePost& out) {
    Impl& d = *m_impl;
    d.init();
    const PostPlan& plan = d.plans.plan(chain, {in.implicitToneMapper, in.forceDisplayTransform});
    if (plan.steps.size() != 1 || plan.steps[0].kind != PostPlanStep::Kind::Fused ||
        !plan.steps[0].encodes)
        return false;
    const PostPlanStep& step = plan.steps[0];
    std::vector<const FusableEffect*> classes;
    if (!d.fusedClasses(chain, plan, step, classes, nullptr))
        return false;
    // fusedPassSource's main as a function of the lit colour: the same effect functions at the
    // same parameter slots, the same operator compiled in.
    const int op = d.fixedOperator(chain, plan, step);
    std::string text = "#define POST_INLINE\n";
    if (op >= 0)
        text += "#define TONEMAP_OPERATOR_FIXED " + std::to_string(op) + "\n";
    text += "#include \"post_common.glsl\"\n";
    std::vector<std::string> included;
    for (const FusableEffect* e : classes)
        if (std::find(included.begin(), included.end(), e->glslFile()) == included.end()) {
            included.push_back(e->glslFile());
            text += "#include \"" + e->glslFile() + "\"\n";
        }
    text += "vec4 postInline(vec4 c, ivec2 px) {\n";
    int base = 0;
    for (const FusableEffect* e : classes) {
        text += "    c = " + e->glslFunction() + "(c, px, " + std::to_string(base) + ");\n";
        base += e->slotCount();
    }
    text += "    return c;\n}\n";
    const std::string encodingId = in.encoding ? in.encoding->cacheId() : std::string();
    out.key = "chain:" + step.name + "@" + encodingId + "#" + std::to_string(op);
    out.sources = {{"inline_post.glsl", std::move(text)}, {"post_params.glsl", postParamsGlsl()}};
    for (auto& s : in.encoding ? in.encoding->sources(encodingId) : DisplayEncoding().sources(""))
        out.sources.push_back(std::move(s));
    return true;
}

void PostChainRenderer::bindInline(const PostChain& chain, const PostRunInputs& in,
                                   const std::vector<unsigned>& programs) {
    Impl& d = *m_impl;
    d.init();
    endFrame(); // no run this frame: last run's targets go back to the pool
    const PostPlan& plan = d.plans.plan(chain, {in.implicitToneMapper, in.forceDisplayTransform});
    std::vector<const FusableEffect*> classes;
    if (plan.steps.size() != 1 || !d.fusedClasses(chain, plan, plan.steps[0], classes, nullptr))
        return;
    d.uploadFrameBlock(in);
    for (unsigned program : programs) {
        int base = 0;
        for (size_t k = 0; k < classes.size(); ++k) {
            classes[k]->upload(program, plan.effect(chain, plan.steps[0].effects[k]), base);
            base += classes[k]->slotCount();
        }
        if (in.encoding)
            in.encoding->setUniforms(program, in.encoding->cacheId());
    }
    if (in.encoding)
        in.encoding->bindLuts();
    d.encoding = in.encoding;
    d.lastSteps = 0;
}

void PostChainRenderer::unbindInline() {
    if (m_impl->encoding)
        m_impl->encoding->unbindLuts();
}

void PostChainRenderer::setSpecialiseOperators(bool on) {
    m_impl->specialiseOperators = on;
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
