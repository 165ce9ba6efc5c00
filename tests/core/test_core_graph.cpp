// core/graph: the node catalogue, the model's connection rules (type, one link per input, no
// cycles, ports exist, one output), change notifications (value vs structural), and the JSON form
// (round trip equal, malformed graphs refused as a whole with JSON paths). No UI, no GPU.
#include "core/graph/graph.h"
#include "core/graph/graph_json.h"
#include "core/graph/node_catalogue.h"
#include "graph_test_util.h"

#include <QtTest>
#include <set>

using namespace velvet;
using namespace velvet::graph;
using velvet::test::add;
using velvet::test::inputPort;
using velvet::test::link;

namespace {

/// Records every change it is told about.
struct Recorder : GraphListener {
    std::vector<Change> changes;
    void graphChanged(const Change& c) override { changes.push_back(c); }
};

/// A graph using every node type, with values and settings off their defaults.
Graph everyNodeGraph() {
    Graph g;
    const NodeId outNode = add(g, kOutputTypeId);
    std::map<std::string_view, NodeId> ids;
    for (const NodeType& t : nodeTypes())
        if (!t.isOutput)
            ids[t.id] = add(g, t.id);
    g.moveNode(ids["math.mix"], {-120.5f, 33.25f});
    g.setInputValue(ids["constant.float"], 0, glm::vec4(0.3f));
    g.setInputValue(ids["constant.color"], 0, glm::vec4(0.1f, 0.2f, 0.3f, 0.0f));
    g.setInputValue(ids["texture.image"], inputPort(g, ids["texture.image"], "scale"),
                    {4, 2, 0, 0});
    g.setInputValue(ids["texture.image"], inputPort(g, ids["texture.image"], "rotation"),
                    {30, 0, 0, 0});
    g.setSetting(ids["texture.image"], "file", "textures/denim.png");
    g.setSetting(ids["texture.image"], "colorSpace", "sRGB texture");
    g.setSetting(ids["texture.atlasRegion"], "file", "atlas.png");
    g.setInputValue(ids["texture.atlasRegion"], inputPort(g, ids["texture.atlasRegion"], "region"),
                    {64, 0, 64, 32});
    auto connect = [&](Connection c) {
        const EditResult r = g.connect(c);
        if (!r)
            qFatal("connect: %s", r.message.c_str());
    };
    connect(link(g, ids["input.uv"], "uv", ids["texture.image"], "uv"));
    connect(link(g, ids["texture.image"], "color", ids["math.mix"], "a"));
    connect(link(g, ids["noise.checker"], "color", ids["math.mix"], "b"));
    connect(link(g, ids["noise.fbm"], "value", ids["math.mix"], "factor"));
    connect(link(g, ids["math.mix"], "result", outNode, "baseColor"));
    connect(link(g, ids["texture.atlasRegion"], "color", ids["channel.unpackSrm"], "packed"));
    connect(link(g, ids["channel.unpackSrm"], "roughness", outNode, "roughness"));
    connect(link(g, ids["channel.unpackSrm"], "metallic", outNode, "metallic"));
    connect(link(g, ids["normal.map"], "normal", outNode, "normal"));
    return g;
}

} // namespace

class TestCoreGraph : public QObject {
    Q_OBJECT

private slots:
    /// The value rules of an input edit: the port type's components clamped to the input's
    /// range, the others 0; Graph::setInputValue stores exactly that.
    void inputValuesAreConstrained() {
        graph::InputSpec colour;
        colour.type = graph::PortType::Color;
        colour.min = 0.0f;
        colour.max = 1.0f;
        QCOMPARE(graph::constrainInputValue(colour, glm::vec4(-1.0f, 0.5f, 3.0f, 9.0f)),
                 glm::vec4(0.0f, 0.5f, 1.0f, 0.0f));
        graph::InputSpec scalar;
        scalar.min = -2.0f;
        scalar.max = 2.0f;
        QCOMPARE(graph::constrainInputValue(scalar, glm::vec4(5.0f, 1.0f, 1.0f, 1.0f)),
                 glm::vec4(2.0f, 0.0f, 0.0f, 0.0f));
    }

