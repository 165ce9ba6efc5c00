#pragma once
/// @file node_catalogue.h
/// Every node type of the material graph: its inputs (with defaults and ParamMeta-like metadata),
/// its outputs, its string settings and the GLSL snippet it compiles to. The catalogue is a table;
/// the model (graph.h), the files (graph_json.h), the compiler (graph_compiler.h) and, later, the
/// node menu and property panels all read it, so a new node is one entry here.

#include "core/graph/graph_types.h"
#include "core/material.h"

#include <glm/vec4.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace velvet::graph {

/// What an input reads when no link feeds it.
enum class Fallback {
    Value,    ///< its own value (editable; compiled to a uniform slot, so edits never recompile)
    MeshUv,   ///< the mesh's texture coordinates (the `uv` argument of velvetGraph)
    Material, ///< nothing: the material output leaves the material's parameter value in place
};

/// One input port.
struct InputSpec {
    std::string_view name;  ///< stable id in files and GLSL ("roughness", "uv", "scale")
    std::string_view label; ///< shown on the node
    PortType type = PortType::Float;
    Fallback fallback = Fallback::Value;
    glm::vec4 defaultValue{0.0f}; ///< components beyond the type's are 0
    float min = 0.0f;             ///< hard range of every component of the value
    float max = 1.0f;
    float softMax = 0.0f; ///< slider end when smaller than max (0: same as max)
    std::string_view unit;
    std::string_view tooltip;
    /// False: a parameter of the node shown only in Properties (a UV scale, an atlas rectangle);
    /// it has a value slot like any input but refuses links.
    bool connectable = true;
};

/// One output port.
struct OutputSpec {
    std::string_view name; ///< stable id in files and GLSL ("color", "alpha")
    std::string_view label;
    PortType type = PortType::Float;
};

/// A string setting of a node (an image file, its colour space). Changing one rebinds a texture but
/// never changes the shader text (see ChangeKind::Texture).
struct SettingSpec {
    std::string_view name; ///< "file", "colorSpace"
    std::string_view label;
    std::string_view defaultValue;
    std::string_view tooltip;
};

/// GLSL helper functions a snippet calls; the compiler emits each needed group once, in this
/// order, before velvetGraph().
enum Helper : unsigned {
    HelperNone = 0,
    HelperUvTransform = 1u << 0, ///< velvetGraphUvTransform
    HelperNoise = 1u << 1,       ///< common_hash.glsl, velvetGraphPerlin, velvetGraphFbm
    /// The fabric functions (core/graph/fabric.h, fabric::fabricGlsl); they call the noise
    /// helpers, so a node with this bit sets HelperNoise too.
    HelperFabric = 1u << 2,
};

/// What a snippet generator is given. Input expressions are already converted to the input's type;
/// outputs are variables the compiler has declared (with the outputs' GLSL types) and the snippet
/// must assign. Snippets run inside their own `{ }` block, so they may declare locals freely.
struct SnippetArgs {
    std::vector<std::string> in;  ///< one GLSL expression per input (empty for Material fallback)
    std::vector<std::string> out; ///< one variable name per output
    std::string sampler;          ///< the node's sampler2D uniform (texture nodes)
    std::vector<std::string> outputFields; ///< material output: the MaterialInputs field per input
    std::vector<bool> connected;           ///< whether each input is fed by a link
};

/// Appends the GLSL statements of one node, indented by four spaces, each line ending in '\n'.
using SnippetFn = void (*)(const SnippetArgs& args, std::string& out);

/// One node type.
struct NodeType {
    std::string_view id;       ///< stable id in files: "math.add", "texture.image"
    std::string_view label;    ///< node title and menu entry
    std::string_view category; ///< menu group: "Input", "Texture", "Math", "Noise", "Output"…
    std::string_view tooltip;
    std::vector<InputSpec> inputs;
    std::vector<OutputSpec> outputs;
    std::vector<SettingSpec> settings;
    SnippetFn glsl = nullptr;
    unsigned helpers = HelperNone; ///< Helper bits the snippet needs
    bool samplesTexture = false;   ///< declares one sampler2D (settings "file", "colorSpace")
    bool isOutput = false;         ///< the material output (at most one per graph)

    /// Index of the input / output / setting named @p name, or -1.
    int inputIndex(std::string_view name) const;
    int outputIndex(std::string_view name) const;
    int settingIndex(std::string_view name) const;
};

/// The value rules of an input edit, next to its metadata (as constrainParamValue is for
/// parameters): each of the port type's components clamped to [min, max], the others 0. A
/// non-finite component is left for the caller to refuse (Graph::setInputValue does).
glm::vec4 constrainInputValue(const InputSpec& spec, glm::vec4 value);

/// Every node type, in menu order.
std::span<const NodeType> nodeTypes();
/// The type whose id is @p id, or nullptr.
const NodeType* findNodeType(std::string_view id);
/// Every type id (for "did you mean" in messages and for the node menu's search).
std::span<const std::string_view> nodeTypeIds();
/// The material output's type id, "output.material".
inline constexpr std::string_view kOutputTypeId = "output.material";

/// @name The material output's inputs
/// One input per Float or Color ParamId (which includes every lobe weight: specularWeight,
/// clearcoatWeight, sheenWeight, emissionStrength), in ParamId order, then four map inputs that
/// have no parameter: `occlusion` (Float, ambient occlusion before occlusionStrength), `normal` and
/// `clearcoatNormal` (tangent-space Normal), `anisotropyDirection` (Vec2, tangent space, default
/// (1, 0): the tangent; not normalised here). The port names are generated from ParamMeta ids:
/// "lobes.base.color" -> "baseColor", "lobes.base.roughness" -> "roughness",
/// "lobes.sheen.color" -> "sheenColor" (base-lobe fields keep their plain name, other lobes prefix
/// theirs). They are also the field names of the GLSL struct MaterialInputs.
/// @{
/// The output input fed by parameter @p id, or -1 when the parameter is a Choice.
int outputInputForParam(ParamId id);
/// The parameter an output input stands for, or ParamId::Count for
/// occlusion/normal/clearcoatNormal/anisotropyDirection.
ParamId paramForOutputInput(PortIndex input);
/// @}

} // namespace velvet::graph
