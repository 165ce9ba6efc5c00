#pragma once
/// @file graph_types.h
/// The vocabulary of the material graph: node and port addresses, connections and port types with
/// their implicit conversions. Nodes, ports and connections are addressed by ID, as QtNodes does
/// (paceholder/nodeeditor, include/QtNodes/internal/Definitions.hpp), so the model is edited and
/// tested without any UI. No Qt, no GL.

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

namespace velvet::graph {

/// A node's identity inside one graph; stable for the node's life and kept by files and undo.
using NodeId = std::uint32_t;
/// The index of a port among a node's inputs or among its outputs (two separate lists).
using PortIndex = std::uint32_t;
/// No node (QtNodes' InvalidNodeId). Valid ids start at 1.
inline constexpr NodeId kInvalidNodeId = 0;

/// A link from output @ref outPort of @ref outNode to input @ref inPort of @ref inNode.
struct Connection {
    NodeId outNode = kInvalidNodeId;
    PortIndex outPort = 0;
    NodeId inNode = kInvalidNodeId;
    PortIndex inPort = 0;
    bool operator==(const Connection&) const = default;
    /// Ordered by outNode, outPort, inNode, inPort (so the links leaving a node are contiguous).
    /// Written out rather than `<=>` so Qt's moc, which reads this header from tests, can parse it.
    bool operator<(const Connection& o) const {
        if (outNode != o.outNode)
            return outNode < o.outNode;
        if (outPort != o.outPort)
            return outPort < o.outPort;
        if (inNode != o.inNode)
            return inNode < o.inNode;
        return inPort < o.inPort;
    }
};

/// "3.0 -> 5.2" (node.outPort -> node.inPort), for messages and logs.
std::string toString(const Connection& c);

/// What flows along a link. Sampled textures give Color (RGB) and a separate Float alpha, so Vec4
/// exists only for completeness of the conversion table and for future RGBA nodes.
enum class PortType : int {
    Float,  ///< a scalar (roughness, a mask, a noise value)
    Vec2,   ///< texture coordinates (UV) or a 2D vector
    Color,  ///< RGB, scene-linear Rec.709 for colours, raw for packed data (GLSL vec3)
    Vec4,   ///< RGBA
    Normal, ///< a unit tangent-space normal (+Z out of the surface, OpenGL +Y up convention)
    Count
};

/// "float", "vec2", "color", "vec4", "normal" (JSON and messages).
std::string_view portTypeName(PortType t);
/// The GLSL type carrying @p t ("float", "vec2", "vec3", "vec4", "vec3").
std::string_view portTypeGlsl(PortType t);
/// How many floats of a value slot the type uses (1, 2, 3, 4, 3).
int portTypeComponents(PortType t);

/// Whether a link from an output of type @p from may feed an input of type @p to. The one table of
/// implicit conversions (rows: from, columns: to):
///
/// |        | Float     | Vec2   | Color      | Vec4         | Normal |
/// |--------|-----------|--------|------------|--------------|--------|
/// | Float  | =         | splat  | splat      | (f, f, f, 1) | no     |
/// | Vec2   | no        | =      | (x, y, 0)  | (x, y, 0, 1) | no     |
/// | Color  | luminance | .xy    | =          | (rgb, 1)     | no     |
/// | Vec4   | luminance | .xy    | .rgb       | =            | no     |
/// | Normal | no        | no     | no         | no           | =      |
///
/// Luminance uses the Rec.709 / sRGB weights (0.2126, 0.7152, 0.0722; ITU-R BT.709-6 item 3.2),
/// as Blender's colour-to-float socket conversion does; the weights sum to 1, so a grey colour
/// converts back to its own value and math nodes (which work on colours) serve float chains too.
/// Normal connects only to Normal: a colour is never a normal until a Normal map node decodes it
/// (plugging a raw normal texture into a normal input is the classic mistake this refuses), and
/// Vec2 never silently becomes a scalar (which component would it be?).
bool canConvert(PortType from, PortType to);
/// The GLSL expression converting @p expr of type @p from to @p to; nullopt when not allowed.
std::optional<std::string> convertGlsl(const std::string& expr, PortType from, PortType to);

} // namespace velvet::graph