    // The catalogue is well formed: unique ids and port names, defaults within range, snippets.
    void catalogue() {
        std::set<std::string_view> ids;
        for (const NodeType& t : nodeTypes()) {
            QVERIFY2(ids.insert(t.id).second, std::string(t.id).c_str());
            QVERIFY(t.glsl);
            QVERIFY(!t.label.empty() && !t.category.empty());
            std::set<std::string_view> names;
            for (const InputSpec& i : t.inputs) {
                QVERIFY2(names.insert(i.name).second, std::string(i.name).c_str());
                for (int c = 0; c < portTypeComponents(i.type); ++c)
                    QVERIFY2(i.defaultValue[c] >= i.min && i.defaultValue[c] <= i.max,
                             (std::string(t.id) + "." + std::string(i.name)).c_str());
            }
            names.clear();
            for (const OutputSpec& o : t.outputs)
                QVERIFY2(names.insert(o.name).second, std::string(o.name).c_str());
            QCOMPARE(t.samplesTexture, t.settingIndex("file") >= 0);
        }
        for (std::string_view id :
             {"constant.float",  "constant.color",    "texture.image",   "texture.atlasRegion",
              "input.uv",        "channel.split",     "channel.combine", "channel.unpackOrm",
              "channel.packOrm", "channel.unpackSrm", "channel.packSrm", "math.add",
              "math.multiply",   "math.mix",          "math.remap",      "math.invert",
              "math.clamp",      "math.power",        "noise.perlin",    "noise.fbm",
              "noise.checker",   "noise.gradient",    "normal.map",      "output.material"})
            QVERIFY2(findNodeType(id), std::string(id).c_str());
        QVERIFY(!findNodeType("nope"));
    }

    // The material output has one input per Float or Color parameter (every lobe weight included),
    // typed and ranged from ParamMeta, plus occlusion, the two normals and the anisotropy
    // direction.
    void outputInputs() {
        const NodeType& t = *findNodeType(kOutputTypeId);
        int params = 0;
        for (int i = 0; i < kParamCount; ++i) {
            const ParamMeta& m = paramMeta(ParamId(i));
            const int input = outputInputForParam(ParamId(i));
            if (m.type == ParamType::Choice) {
                QCOMPARE(input, -1);
                continue;
            }
            ++params;
            QVERIFY2(input >= 0, std::string(m.id).c_str());
            const InputSpec& spec = t.inputs[size_t(input)];
            QCOMPARE(spec.type, m.type == ParamType::Color ? PortType::Color : PortType::Float);
            QCOMPARE(spec.fallback, Fallback::Material);
            QCOMPARE(spec.max, m.max);
            QCOMPARE(paramForOutputInput(PortIndex(input)), ParamId(i));
        }
        QCOMPARE(int(t.inputs.size()), params + 4);
        QCOMPARE(t.inputIndex("baseColor"), outputInputForParam(ParamId::BaseColor));
        QCOMPARE(t.inputIndex("roughness"), outputInputForParam(ParamId::Roughness));
        QCOMPARE(t.inputIndex("sheenWeight"), outputInputForParam(ParamId::SheenWeight));
        QCOMPARE(t.inputIndex("clearcoatWeight"), outputInputForParam(ParamId::ClearcoatWeight));
        QCOMPARE(t.inputIndex("specularWeight"), outputInputForParam(ParamId::SpecularWeight));
        QCOMPARE(t.inputIndex("emissionStrength"), outputInputForParam(ParamId::EmissiveStrength));
        QVERIFY(t.inputIndex("occlusion") >= 0);
        QCOMPARE(t.inputs[size_t(t.inputIndex("normal"))].type, PortType::Normal);
        QCOMPARE(t.inputs[size_t(t.inputIndex("clearcoatNormal"))].type, PortType::Normal);
        QCOMPARE(t.inputs[size_t(t.inputIndex("anisotropyDirection"))].type, PortType::Vec2);
    }

