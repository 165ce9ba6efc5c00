#pragma once
/// @file post_chain.h
/// The post-effect chain of a scene: an ordered list of effect instances with parameters.
/// An empty chain is valid (tone mapping then falls back to the renderer default).
/// The effect catalogue and stage rules grow with the post-chain issue.

#include <map>
#include <string>
#include <vector>

namespace velvet {

/// One effect in the chain. Parameters are numbers or number lists keyed by parameter id.
struct EffectInstance {
    std::string type; ///< effect type id, e.g. "bloom", "tonemap", "vignette"
    bool enabled = true;
    std::map<std::string, std::vector<float>> params;
    bool operator==(const EffectInstance&) const = default;
};

struct PostChain {
    std::vector<EffectInstance> effects;
    bool operator==(const PostChain&) const = default;
};

} // namespace velvet
