#include "core/graph/graph_json.h"

#include <array>
#include <limits>

namespace velvet::graph {
namespace {

constexpr std::array<std::string_view, 2> kGraphKeys{"nodes", "links"};
constexpr std::array<std::string_view, 5> kNodeKeys{"id", "type", "position", "inputs", "settings"};
constexpr std::array<std::string_view, 4> kLinkKeys{"from", "output", "to", "input"};
// Deep nesting is refused by the parser; this bounds how large a file may make the model.
constexpr size_t kMaxNodes = 4096;

JsonValue floats(const glm::vec4& v, int count) {
    if (count == 1)
        return JsonValue::makeFloat(v.x);
    JsonValue a = JsonValue::makeArray();
    for (int i = 0; i < count; ++i)
        a.push(JsonValue::makeFloat(v[i]));
    return a;
}

template <typename Spec>
std::vector<std::string_view> names(const std::vector<Spec>& specs) {
    std::vector<std::string_view> out;
    for (const Spec& s : specs)
        out.push_back(s.name);
    return out;
}

std::string describeNode(const Node& n) {
    return "node " + std::to_string(n.id) + " (" + std::string(n.type->id) + ")";
}

void readInputs(JsonReader& r, const JsonValue& v, const std::string& path, Node& n,
                std::vector<std::pair<PortIndex, glm::vec4>>& values) {
    if (v.kind == JsonValue::Kind::Invalid)
        return;
    if (!v.isObject()) {
        r.error(path, "expected an object of input values, got " + describeValue(v));
        return;
    }
    for (const JsonMember& m : v.members) {
        const std::string p = jsonPathKey(path, m.key);
        const int index = n.type->inputIndex(m.key);
        if (index < 0) {
            const auto known = names(n.type->inputs);
            r.error(p,
                    describeNode(n) + " has no input \"" + m.key + "\"" + didYouMean(m.key, known));
            continue;
        }
        const InputSpec& spec = n.type->inputs[size_t(index)];
        if (spec.fallback != Fallback::Value) {
            r.error(p,
                    "input \"" + m.key + "\" of " + describeNode(n) + " has no value of its own");
            continue;
        }
        const NumberRange range = closedRange(spec.min, spec.max);
        const int count = portTypeComponents(spec.type);
        glm::vec4 value(0.0f);
        if (count == 1) {
            auto x = r.number(m.value, p, range);
            if (!x)
                continue;
            value.x = float(*x);
        } else {
            auto xs = r.numbers(m.value, p, size_t(count), range);
            if (!xs)
                continue;
            for (int i = 0; i < count; ++i)
                value[i] = float((*xs)[size_t(i)]);
        }
        values.emplace_back(PortIndex(index), value);
    }
}

void readSettings(JsonReader& r, const JsonValue& v, const std::string& path, Node& n,
                  std::vector<std::pair<std::string, std::string>>& settings) {
    if (v.kind == JsonValue::Kind::Invalid)
        return;
    if (!v.isObject()) {
        r.error(path, "expected an object of settings, got " + describeValue(v));
        return;
    }
    for (const JsonMember& m : v.members) {
        const std::string p = jsonPathKey(path, m.key);
        if (n.type->settingIndex(m.key) < 0) {
            const auto known = names(n.type->settings);
            r.error(p, describeNode(n) + " has no setting \"" + m.key + "\"" +
                           didYouMean(m.key, known));
            continue;
        }
        if (auto s = r.string(m.value, p))
            settings.emplace_back(m.key, *s);
    }
}

void readNode(JsonReader& r, const JsonValue& v, const std::string& path, Graph& g) {
    if (!r.expectObject(v, path, kNodeKeys))
        return;
    std::optional<long long> id;
    if (const JsonValue* idv = r.require(v, path, "id"))
        id = r.integer(*idv, jsonPathKey(path, "id"),
                       closedRange(1, double(std::numeric_limits<NodeId>::max() - 1)));
    const NodeType* type = nullptr;
    const std::string typePath = jsonPathKey(path, "type");
    if (const JsonValue* tv = r.require(v, path, "type"))
        if (auto t = r.string(*tv, typePath, false)) {
            type = findNodeType(*t);
            if (!type)
                r.error(typePath,
                        "unknown node type \"" + *t + "\"" + didYouMean(*t, nodeTypeIds()));
        }
    glm::vec2 position(0.0f);
    bool positionOk = true;
    if (const JsonValue* pv = v.find("position")) {
        const auto p = r.vec2(*pv, jsonPathKey(path, "position"), NumberRange{});
        positionOk = p.has_value();
        if (p)
            position = *p;
    }
    if (!id || !type || !positionOk)
        return;
    if (g.node(NodeId(*id))) {
        r.error(jsonPathKey(path, "id"), "node id " + std::to_string(*id) + " is used twice");
        return;
    }
    const EditResult added = g.addNodeWithId(NodeId(*id), type->id, position);
    if (!added) {
        r.error(path, added.message);
        return;
    }
    Node node = *g.node(NodeId(*id));
    std::vector<std::pair<PortIndex, glm::vec4>> values;
    std::vector<std::pair<std::string, std::string>> settings;
    if (const JsonValue* iv = v.find("inputs"))
        readInputs(r, *iv, jsonPathKey(path, "inputs"), node, values);
    if (const JsonValue* sv = v.find("settings"))
        readSettings(r, *sv, jsonPathKey(path, "settings"), node, settings);
    for (const auto& [input, value] : values)
        g.setInputValue(node.id, input, value); // in range: checked above
    for (auto& [name, value] : settings)
        g.setSetting(node.id, name, std::move(value));
}

void readLink(JsonReader& r, const JsonValue& v, const std::string& path, Graph& g) {
    if (!r.expectObject(v, path, kLinkKeys))
        return;
    const NumberRange idRange = closedRange(1, double(std::numeric_limits<NodeId>::max() - 1));
    // Each end: the node (it must exist) and the port name (it must exist on that node).
    auto end = [&](std::string_view nodeKey, std::string_view portKey, bool output,
                   PortIndex& port) -> const Node* {
        const JsonValue* nv = r.require(v, path, nodeKey);
        const JsonValue* pv = r.require(v, path, portKey);
        if (!nv || !pv)
            return nullptr;
        const std::string nodePath = jsonPathKey(path, nodeKey);
        const std::string portPath = jsonPathKey(path, portKey);
        const auto id = r.integer(*nv, nodePath, idRange);
        const auto name = r.string(*pv, portPath, false);
        if (!id || !name)
            return nullptr;
        const Node* n = g.node(NodeId(*id));
        if (!n) {
            r.error(nodePath, "no node with id " + std::to_string(*id));
            return nullptr;
        }
        const int index = output ? n->type->outputIndex(*name) : n->type->inputIndex(*name);
        if (index < 0) {
            const auto known = output ? names(n->type->outputs) : names(n->type->inputs);
            r.error(portPath, describeNode(*n) + " has no " + (output ? "output" : "input") +
                                  " \"" + *name + "\"" + didYouMean(*name, known));
            return nullptr;
        }
        port = PortIndex(index);
        return n;
    };
    Connection c;
    const Node* from = end("from", "output", true, c.outPort);
    const Node* to = end("to", "input", false, c.inPort);
    if (!from || !to)
        return;
    c.outNode = from->id;
    c.inNode = to->id;
    const EditResult res = g.connect(c);
    if (!res)
        r.error(path, res.message);
}

} // namespace

JsonValue graphToJson(const Graph& graph) {
    JsonValue root = JsonValue::makeObject();
    JsonValue& nodes = root.add("nodes", JsonValue::makeArray());
    for (const auto& [id, n] : graph.nodes()) {
        JsonValue o = JsonValue::makeObject();
        o.add("id", JsonValue::makeNumber(double(id)));
        o.add("type", JsonValue::makeString(std::string(n.type->id)));
        JsonValue pos = JsonValue::makeArray();
        pos.push(JsonValue::makeFloat(n.position.x));
        pos.push(JsonValue::makeFloat(n.position.y));
        o.add("position", std::move(pos));
        JsonValue inputs = JsonValue::makeObject();
        for (size_t i = 0; i < n.type->inputs.size(); ++i) {
            const InputSpec& spec = n.type->inputs[i];
            if (spec.fallback == Fallback::Value)
                inputs.add(std::string(spec.name),
                           floats(n.inputValues[i], portTypeComponents(spec.type)));
        }
        if (!inputs.members.empty())
            o.add("inputs", std::move(inputs));
        JsonValue settings = JsonValue::makeObject();
        for (size_t i = 0; i < n.type->settings.size(); ++i)
            if (n.settings[i] != n.type->settings[i].defaultValue)
                settings.add(std::string(n.type->settings[i].name),
                             JsonValue::makeString(n.settings[i]));
        if (!settings.members.empty())
            o.add("settings", std::move(settings));
        nodes.push(std::move(o));
    }
    JsonValue& links = root.add("links", JsonValue::makeArray());
    for (const Connection& c : graph.connections()) {
        const Node* from = graph.node(c.outNode);
        const Node* to = graph.node(c.inNode);
        JsonValue o = JsonValue::makeObject();
        o.add("from", JsonValue::makeNumber(double(c.outNode)));
        o.add("output", JsonValue::makeString(std::string(from->type->outputs[c.outPort].name)));
        o.add("to", JsonValue::makeNumber(double(c.inNode)));
        o.add("input", JsonValue::makeString(std::string(to->type->inputs[c.inPort].name)));
        links.push(std::move(o));
    }
    return root;
}

std::optional<Graph> graphFromJson(const JsonValue& value, const std::string& path,
                                   JsonReader& reader) {
    const size_t errorsBefore = reader.errorCount();
    if (!reader.expectObject(value, path, kGraphKeys))
        return std::nullopt;
    Graph g;
    const std::string nodesPath = jsonPathKey(path, "nodes");
    if (const JsonValue* nodes = value.find("nodes")) {
        if (nodes->kind == JsonValue::Kind::Invalid) {
        } else if (!nodes->isArray()) {
            reader.error(nodesPath, "expected an array of nodes, got " + describeValue(*nodes));
        } else if (nodes->items.size() > kMaxNodes) {
            reader.error(nodesPath, "too many nodes (" + std::to_string(nodes->items.size()) +
                                        "; at most " + std::to_string(kMaxNodes) + ")");
        } else {
            for (size_t i = 0; i < nodes->items.size(); ++i)
                readNode(reader, nodes->items[i], jsonPathIndex(nodesPath, i), g);
        }
    }
    const std::string linksPath = jsonPathKey(path, "links");
    if (const JsonValue* links = value.find("links")) {
        if (links->kind == JsonValue::Kind::Invalid) {
        } else if (!links->isArray()) {
            reader.error(linksPath, "expected an array of links, got " + describeValue(*links));
        } else {
            for (size_t i = 0; i < links->items.size(); ++i)
                readLink(reader, links->items[i], jsonPathIndex(linksPath, i), g);
        }
    }
    if (reader.errorCount() != errorsBefore)
        return std::nullopt;
    return g;
}

std::string graphToJsonText(const Graph& graph) {
    JsonValue root = JsonValue::makeObject();
    root.add("graph", graphToJson(graph));
    return writeJson(root);
}

std::optional<Graph> graphFromJsonText(std::string_view text, const std::string& fileName,
                                       Problems& problems) {
    const size_t before = problems.items.size();
    auto root = parseJson(text, fileName, problems, 64);
    if (!root)
        return std::nullopt;
    JsonReader reader(fileName, problems);
    if (!reader.expectObject(*root, "", std::array<std::string_view, 1>{"graph"}))
        return std::nullopt;
    const JsonValue* g = reader.require(*root, "", "graph");
    if (!g)
        return std::nullopt;
    auto graph = graphFromJson(*g, "graph", reader);
    for (size_t i = before; i < problems.items.size(); ++i)
        if (problems.items[i].severity == Problem::Severity::Error)
            return std::nullopt;
    return graph;
}

} // namespace velvet::graph