    // The one conversion table: splat up, luminance down, normals only to normals.
    void conversions() {
        QVERIFY(canConvert(PortType::Float, PortType::Color));
        QVERIFY(canConvert(PortType::Color, PortType::Float));
        QVERIFY(canConvert(PortType::Color, PortType::Vec4));
        QVERIFY(canConvert(PortType::Vec4, PortType::Color));
        QVERIFY(!canConvert(PortType::Vec2, PortType::Float));
        for (int t = 0; t < int(PortType::Count); ++t) {
            QVERIFY(canConvert(PortType(t), PortType(t)));
            if (PortType(t) != PortType::Normal) {
                QVERIFY(!canConvert(PortType(t), PortType::Normal));
                QVERIFY(!canConvert(PortType::Normal, PortType(t)));
            }
        }
        QCOMPARE(*convertGlsl("x", PortType::Float, PortType::Color), std::string("vec3(x)"));
        QCOMPARE(*convertGlsl("c", PortType::Color, PortType::Float),
                 std::string("dot(c, vec3(0.2126, 0.7152, 0.0722))"));
        QVERIFY(!convertGlsl("c", PortType::Color, PortType::Normal));
    }

    void connectAccepted() {
        Graph g;
        Recorder rec;
        g.addListener(&rec);
        const NodeId c = add(g, "constant.color");
        const NodeId o = add(g, kOutputTypeId);
        const Connection l = link(g, c, "color", o, "baseColor");
        QVERIFY(g.canConnect(l));
        QVERIFY(g.connect(l));
        QCOMPARE(g.connections().size(), size_t(1));
        QVERIFY(*g.connectionTo(o, l.inPort) == l);
        QCOMPARE(rec.changes.back().what, Change::What::Connected);
        QCOMPARE(rec.changes.back().kind, ChangeKind::Structure);
        QVERIFY(rec.changes.back().connection == l);
        // Float into a colour input splats; colour into a float input takes luminance.
        const NodeId f = add(g, "constant.float");
        QVERIFY(g.connect(link(g, f, "value", o, "sheenColor")));
        QVERIFY(g.connect(link(g, c, "color", o, "roughness")));
        g.removeListener(&rec);
    }

    void typeMismatchRefused() {
        Graph g;
        const NodeId c = add(g, "constant.color");
        const NodeId uv = add(g, "input.uv");
        const NodeId nm = add(g, "normal.map");
        const NodeId o = add(g, kOutputTypeId);
        Recorder rec;
        g.addListener(&rec);
        EditResult r = g.connect(link(g, c, "color", o, "normal"));
        QVERIFY(!r);
        QVERIFY2(r.message.find("(color)") != std::string::npos &&
                     r.message.find("(normal)") != std::string::npos,
                 r.message.c_str());
        QVERIFY(!g.connect(link(g, nm, "normal", o, "baseColor")));
        QVERIFY(!g.connect(link(g, uv, "uv", o, "roughness")));
        QVERIFY(g.connections().empty());
        QVERIFY(rec.changes.empty()); // refusals change nothing and tell no one
        QVERIFY(g.connect(link(g, nm, "normal", o, "normal")));
        g.removeListener(&rec);
    }

