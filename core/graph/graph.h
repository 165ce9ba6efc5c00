#pragma once
/// @file graph.h
/// The material graph model: nodes (typed by node_catalogue.h), their input values, settings and
/// positions, and the connections between them. Every edit goes through the small API below, which
/// checks the rules and returns an EditResult with a message on refusal, so the rules hold for the
/// editor, the file reader and the tests alike (QtNodes' DataFlowGraphModel::connectionPossible
/// keeps them in the model the same way). No Qt: listeners are a plain interface.
///
/// Rules:
/// - ports exist: a connection names an existing output of its source and an existing,
///   connectable input of its target;
/// - types are compatible (canConvert() in graph_types.h);
/// - one link per input: a link to an input that is already fed is **refused** (as QtNodes does);
///   the editor replaces a link as one undo macro, disconnect() then connect();
/// - no cycles, no self-links;
/// - at most one material output node.

#include "core/graph/graph_types.h"
#include "core/graph/node_catalogue.h"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace velvet::graph {

/// One node. Values are indexed like the type's inputs, settings like its settings.
struct Node {
    NodeId id = kInvalidNodeId;
    const NodeType* type = nullptr;
    glm::vec2 position{0.0f};             ///< scene position of the node's top-left corner
    std::vector<glm::vec4> inputValues;   ///< used when an input is unconnected (Fallback::Value)
    std::vector<std::string> settings;    ///< e.g. image file and colour space
    bool operator==(const Node& o) const; ///< same id, type, position, values and settings
};

/// What an edit changed, as the editor and renderer need to know it:
enum class ChangeKind {
    Value,     ///< an input value: update the uniform value block only (no recompile)
    Texture,   ///< a setting of a texture node (file, colour space): rebind, no recompile
    Layout,    ///< a node moved: redraw the graph view, nothing for the renderer
    Structure, ///< nodes or links added or removed: regenerate and recompile the shader
};

/// One change, sent to listeners after it is applied.
struct Change {
    enum class What {
        NodeAdded,
        NodeRemoved,
        Connected,
        Disconnected,
        ValueSet,
        SettingSet,
        Moved
    };
    What what = What::NodeAdded;
    ChangeKind kind = ChangeKind::Structure;
    NodeId node = kInvalidNodeId; ///< node added, removed, edited, moved; links: the input side
    PortIndex index = 0;          ///< the input (ValueSet) or setting (SettingSet)
    Connection connection;        ///< Connected / Disconnected
};

/// Receives changes. removeNode() reports the node's links as Disconnected first, then NodeRemoved,
/// so an undo command can record and restore them.
class GraphListener {
public:
    virtual ~GraphListener() = default;
    virtual void graphChanged(const Change& change) = 0;
};

/// The outcome of an edit: ok, or refused with a one-line reason naming nodes by id.
struct EditResult {
    bool ok = true;
    std::string message;          ///< why the edit was refused ("" when ok)
    NodeId node = kInvalidNodeId; ///< addNode: the new node's id
    explicit operator bool() const { return ok; }
    static EditResult refuse(std::string why) { return {false, std::move(why), kInvalidNodeId}; }
};

class Graph {
public:
    Graph() = default;
    /// Copies nodes and links, not listeners (a move takes them along).
    Graph(const Graph& other);
    Graph& operator=(const Graph& other);
    Graph(Graph&&) noexcept = default;
    Graph& operator=(Graph&&) noexcept = default;

    /// @name Edits
    /// @{
    /// Adds a node of type @p typeId with default values and settings; the id is in the result.
    EditResult addNode(std::string_view typeId, glm::vec2 position = {});
    /// Adds a node with a chosen id (files, undo of a delete, paste): refused when the id is taken
    /// or invalid. Later addNode() ids stay above every id used.
    EditResult addNodeWithId(NodeId id, std::string_view typeId, glm::vec2 position = {});
    /// Removes a node and every link to or from it.
    EditResult removeNode(NodeId id);
    /// Whether connect(@p c) would be accepted, and why not (QtNodes' connectionPossible).
    EditResult canConnect(const Connection& c) const;
    EditResult connect(const Connection& c);
    EditResult disconnect(const Connection& c);
    /// Sets an input's value, clamped to the input's hard range (as Material::setValue clamps);
    /// components beyond the input's type are set to 0. Refused for non-finite values and for the
    /// material output's inputs (their value is the material's parameter). A connected input keeps
    /// the value for when it is disconnected.
    EditResult setInputValue(NodeId id, PortIndex input, glm::vec4 value);
    /// Sets a string setting (a texture node's "file" or "colorSpace").
    EditResult setSetting(NodeId id, std::string_view name, std::string value);
    EditResult moveNode(NodeId id, glm::vec2 position);
    /// Removes everything (one Structure change per removed node and link).
    void clear();
    /// @}

    /// @name Queries
    /// @{
    /// Nodes by id, in increasing id order.
    const std::map<NodeId, Node>& nodes() const { return m_nodes; }
    const Node* node(NodeId id) const;
    /// Links in increasing (outNode, outPort, inNode, inPort) order.
    const std::set<Connection>& connections() const { return m_connections; }
    /// The link feeding input @p input of @p id, or nullptr.
    const Connection* connectionTo(NodeId id, PortIndex input) const;
    /// Every link to or from @p id.
    std::vector<Connection> connectionsOf(NodeId id) const;
    /// The material output node, or kInvalidNodeId.
    NodeId outputNode() const;
    /// The id the next addNode() will use.
    NodeId nextId() const { return m_nextId; }
    /// @}

    /// Same nodes (ids, types, positions, values, settings) and links; listeners are not compared.
    bool operator==(const Graph& other) const;

    /// @name Listeners (not owned; remove before destroying them)
    /// @{
    void addListener(GraphListener* listener);
    void removeListener(GraphListener* listener);
    /// @}

private:
    Node* findNode(NodeId id);
    /// Whether @p to can be reached from @p from following links downstream.
    bool reaches(NodeId from, NodeId to) const;
    void notify(const Change& change);

    std::map<NodeId, Node> m_nodes;
    std::set<Connection> m_connections;
    NodeId m_nextId = 1;
    std::vector<GraphListener*> m_listeners;
};

} // namespace velvet::graph
