#pragma once
/// @file post_effects.h
/// The post-effect catalogue and the chain operations (DESIGN.md, "Parameters"): every effect
/// type declares its parameters with ParamMeta, the stage it belongs to and what it reads. The
/// renderer, the JSON readers and writers, the schema and the UI are generated from this table.
///
/// Stage order (seed 004, "Post-process Effects"): pre-passes (bloom), HDR effects, paintbrush,
/// tone mapping, LDR effects. Effects of stage Any (blur, pixelation, chromatic aberration) may
/// sit anywhere. A chain without a tone-mapping effect is valid: the renderer's own final pass
/// tone maps (and LDR effects then run after it, on display values).

#include "core/param_meta.h"
#include "core/post_chain.h"

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {

/// Where in the chain an effect runs; the order of the enumerators is the chain's order.
enum class PostStage {
    PrePass, ///< reads the lit image before any HDR effect changes it (bloom)
    Hdr,     ///< scene-linear HDR colour (motion blur, depth of field, toon, grading)
    Paint,   ///< the last HDR effect, after the others (paintbrush, seed 004)
    ToneMap, ///< scene-linear -> display-encoded
    Ldr,     ///< display-encoded colour in [0, 1] (vignette, grain, FXAA)
    Any,     ///< works on either; no order constraint (blur, pixelation, aberration)
};

/// What an effect reads besides its input colour (bit set).
enum PostReads : unsigned {
    kReadsColor = 1u << 0,
    kReadsDepth = 1u << 1,
    kReadsNormals = 1u << 2,
    kReadsPreviousFrame = 1u << 3,
    kReadsCameraMotion = 1u << 4, ///< the previous frame's view-projection
    kReadsTime = 1u << 5,         ///< FrameSettings::time (animated noise)
};

/// One effect type of the catalogue. All strings static.
struct EffectMeta {
    std::string_view type;  ///< id in files, e.g. "bloom"
    std::string_view label; ///< shown to the artist, e.g. "Bloom"
    std::string_view description;
    PostStage stage = PostStage::Hdr;
    unsigned reads = kReadsColor;
    /// Reads its input colour only at its own pixel, so consecutive pointwise effects are fused
    /// into one pass by the renderer.
    bool pointwise = false;
    std::span<const ParamMeta> params;
};

/// Every effect type, in the order a menu lists them.
std::span<const EffectMeta> postEffectCatalogue();
/// The catalogue entry of @p type, or nullptr.
const EffectMeta* findPostEffect(std::string_view type);
/// The parameter @p id of @p meta, or nullptr.
const ParamMeta* findEffectParam(const EffectMeta& meta, std::string_view id);
/// The index of the tonemap effect's operator @p name ("pbr-neutral", "aces", "reinhard",
/// "linear", …) in its "operator" choice, or -1: the renderer maps its built-in curves to the
/// effect's numbering by name through this, never by literal.
int toneMapOperatorIndex(std::string_view name);
/// Number of floats a parameter holds (1, or 3 for colours).
int paramComponents(const ParamMeta& p);
/// "pre-pass", "HDR", "paint", "tone mapping", "LDR", "any".
std::string_view postStageName(PostStage stage);
/// "colour, depth, camera motion"
std::string describeReads(unsigned reads);

/// A new instance of @p type with every parameter at its default (empty type when unknown).
EffectInstance makeEffect(std::string_view type);
/// The value of @p param in @p effect, or its default when absent (x for scalars and choices).
glm::vec3 effectValue(const EffectInstance& effect, const ParamMeta& param);
/// Scalar shortcut; the default of an unknown id is 0.
float effectFloat(const EffectInstance& effect, std::string_view id);

/// Whether an enabled effect of @p chain reads FrameSettings::time (kReadsTime: film grain,
/// night-vision grain, vaporwave static, paintbrush strokes): its image changes from one second
/// to the next, so a viewport must keep drawing frames to show it.
bool postChainReadsTime(const PostChain& chain);

/// The index of the effect with id @p id in @p chain, or -1.
long findEffectIndex(const PostChain& chain, EffectId id);

/// Sets parameter @p param of the effect with id @p id to @p value after the value rules
/// (constrainParamValue: clamped to the range, a choice rounded; colours take three components,
/// the others x). False, and nothing changes, for an unknown id, type or parameter. The editor's
/// panel and undo commands edit through this (DocumentController::editEffectParam).
bool setEffectParam(PostChain& chain, EffectId id, std::string_view param, glm::vec3 value);
/// @p value as parameter @p param stores it: constrainParamValue, then its components.
std::vector<float> effectParamComponents(const ParamMeta& param, glm::vec3 value);

/// @name Chain edits. Each returns false (and changes nothing) on an index out of range.
/// @{
bool setEffectEnabled(PostChain& chain, size_t index, bool enabled);
/// Moves effect @p from to position @p to (the others keep their relative order).
bool moveEffect(PostChain& chain, size_t from, size_t to);
/// Inserts a copy, with a new id, right after @p index.
bool duplicateEffect(PostChain& chain, size_t index);
bool removeEffect(PostChain& chain, size_t index);
/// @}

/// One thing wrong with a chain: the effect index and a sentence saying why.
struct ChainIssue {
    size_t index = 0;
    std::string message;
};

/// Stage rules: constrained effects appear in PostStage order, at most one tone-mapping effect.
/// Disabled effects are checked too (enabling one must not make the chain invalid). Unknown types
/// are left to checkEffectParams.
std::vector<ChainIssue> checkStageOrder(const PostChain& chain);
/// Unknown type (with a suggestion), unknown parameter, wrong component count, out of range.
std::vector<ChainIssue> checkEffectParams(const PostChain& chain);

/// The catalogue as Markdown (one section per effect: stage, reads, fusion, a parameter table
/// with ranges, defaults and units). docs/post-effects.md embeds this text between its
/// `<!-- catalogue:begin -->` and `<!-- catalogue:end -->` markers (a test keeps them equal;
/// `velvet post-catalogue` prints it).
std::string postEffectCatalogueMarkdown();

/// The default chain (the "Bloom + ACES" preset): bloom, ACES tone mapping, vignette, FXAA. The
/// bench's post_chain_share measures this chain.
PostChain defaultPostChain();

} // namespace velvet