    // One link per input: a second link to a fed input is refused (not replaced), and the first
    // stays. The editor replaces as disconnect + connect in one undo macro.
    void secondLinkRefused() {
        Graph g;
        const NodeId a = add(g, "constant.color");
        const NodeId b = add(g, "constant.color");
        const NodeId o = add(g, kOutputTypeId);
        const Connection first = link(g, a, "color", o, "baseColor");
        const Connection second = link(g, b, "color", o, "baseColor");
        QVERIFY(g.connect(first));
        const EditResult r = g.connect(second);
        QVERIFY(!r);
        QVERIFY2(r.message.find("already fed by node " + std::to_string(a)) != std::string::npos,
                 r.message.c_str());
        QCOMPARE(g.connections().size(), size_t(1));
        QVERIFY(*g.connectionTo(o, first.inPort) == first);
        // An output may feed many inputs.
        QVERIFY(g.connect(link(g, a, "color", o, "sheenColor")));
        // Replacing: disconnect, then connect.
        QVERIFY(g.disconnect(first));
        QVERIFY(g.connect(second));
        QVERIFY(!g.disconnect(first)); // already gone
    }

    void cycleRefused() {
        Graph g;
        const NodeId a = add(g, "math.add");
        const NodeId b = add(g, "math.multiply");
        const NodeId c = add(g, "math.invert");
        QVERIFY(g.connect(link(g, a, "result", b, "a")));
        QVERIFY(g.connect(link(g, b, "result", c, "value")));
        EditResult r = g.connect(link(g, c, "result", a, "a")); // a -> b -> c -> a
        QVERIFY(!r);
        QVERIFY2(r.message.find("cycle") != std::string::npos, r.message.c_str());
        QVERIFY(!g.connect(link(g, b, "result", a, "b"))); // two-node cycle
        QVERIFY(!g.connect(link(g, a, "result", a, "b"))); // self link
        QCOMPARE(g.connections().size(), size_t(2));
        // A diamond is not a cycle.
        QVERIFY(!g.connect(link(g, a, "result", c, "value"))); // input taken, not a cycle
        const NodeId d = add(g, "math.add");
        QVERIFY(g.connect(link(g, a, "result", d, "a")));
        QVERIFY(g.connect(link(g, c, "result", d, "b")));
    }

    void unknownPortsRefused() {
        Graph g;
        const NodeId c = add(g, "constant.color");
        const NodeId o = add(g, kOutputTypeId);
        EditResult r = g.connect({c, 5, o, 0});
        QVERIFY(!r);
        QVERIFY2(r.message.find("no output 5") != std::string::npos, r.message.c_str());
        r = g.connect({c, 0, o, 999});
        QVERIFY2(!r && r.message.find("no input 999") != std::string::npos, r.message.c_str());
        r = g.connect({c, 0, 77, 0});
        QVERIFY2(!r && r.message.find("no node 77") != std::string::npos, r.message.c_str());
        QVERIFY(!g.connect({77, 0, o, 0}));
        // A node's settings-like inputs (UV scale) take no link.
        const NodeId t = add(g, "texture.image");
        const NodeId f = add(g, "input.uv");
        r = g.connect(link(g, f, "uv", t, "scale"));
        QVERIFY2(!r && r.message.find("takes no link") != std::string::npos, r.message.c_str());
        QVERIFY(g.connections().empty());
    }

    void oneMaterialOutput() {
        Graph g;
        const NodeId o = add(g, kOutputTypeId);
        const EditResult r = g.addNode(kOutputTypeId);
        QVERIFY(!r);
        QVERIFY2(r.message.find("already has a material output") != std::string::npos,
                 r.message.c_str());
        QCOMPARE(g.outputNode(), o);
        QVERIFY(g.removeNode(o));
        QCOMPARE(g.outputNode(), kInvalidNodeId);
        QVERIFY(g.addNode(kOutputTypeId));
        QVERIFY(!g.addNode("no.such.type"));
    }

