#pragma once
/// @file post_chain_json.h
/// Internal to core's readers: the "effects" array shared by scenes (`post.effects`) and chain
/// presets (`effects`), and its schema.

#include "core/json_read.h"
#include "core/json_value.h"
#include "core/post_chain.h"

#include <string>

namespace velvet {

/// Reads the effects array @p v at JSON path @p path into @p chain, validating types and
/// parameters against the catalogue, then the stage order. Problems go to @p r.
void readPostEffects(JsonReader& r, const JsonValue& v, const std::string& path, PostChain& chain);
/// The effects array (floats as one-element arrays, colours as triples, choices by name).
JsonValue postEffectsToJson(const PostChain& chain);
/// The schema of the effects array: one alternative per effect type.
JsonValue postEffectsSchema();

} // namespace velvet
