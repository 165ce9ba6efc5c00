#pragma once
/// @file graph_eval.h
/// The CPU twin of the graph compiler: evaluates a material graph at one UV, node by node, with
/// the same statements the compiled GLSL runs (node_catalogue.cpp's snippets, the conversions of
/// graph_types.h, the fabric and noise twins of fabric.h). The reference path tracer evaluates
/// the material through it at every hit (issue 15: "textures and graph evaluated through their
/// CPU twins"); tests check it against the GPU's node thumbnails (render/graph_preview.h).

#include "core/graph/graph.h"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <optional>
#include <vector>

namespace velvet::graph {

/// Where texture nodes read their images. The default samples opaque white, as an unset file
/// does in the renderer.
class GraphTextures {
public:
    virtual ~GraphTextures() = default;
    /// The image of texture node @p node at @p uv (wrapping, as GL_REPEAT), RGBA in the colour
    /// the renderer uploads (scene-linear for colour data, raw for "Raw").
    virtual glm::vec4 sample(NodeId node, glm::vec2 uv) const;
    /// Its size in pixels (atlas regions are in pixels).
    virtual glm::ivec2 size(NodeId node) const;
};

/// What the material output receives at one point: per input of the output node, the value when
/// a link feeds it (converted to the input's type and clamped as the GLSL clamps it), nothing
/// where the material's own parameter stays.
struct GraphSample {
    std::vector<std::optional<glm::vec4>> outputInputs;
};

class GraphEvaluator {
public:
    /// Plans the evaluation of @p graph (a copy is not kept; the graph must outlive nothing).
    /// Nodes that do not feed the material output are not evaluated.
    explicit GraphEvaluator(const Graph& graph, const GraphTextures* textures = nullptr);

    /// True when the graph has a material output with at least one fed input.
    bool drivesMaterial() const { return m_drives; }
    /// The material output's inputs at @p uv.
    GraphSample evaluate(glm::vec2 uv) const;
    /// Output @p output of node @p node at @p uv, in its port type's components (the value the
    /// GPU's preview of that output shows, before display encoding). Zero for an unknown node.
    glm::vec4 evaluateOutput(NodeId node, PortIndex output, glm::vec2 uv) const;

    /// One node of the plan: its type, its own values and where each input reads from.
    struct Step {
        NodeId id = kInvalidNodeId;
        const NodeType* type = nullptr;
        std::vector<glm::vec4> values;
        std::vector<int> sourceSlot;      ///< per input: value slot of the feeding output, or -1
        std::vector<PortType> sourceType; ///< per input: that output's type
    };

private:
    std::vector<Step> m_steps;         // in dependency order
    std::vector<size_t> m_outputFirst; // per step: first slot of its outputs in a value array
    size_t m_slots = 0;
    const GraphTextures* m_textures = nullptr;
    int m_outputStep = -1;
    bool m_drives = false;
    void run(glm::vec2 uv, std::vector<glm::vec4>& values, int lastStep) const;
    int stepOf(NodeId node) const;
};

} // namespace velvet::graph
