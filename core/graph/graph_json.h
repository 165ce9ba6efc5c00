#pragma once
/// @file graph_json.h
/// The material graph in JSON, as the "graph" object of a material preset (the lead wires it into
/// material_json.cpp). Layout:
///
///     "graph": {
///       "nodes": [
///         {"id": 1, "type": "texture.image", "position": [-420, 80],
///          "inputs": {"scale": [4, 4], "rotation": 0},
///          "settings": {"file": "textures/denim.png", "colorSpace": "sRGB texture"}},
///         {"id": 2, "type": "output.material", "position": [0, 0]}
///       ],
///       "links": [{"from": 1, "output": "color", "to": 2, "input": "baseColor"}]
///     }
///
/// Ports and settings are named, not numbered, so files survive ports being added to a type.
/// `inputs` holds values of inputs that have one (Fallback::Value): a number for Float, an array of
/// 2, 3 or 4 numbers otherwise, each within the input's range; absent inputs take the default.
/// Reading is all-or-nothing: every problem is reported with its JSON path (e.g.
/// `graph.links[2].input: node 7 (math.add) has no input "c" (did you mean "a"?)`) and no graph is
/// returned unless there were none. Links obey the model's rules (graph.h), checked in file order.

#include "core/graph/graph.h"
#include "core/json_read.h"
#include "core/json_value.h"

#include <optional>
#include <string>
#include <string_view>

namespace velvet::graph {

/// The "graph" object for @p graph: nodes in id order, every value input written, settings only
/// when not at their default, links in Graph::connections() order. Same graph, same JSON.
JsonValue graphToJson(const Graph& graph);

/// Reads a "graph" object found at JSON path @p path (normally "graph"), reporting problems
/// through @p reader. nullopt when any problem was found.
std::optional<Graph> graphFromJson(const JsonValue& value, const std::string& path,
                                   JsonReader& reader);

/// @name Text forms (tests, clipboard)
/// @{
std::string graphToJsonText(const Graph& graph);
/// Parses @p text and reads it as a graph at path "graph". Problems name @p fileName.
std::optional<Graph> graphFromJsonText(std::string_view text, const std::string& fileName,
                                       Problems& problems);
/// @}

} // namespace velvet::graph