    // removeNode removes its links (reported one by one before the node, for undo).
    void removeNodeRemovesLinks() {
        Graph g;
        const NodeId uv = add(g, "input.uv");
        const NodeId t = add(g, "texture.image");
        const NodeId o = add(g, kOutputTypeId);
        const NodeId f = add(g, "constant.float");
        QVERIFY(g.connect(link(g, uv, "uv", t, "uv")));
        QVERIFY(g.connect(link(g, t, "color", o, "baseColor")));
        QVERIFY(g.connect(link(g, t, "alpha", o, "roughness")));
        QVERIFY(g.connect(link(g, f, "value", o, "metallic")));
        Recorder rec;
        g.addListener(&rec);
        QVERIFY(g.removeNode(t));
        QVERIFY(!g.node(t));
        QCOMPARE(g.connections().size(), size_t(1));
        QCOMPARE(g.connections().begin()->outNode, f);
        QCOMPARE(rec.changes.size(), size_t(4));
        for (int i = 0; i < 3; ++i) {
            QCOMPARE(rec.changes[size_t(i)].what, Change::What::Disconnected);
            QVERIFY(rec.changes[size_t(i)].connection.outNode == t ||
                    rec.changes[size_t(i)].connection.inNode == t);
        }
        QCOMPARE(rec.changes[3].what, Change::What::NodeRemoved);
        QCOMPARE(rec.changes[3].node, t);
        QVERIFY(!g.removeNode(t));
        g.removeListener(&rec);
        // Undo restores it with its id; new ids stay above every id used.
        QVERIFY(g.addNodeWithId(t, "texture.image"));
        QVERIFY(!g.addNodeWithId(t, "texture.image"));
        QVERIFY(!g.addNodeWithId(kInvalidNodeId, "texture.image"));
        QVERIFY(g.addNodeWithId(40, "math.add"));
        QCOMPARE(g.addNode("math.add").node, NodeId(41));
    }

    // The listener tells a value edit (uniform only) from structural and layout edits.
    void changeKinds() {
        Graph g;
        Recorder rec;
        g.addListener(&rec);
        const NodeId c = add(g, "constant.float");
        const NodeId t = add(g, "texture.image");
        QCOMPARE(rec.changes.back().kind, ChangeKind::Structure);
        QVERIFY(g.setInputValue(c, 0, glm::vec4(0.25f)));
        QCOMPARE(rec.changes.back().what, Change::What::ValueSet);
        QCOMPARE(rec.changes.back().kind, ChangeKind::Value);
        QCOMPARE(rec.changes.back().node, c);
        QVERIFY(g.setSetting(t, "file", "a.png"));
        QCOMPARE(rec.changes.back().kind, ChangeKind::Texture);
        QCOMPARE(g.node(t)->settings[0], std::string("a.png"));
        QVERIFY(!g.setSetting(t, "nope", "x"));
        QVERIFY(g.moveNode(c, {10, 20}));
        QCOMPARE(rec.changes.back().kind, ChangeKind::Layout);
        QCOMPARE(g.node(c)->position, glm::vec2(10, 20));
        QVERIFY(!g.moveNode(99, {0, 0}));
        const size_t before = rec.changes.size();
        g.removeListener(&rec);
        QVERIFY(g.moveNode(c, {1, 1}));
        QCOMPARE(rec.changes.size(), before);
    }

    void inputValues() {
        Graph g;
        const NodeId m = add(g, "math.mix");
        const NodeId o = add(g, kOutputTypeId);
        const PortIndex factor = inputPort(g, m, "factor");
        QCOMPARE(g.node(m)->inputValues[factor].x, 0.5f);
        QVERIFY(g.setInputValue(m, factor, {2.0f, 7.0f, 7.0f, 7.0f})); // clamped, unused zeroed
        QCOMPARE(g.node(m)->inputValues[factor], glm::vec4(1, 0, 0, 0));
        EditResult r = g.setInputValue(m, factor, glm::vec4(std::nanf("")));
        QVERIFY2(!r && r.message.find("finite") != std::string::npos, r.message.c_str());
        QVERIFY(!g.setInputValue(m, 42, glm::vec4(0)));
        r = g.setInputValue(o, inputPort(g, o, "roughness"), glm::vec4(0.2f));
        QVERIFY2(!r && r.message.find("material's parameter") != std::string::npos,
                 r.message.c_str());
        const NodeId t = add(g, "texture.image");
        QVERIFY(!g.setInputValue(t, inputPort(g, t, "uv"), glm::vec4(0)));
    }

