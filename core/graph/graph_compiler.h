#pragma once
/// @file graph_compiler.h
/// Compiles a material graph to GLSL for the G-buffer pass.
///
/// ## The interface for the renderer
/// The generated text (CompiledGraph::glsl) is a GLSL 4.50 include with no `#version`. It declares:
///
/// - `struct MaterialInputs` — one field per input of the material output node, named as the
///   ports are (node_catalogue.h, "The material output's inputs"), in port order:
///   `vec3 baseColor; float metallic; float roughness; float specularWeight; vec3 specularColor;
///   float ior; float normalScale; float occlusionStrength; vec3 emissionColor;
///   float emissionStrength; float clearcoatWeight; float clearcoatRoughness;
///   float clearcoatNormalScale; float sheenWeight; vec3 sheenColor; float sheenRoughness;
///   float anisotropyStrength; float anisotropyRotation;` then `float occlusion; vec3 normal;
///   vec3 clearcoatNormal; vec2 anisotropyDirection;`. Colours are scene-linear and
///   unmultiplied (emissionColor before strength, sheenColor before weight), exactly the values of
///   the Material parameters; `occlusion` is the raw AO (1: none) before occlusionStrength;
///   `normal` / `clearcoatNormal` are unit tangent-space normals (+Z out, OpenGL +Y up) before
///   normalScale, for the renderer's TBN; `anisotropyStrength` is KHR_materials_anisotropy's
///   strength in [0, 1], `anisotropyRotation` degrees counter-clockwise from the tangent, and
///   `anisotropyDirection` the tangent-space direction (default (1, 0), unnormalised) that the
///   rotation turns, as the extension's anisotropyTexture RG.
/// - `MaterialInputs velvetGraphDefaults()` — every field at its ParamMeta default, (0, 0, 1)
///   normals, anisotropy direction (1, 0) and occlusion 1 (for tests and previews without a
///   material table).
/// - `layout(std140, binding = B) uniform VelvetGraphValues { vec4 u_graphValues[N]; };` with
///   B = CompileOptions::valuesBinding and N = CompiledGraph::values.size() (>= 1). Every constant
///   and unconnected input value of the graph lives in one vec4 slot (x; xy; xyz; xyzw by type).
/// - `layout(binding = U) uniform sampler2D u_graphTexK;` for each texture node, K = 0, 1, …,
///   U = CompileOptions::firstSamplerUnit + K (see CompiledGraph::samplers).
/// - `void velvetGraph(in vec2 uv, inout MaterialInputs m)` — overwrites the fields whose output
///   input is connected (clamped to the parameter's hard range) and leaves every other field as it
///   came in. The renderer fills `m` from the material table first, then calls velvetGraph with
///   the mesh UVs, so unconnected inputs keep the material's parameter values.
///
/// ## Value edits and structural edits
/// The text depends only on the graph's structure (nodes feeding the output, their types and ids,
/// links) — never on input values, settings or positions — so a value edit (ChangeKind::Value)
/// needs only graphValues() and a buffer upload, and a texture edit (ChangeKind::Texture) only a
/// rebind; ChangeKind::Structure needs compileGraph() and a new program. The same graph always
/// gives byte-identical text: nodes are emitted in topological order, ties broken by increasing
/// id, and numbers are printed the same on every machine.

#include "core/graph/graph.h"

#include <glm/vec4.hpp>
#include <span>
#include <string>
#include <vector>

namespace velvet::graph {

/// Where the generated declarations bind. Defaults fit render/shader_program.h's binding points
/// (UBO 0 frame; texture units 0-6 taken, 16+ display LUTs).
struct CompileOptions {
    int valuesBinding = 2;    ///< UBO binding point of VelvetGraphValues
    int firstSamplerUnit = 7; ///< texture unit of u_graphTex0
    int maxSamplers = 9;      ///< more texture nodes than this is a compile error
    int maxValueSlots = 1024; ///< 16 KiB, GL's guaranteed minimum GL_MAX_UNIFORM_BLOCK_SIZE
};

/// Which input's value a slot of u_graphValues holds.
struct ValueSlot {
    NodeId node = kInvalidNodeId;
    PortIndex input = 0;
    bool operator==(const ValueSlot&) const = default;
};

/// A texture the renderer binds: the image of one texture node.
struct SamplerBinding {
    NodeId node = kInvalidNodeId;
    std::string uniform;    ///< "u_graphTex0"
    int unit = 0;           ///< texture unit (the layout(binding) in the text)
    std::string file;       ///< the node's "file" setting ("" : bind a fallback texture)
    std::string colorSpace; ///< the node's "colorSpace" setting ("" : the config's file rules)
    bool operator==(const SamplerBinding&) const = default;
};

/// The result of compileGraph().
struct CompiledGraph {
    bool ok = false;
    std::string error; ///< why compilation failed (ok == false)
    std::string glsl;  ///< the include described above
    /// The contents of VelvetGraphValues (std140: one vec4 per slot), max(1, valueSlots) entries.
    std::vector<glm::vec4> values;
    std::vector<ValueSlot> valueSlots; ///< slot i of u_graphValues holds valueSlots[i]
    std::vector<SamplerBinding> samplers;
    std::vector<NodeId> order;              ///< nodes compiled, in emission (topological) order
    std::vector<std::string> writtenFields; ///< MaterialInputs fields velvetGraph overwrites
    /// compileGraphPreview(): the type of the previewed output (Color is shown sRGB-encoded).
    PortType previewType = PortType::Color;
};

/// Compiles the nodes that feed the material output. A graph without an output compiles to a
/// velvetGraph that changes nothing. Fails (ok == false, with a message) only when the graph needs
/// more samplers or value slots than @p options allow.
CompiledGraph compileGraph(const Graph& graph, const CompileOptions& options = {});

/// Compiles the nodes that feed output @p output of @p node (the node itself included) for a
/// preview: the same declarations as compileGraph() (MaterialInputs, the value block, samplers,
/// helpers; the same slot and sampler layout rules), then, instead of velvetGraph,
/// `vec4 velvetGraphPreview(in vec2 uv)` returning that output's value at @p uv as RGBA: a float
/// as grey, a Vec2 as (x, y, 0), a colour as is (scene-linear), a normal as n * 0.5 + 0.5, alpha 1.
/// Nodes not upstream of @p node are left out, so the text depends only on that part of the
/// structure and a value edit needs only graphValues(). Fails (with a message) for an unknown
/// node or output and on the limits of compileGraph().
CompiledGraph compileGraphPreview(const Graph& graph, NodeId node, PortIndex output,
                                  const CompileOptions& options = {});

/// The value block for @p valueSlots with the graph's current values: what a value edit uploads
/// (equal to compileGraph(graph).values while the structure is unchanged).
std::vector<glm::vec4> graphValues(const Graph& graph, std::span<const ValueSlot> valueSlots);

} // namespace velvet::graph
