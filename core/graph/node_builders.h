#pragma once
/// @file node_builders.h
/// Internal to core/graph: the building blocks of the node table (node_catalogue.cpp and the
/// fabric nodes of fabric_nodes.cpp), and the hook through which the fabric nodes join it.

#include "core/graph/node_catalogue.h"

#include <string>
#include <vector>

namespace velvet::graph::detail {

inline InputSpec value(std::string_view name, std::string_view label, PortType type, glm::vec4 def,
                       float min, float max, std::string_view tooltip, bool connectable = true,
                       float softMax = 0.0f, std::string_view unit = {}) {
    InputSpec s;
    s.name = name;
    s.label = label;
    s.type = type;
    s.fallback = Fallback::Value;
    s.defaultValue = def;
    s.min = min;
    s.max = max;
    s.softMax = softMax;
    s.unit = unit;
    s.tooltip = tooltip;
    s.connectable = connectable;
    return s;
}

inline InputSpec scalarIn(std::string_view name, std::string_view label, float def, float min,
                          float max, std::string_view tooltip, bool connectable = true,
                          float softMax = 0.0f, std::string_view unit = {}) {
    return value(name, label, PortType::Float, glm::vec4(def, 0, 0, 0), min, max, tooltip,
                 connectable, softMax, unit);
}

inline InputSpec colorIn(std::string_view name, std::string_view label, float def, float min,
                         float max, std::string_view tooltip, bool connectable = true) {
    return value(name, label, PortType::Color, glm::vec4(def, def, def, 0), min, max, tooltip,
                 connectable);
}

inline InputSpec uvIn() {
    InputSpec s;
    s.name = "uv";
    s.label = "UV";
    s.type = PortType::Vec2;
    s.fallback = Fallback::MeshUv;
    s.min = -1e6f;
    s.max = 1e6f;
    s.tooltip = "Texture coordinates; the mesh's UVs when nothing is connected.";
    return s;
}

// Ranges wide enough for any artistic use, finite so files and sliders stay sane.
inline constexpr float kBig = 10000.0f;

inline void line(std::string& o, const std::string& text) {
    o += "    ";
    o += text;
    o += '\n';
}

inline NodeType make(std::string_view id, std::string_view label, std::string_view category,
                     std::string_view tooltip, std::vector<InputSpec> inputs,
                     std::vector<OutputSpec> outputs, SnippetFn fn, unsigned helpers = HelperNone) {
    NodeType t;
    t.id = id;
    t.label = label;
    t.category = category;
    t.tooltip = tooltip;
    t.inputs = std::move(inputs);
    t.outputs = std::move(outputs);
    t.glsl = fn;
    t.helpers = helpers;
    return t;
}

/// Appends the fabric nodes (Weave, Knit, Fibre fuzz, Pile; category "Fabric") to @p types.
void appendFabricNodes(std::vector<NodeType>& types);

} // namespace velvet::graph::detail
