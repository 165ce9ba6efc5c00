#pragma once
/// @file post_chain_io.h
/// Post-chain presets as versioned JSON (`{"format": "velvet.post-chain", "version": 1, "name":
/// …, "effects": […]}`), the chain part of scenes, and the JSON Schema of both, all generated from
/// the effect catalogue (core/post_effects.h). Loading is all-or-nothing: types, parameters,
/// ranges and the stage order are checked first and every problem names its JSON path.

#include "core/diagnostics.h"
#include "core/post_chain.h"

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace velvet {

inline constexpr std::string_view kPostChainFormat = "velvet.post-chain";
inline constexpr int kPostChainVersion = 1;

/// A chain preset: a display name and the chain.
struct PostChainPreset {
    std::string name;
    PostChain chain;
    bool operator==(const PostChainPreset&) const = default;
};

std::optional<PostChainPreset> parsePostChain(std::string_view text, const std::string& fileName,
                                              Problems& problems);
std::optional<PostChainPreset> loadPostChainFile(const std::filesystem::path& file,
                                                 Problems& problems);
/// Pretty JSON of the current version (parameters in catalogue order, choices by name).
std::string postChainToJson(const PostChainPreset& preset);
/// Atomic write; false + @p error on failure.
bool savePostChainFile(const PostChainPreset& preset, const std::filesystem::path& file,
                       std::string* error);

/// The JSON Schema (draft 2020-12) of chain presets (resources/schemas/post-chain.schema.json).
std::string postChainJsonSchema();

} // namespace velvet
