#pragma once
/// @file post_plan.h
/// Render-private, no GL: the plan of a post chain, i.e. which passes a run draws. A pure
/// function of the chain (core/post_chain.h) and two frame settings, decided from the catalogue's
/// metadata (core/post_effects.h) alone, so it is tested without a GL context
/// (tests/render/test_render_post_plan.cpp) and cached by PostChainRenderer until the chain or
/// the settings change.
///
/// The rules (docs/post-effects.md, "How the chain runs"):
/// - disabled effects and types missing from the catalogue are skipped;
/// - a chain with LDR effects but no enabled "tonemap" gets an implicit one, with the frame's
///   tone curve, right before its first LDR effect;
/// - consecutive pointwise effects (EffectMeta::pointwise) share one fused pass while their
///   parameter slots fit in kPostMaxSlots; every other effect is a step of its own;
/// - a tone map with the "display" operator, or any tone map when the frame's OCIO view tone maps
///   itself, is drawn by the OCIO display transform as a step of its own.

#include "core/post_chain.h"

#include <cstddef>
#include <string>
#include <vector>

namespace velvet::render {

/// The frame settings a plan depends on (PostRunInputs carries them).
struct PostPlanOptions {
    /// The "operator" choice of the implicit tone map.
    int implicitToneMapper = 0;
    /// The frame's OCIO view tone maps itself: every tone map is the display transform.
    bool forceDisplayTransform = false;
    bool operator==(const PostPlanOptions&) const = default;
};

/// PostPlanStep::effects entry naming the plan's implicit tone map (PostPlan::implicitToneMap).
inline constexpr int kImplicitToneMap = -1;

/// One pass (or multi-pass effect) of a run.
struct PostPlanStep {
    enum class Kind {
        Fused,          ///< consecutive pointwise effects in one generated pass
        Single,         ///< one effect drawn by its own renderer (post_<type>.frag or a class)
        DisplayToneMap, ///< a tone map drawn by the OCIO display transform
    };
    Kind kind = Kind::Single;
    /// Chain indices, in order (one for Single and DisplayToneMap), or kImplicitToneMap.
    std::vector<int> effects;
    /// vec4 parameter slots the fused pass uses (the sum of its effects' parameter counts).
    int paramSlots = 0;
    /// A fused pass containing the tone curve: it calls displayEncode() and is built per display
    /// encoding.
    bool encodes = false;
    /// Position of a Single step's effect among the effective (enabled, implicit included)
    /// effects: the key of its previous-frame history.
    size_t listIndex = 0;
    /// "tonemap+vignette" for a fused pass, "tonemap (display)" for the display transform.
    std::string name;
    bool operator==(const PostPlanStep&) const = default;
};

struct PostPlan {
    std::vector<PostPlanStep> steps;
    /// The chain tone maps (explicitly or implicitly): the last step writes display values.
    bool toneMaps = false;
    /// The implicit tone map, when a step names kImplicitToneMap (type empty otherwise).
    EffectInstance implicitToneMap;

    /// The instance step entry @p index stands for: chain.effects[index] or implicitToneMap.
    const EffectInstance& effect(const PostChain& chain, int index) const {
        return index == kImplicitToneMap ? implicitToneMap : chain.effects[size_t(index)];
    }
    bool operator==(const PostPlan&) const = default;
};

/// The plan of @p chain under @p options.
PostPlan planPostChain(const PostChain& chain, const PostPlanOptions& options);

/// Whether tone map @p effect is drawn by the OCIO display transform rather than fused as a
/// built-in curve (the "display" operator, or @p forceDisplayTransform).
bool toneMapUsesDisplayTransform(const EffectInstance& effect, bool forceDisplayTransform);

/// The last plan, kept until the chain or the options change (a still chain plans once).
class PostPlanCache {
public:
    const PostPlan& plan(const PostChain& chain, const PostPlanOptions& options);
    /// Plans computed since construction.
    int buildCount() const { return m_builds; }

private:
    bool m_valid = false;
    PostChain m_chain;
    PostPlanOptions m_options;
    PostPlan m_plan;
    int m_builds = 0;
};

} // namespace velvet::render