    void copyAndCompare() {
        const Graph a = everyNodeGraph();
        Graph b = a;
        QVERIFY(a == b);
        b.moveNode(b.nodes().begin()->first, {1, 2});
        QVERIFY(!(a == b));
        Graph c = a;
        c.disconnect(*c.connections().begin());
        QVERIFY(!(a == c));
        c.clear();
        QVERIFY(c.nodes().empty() && c.connections().empty());
    }

    // ---- JSON ----

    // Write, read back: the same graph; write again: the same text.
    void jsonRoundTrip() {
        const Graph g = everyNodeGraph();
        const std::string text = graphToJsonText(g);
        Problems problems;
        const std::optional<Graph> back = graphFromJsonText(text, "mem.json", problems);
        for (const Problem& p : problems.items)
            qWarning("%s", p.toString().c_str());
        QVERIFY(back.has_value());
        QVERIFY(problems.items.empty());
        QVERIFY(*back == g);
        QCOMPARE(graphToJsonText(*back), text);
        QVERIFY(text.find("\"textures/denim.png\"") != std::string::npos);
        QVERIFY(text.find("\"baseColor\"") != std::string::npos);
        // An empty graph too.
        const std::optional<Graph> empty =
            graphFromJsonText(graphToJsonText(Graph{}), "", problems);
        QVERIFY(empty && empty->nodes().empty());
    }

