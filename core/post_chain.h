#pragma once
/// @file post_chain.h
/// The post-effect chain of a scene: an ordered list of effect instances with parameters.
/// An empty chain is valid (tone mapping then falls back to the renderer default).
/// The effect catalogue and stage rules grow with the post-chain issue.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace velvet {

/// A post effect's identity within one run of the program: the editor addresses effects by it
/// (selection, undo commands), so an edit reaches the same effect after a reorder. Never 0.
using EffectId = std::uint64_t;

/// A fresh id, unique within the process (thread-safe).
EffectId newEffectId();

/// One effect in the chain. Parameters are numbers or number lists keyed by parameter id.
struct EffectInstance {
    std::string type; ///< effect type id, e.g. "bloom", "tonemap", "vignette"
    bool enabled = true;
    std::map<std::string, std::vector<float>> params;
    /// Assigned when the instance is created, built by a loader or a preset included: copies
    /// keep it (an undo snapshot is the same effect), duplicateEffect gives the copy a new one.
    /// Runtime only, never saved (docs/post-effects.md, "Effect ids"): files stay as they are,
    /// and two presets loaded into one scene can never collide.
    EffectId id = newEffectId();

    /// Equal values: type, enabled and parameters. The id is identity, not value, so a chain
    /// loaded again equals the one saved.
    bool operator==(const EffectInstance& o) const {
        return type == o.type && enabled == o.enabled && params == o.params;
    }
};

struct PostChain {
    std::vector<EffectInstance> effects;
    bool operator==(const PostChain&) const = default;
};

} // namespace velvet
