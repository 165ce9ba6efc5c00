// The post chain's plan: a pure function of the chain and the catalogue (render/post_plan.h).
#include "render/post_plan.h"

#include "core/post_effects.h"
#include "render/post_effect.h"

#include <algorithm>

namespace velvet::render {
namespace {

constexpr float kDisplayOperator = 6.0f; ///< "display" in the tonemap effect's operator choices

int slotCount(const EffectInstance& effect) {
    const EffectMeta* meta = findPostEffect(effect.type);
    return meta ? int(meta->params.size()) : 0;
}

} // namespace

bool toneMapUsesDisplayTransform(const EffectInstance& effect, bool forceDisplayTransform) {
    return forceDisplayTransform || effectFloat(effect, "operator") == kDisplayOperator;
}

PostPlan planPostChain(const PostChain& chain, const PostPlanOptions& options) {
    PostPlan plan;
    // The effective list: enabled, known effects; an implicit tone map before the first LDR
    // effect when the chain has none (validation keeps explicit ones in stage order).
    std::vector<int> list;
    bool hasToneMap = false;
    for (const EffectInstance& e : chain.effects)
        if (e.enabled && findPostEffect(e.type))
            hasToneMap |= e.type == "tonemap";
    for (size_t i = 0; i < chain.effects.size(); ++i) {
        const EffectInstance& e = chain.effects[i];
        const EffectMeta* meta = e.enabled ? findPostEffect(e.type) : nullptr;
        if (!meta)
            continue;
        if (!hasToneMap && meta->stage == PostStage::Ldr) {
            plan.implicitToneMap = makeEffect("tonemap");
            plan.implicitToneMap.params["operator"] = {float(options.implicitToneMapper)};
            list.push_back(kImplicitToneMap);
            hasToneMap = true;
        }
        list.push_back(int(i));
    }
    plan.toneMaps = hasToneMap;

    // Consecutive pointwise effects share a pass while their uniforms fit.
    for (size_t i = 0; i < list.size(); ++i) {
        const EffectInstance& e = plan.effect(chain, list[i]);
        const EffectMeta& meta = *findPostEffect(e.type);
        const bool toneMap = meta.stage == PostStage::ToneMap;
        if (meta.pointwise &&
            !(toneMap && toneMapUsesDisplayTransform(e, options.forceDisplayTransform))) {
            const int slots = slotCount(e);
            PostPlanStep* last = plan.steps.empty() ? nullptr : &plan.steps.back();
            if (last && last->kind == PostPlanStep::Kind::Fused &&
                last->paramSlots + slots <= kPostMaxSlots) {
                last->effects.push_back(list[i]);
                last->paramSlots += slots;
                last->encodes |= toneMap;
                last->name += "+" + e.type;
            } else {
                PostPlanStep step;
                step.kind = PostPlanStep::Kind::Fused;
                step.effects = {list[i]};
                step.paramSlots = slots;
                step.encodes = toneMap;
                step.listIndex = i;
                step.name = e.type;
                plan.steps.push_back(std::move(step));
            }
        } else {
            PostPlanStep step;
            // A tone map that does not fuse is the display transform's step.
            step.kind = toneMap ? PostPlanStep::Kind::DisplayToneMap : PostPlanStep::Kind::Single;
            step.effects = {list[i]};
            step.listIndex = i;
            step.name = e.type + (toneMap ? " (display)" : "");
            plan.steps.push_back(std::move(step));
        }
    }
    return plan;
}

const PostPlan& PostPlanCache::plan(const PostChain& chain, const PostPlanOptions& options) {
    if (!m_valid || options != m_options || chain != m_chain) {
        m_plan = planPostChain(chain, options);
        m_chain = chain;
        m_options = options;
        m_valid = true;
        ++m_builds;
    }
    return m_plan;
}

} // namespace velvet::render