    // Malformed graphs: nothing is returned, and the problem names the JSON path.
    void jsonMalformed_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("path");
        QTest::addColumn<QString>("message");
        const QString out = R"({"id": 9, "type": "output.material"})";
        const QString col = R"({"id": 1, "type": "constant.color"})";
        auto graph = [](const QString& nodes, const QString& links) {
            return QString(R"({"graph": {"nodes": [%1], "links": [%2]}})").arg(nodes, links);
        };
        QTest::newRow("not an object") << R"({"graph": 3})"
                                       << "graph"
                                       << "expected an object";
        QTest::newRow("unknown key") << R"({"graph": {"nodez": []}})"
                                     << "graph.nodez"
                                     << "did you mean \"nodes\"";
        QTest::newRow("nodes not array") << R"({"graph": {"nodes": {}}})"
                                         << "graph.nodes"
                                         << "expected an array of nodes";
        QTest::newRow("unknown type")
            << graph(R"({"id": 1, "type": "math.ad"})", "") << "graph.nodes[0].type"
            << "unknown node type \"math.ad\" (did you mean \"math.add\"?)";
        QTest::newRow("missing id") << graph(R"({"type": "math.add"})", "") << "graph.nodes[0].id"
                                    << "required key is missing";
        QTest::newRow("bad id") << graph(R"({"id": 0, "type": "math.add"})", "")
                                << "graph.nodes[0].id"
                                << "expected an integer";
        QTest::newRow("duplicate id") << graph(col + ", " + col, "") << "graph.nodes[1].id"
                                      << "used twice";
        QTest::newRow("two outputs")
            << graph(out + R"(, {"id": 2, "type": "output.material"})", "") << "graph.nodes[1]"
            << "already has a material output";
        QTest::newRow("value out of range")
            << graph(R"({"id": 1, "type": "math.mix", "inputs": {"factor": 2}})", "")
            << "graph.nodes[0].inputs.factor"
            << "expected a number in [0, 1], got 2";
        QTest::newRow("value wrong size")
            << graph(R"({"id": 1, "type": "constant.color", "inputs": {"color": [1, 0]}})", "")
            << "graph.nodes[0].inputs.color"
            << "expected an array of 3 numbers";
        QTest::newRow("unknown input")
            << graph(R"({"id": 1, "type": "math.mix", "inputs": {"factr": 0}})", "")
            << "graph.nodes[0].inputs.factr"
            << "did you mean \"factor\"";
        QTest::newRow("output value")
            << graph(R"({"id": 1, "type": "output.material", "inputs": {"roughness": 0.5}})", "")
            << "graph.nodes[0].inputs.roughness"
            << "has no value of its own";
        QTest::newRow("unknown setting")
            << graph(R"({"id": 1, "type": "texture.image", "settings": {"fiel": "a.png"}})", "")
            << "graph.nodes[0].settings.fiel"
            << "did you mean \"file\"";
        QTest::newRow("bad position")
            << graph(R"({"id": 1, "type": "math.add", "position": [1]})", "")
            << "graph.nodes[0].position"
            << "expected an array of 2 numbers";
        QTest::newRow("link to missing node")
            << graph(col, R"({"from": 1, "output": "color", "to": 5, "input": "baseColor"})")
            << "graph.links[0].to"
            << "no node with id 5";
        QTest::newRow("link unknown port")
            << graph(col + ", " + out,
                     R"({"from": 1, "output": "color", "to": 9, "input": "baseColour"})")
            << "graph.links[0].input"
            << "did you mean \"baseColor\"";
        QTest::newRow("link missing key")
            << graph(col + ", " + out, R"({"from": 1, "to": 9, "input": "baseColor"})")
            << "graph.links[0].output"
            << "required key is missing";
        QTest::newRow("link type mismatch")
            << graph(col + ", " + out,
                     R"({"from": 1, "output": "color", "to": 9, "input": "normal"})")
            << "graph.links[0]"
            << "cannot connect";
        QTest::newRow("second link to an input")
            << graph(col + ", " + out + R"(, {"id": 2, "type": "constant.color"})",
                     R"({"from": 1, "output": "color", "to": 9, "input": "baseColor"},
                        {"from": 2, "output": "color", "to": 9, "input": "baseColor"})")
            << "graph.links[1]"
            << "already fed by node 1";
        QTest::newRow("cycle")
            << graph(R"({"id": 1, "type": "math.add"}, {"id": 2, "type": "math.add"})",
                     R"({"from": 1, "output": "result", "to": 2, "input": "a"},
                        {"from": 2, "output": "result", "to": 1, "input": "a"})")
            << "graph.links[1]"
            << "would make a cycle";
    }
    void jsonMalformed() {
        QFETCH(QString, text);
        QFETCH(QString, path);
        QFETCH(QString, message);
        Problems problems;
        const std::optional<Graph> g = graphFromJsonText(text.toStdString(), "bad.json", problems);
        QVERIFY(!g.has_value());
        bool found = false;
        for (const Problem& p : problems.items)
            if (p.severity == Problem::Severity::Error && p.path == path.toStdString() &&
                p.message.find(message.toStdString()) != std::string::npos)
                found = true;
        if (!found)
            for (const Problem& p : problems.items)
                qWarning("got: %s", p.toString().c_str());
        QVERIFY2(found, qPrintable("expected " + path + ": …" + message));
        for (const Problem& p : problems.items)
            QCOMPARE(p.file, std::string("bad.json"));
    }

    // Every problem of a file is reported, not only the first.
    void jsonReportsEveryProblem() {
        Problems problems;
        const auto g = graphFromJsonText(
            R"({"graph": {"nodes": [{"id": 1, "type": "x"}, {"id": 2, "type": "math.mix",
                "inputs": {"factor": -1}}], "links": [7]}})",
            "", problems);
        QVERIFY(!g);
        QCOMPARE(problems.items.size(), size_t(3));
        QCOMPARE(problems.items[0].path, std::string("graph.nodes[0].type"));
        QCOMPARE(problems.items[1].path, std::string("graph.nodes[1].inputs.factor"));
        QCOMPARE(problems.items[2].path, std::string("graph.links[0]"));
    }
};

QTEST_GUILESS_MAIN(TestCoreGraph)
#include "test_core_graph.moc"
