// core/graph/graph_compiler: value edits keep the shader text and change only the value block;
// structural edits change the text; output is deterministic and topologically ordered; every node
// type compiles — checked by a real GLSL compiler and linker on a headless context (Mesa llvmpipe
// here), so a syntax error in any node snippet fails this test — and two known-answer renders
// prove the uniform value path end to end (an edit changes the pixels with no recompile).
#include "core/graph/graph_compiler.h"
#include "core/graph/graph_json.h"
#include "render/shader_program.h"
#include "tests/core/graph_test_util.h"
#include "tests/render/render_test_util.h"

#include <QtTest>
#include <epoxy/gl.h>

using namespace velvet;
using namespace velvet::graph;
using velvet::test::add;
using velvet::test::link;
using velvet::test::mustConnect;

namespace {

/// constant colour -> mix.a, noise -> mix.factor, mix -> baseColor; float -> roughness.
struct Basic {
    Graph g;
    NodeId color, noise, mix, value, output;
};
Basic basicGraph() {
    Basic b;
    b.output = add(b.g, kOutputTypeId);
    b.color = add(b.g, "constant.color");
    b.noise = add(b.g, "noise.perlin");
    b.mix = add(b.g, "math.mix");
    b.value = add(b.g, "constant.float");
    mustConnect(b.g, link(b.g, b.color, "color", b.mix, "a"));
    mustConnect(b.g, link(b.g, b.noise, "value", b.mix, "factor"));
    mustConnect(b.g, link(b.g, b.mix, "result", b.output, "baseColor"));
    mustConnect(b.g, link(b.g, b.value, "value", b.output, "roughness"));
    return b;
}

int slotOf(const CompiledGraph& c, NodeId node, PortIndex input) {
    for (size_t i = 0; i < c.valueSlots.size(); ++i)
        if (c.valueSlots[i] == ValueSlot{node, input})
            return int(i);
    return -1;
}

/// The first input of the material output that output @p port of @p node may feed.
PortIndex outputInputFor(const Graph& g, NodeId node, PortIndex port, NodeId output) {
    const PortType t = g.node(node)->type->outputs[port].type;
    const NodeType& out = *g.node(output)->type;
    for (std::string_view preferred : {"baseColor", "roughness", "normal"}) {
        const int i = out.inputIndex(preferred);
        if (canConvert(t, out.inputs[size_t(i)].type))
            return PortIndex(i);
    }
    qFatal("no output input for %s", std::string(portTypeName(t)).c_str());
    return 0;
}

// ---- GL ---------------------------------------------------------------------------------------

constexpr int kSize = 4;

render::GeneratedSources sources(const CompiledGraph& c) {
    return {{"velvet_graph.glsl", c.glsl}, {"graph_test.frag", R"(#version 450 core
#include "velvet_graph.glsl"
layout(location = 0) out vec4 fragColor;
void main() {
    MaterialInputs m = velvetGraphDefaults();
    velvetGraph(gl_FragCoord.xy / 4.0, m);
    float n = m.normal.z + m.clearcoatNormal.z + m.occlusion + m.sheenRoughness + m.metallic;
    fragColor = vec4(m.baseColor, m.roughness) + 1e-9 * n;
}
)"}};
}

/// Compiles and links @p c into a program; "" or the driver's message.
std::string buildProgram(const CompiledGraph& c, render::ShaderProgram& program) {
    std::string error;
    if (!program.build("fullscreen.vert", "graph_test.frag", {}, sources(c), &error))
        return error.empty() ? std::string("build failed") : error;
    return {};
}

/// Draws @p program over a kSize² RGBA32F target with @p values in the graph's block.
std::vector<glm::vec4> draw(const render::ShaderProgram& program, const CompiledGraph& c,
                            const std::vector<glm::vec4>& values) {
    GLuint tex = 0, fbo = 0, vao = 0, ubo = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA32F, kSize, kSize);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
    glCreateVertexArrays(1, &vao);
    glCreateBuffers(1, &ubo);
    glNamedBufferData(ubo, GLsizeiptr(values.size() * sizeof(glm::vec4)), values.data(),
                      GL_DYNAMIC_DRAW);
    glBindBufferBase(GL_UNIFORM_BUFFER, CompileOptions{}.valuesBinding, ubo);
    // Texture nodes get a 1x1 white texture (what the renderer binds for an empty file).
    GLuint white = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &white);
    glTextureStorage2D(white, 1, GL_RGBA8, 1, 1);
    const unsigned char px[4] = {255, 255, 255, 255};
    glTextureSubImage2D(white, 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
    for (const SamplerBinding& s : c.samplers)
        glBindTextureUnit(GLuint(s.unit), white);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, kSize, kSize);
    glUseProgram(program.id());
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<glm::vec4> pixels(kSize * kSize);
    glReadPixels(0, 0, kSize, kSize, GL_RGBA, GL_FLOAT, pixels.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteTextures(1, &white);
    glDeleteBuffers(1, &ubo);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    return pixels;
}

bool near(const glm::vec4& a, const glm::vec4& b, float eps = 1e-5f) {
    for (int i = 0; i < 4; ++i)
        if (std::abs(a[i] - b[i]) > eps)
            return false;
    return true;
}

} // namespace

class TestCoreGraphCompiler : public QObject {
    Q_OBJECT

private slots:
    // A value edit: same text, a new value block (the edited slot only).
    void valueEditKeepsText() {
        Basic b = basicGraph();
        const CompiledGraph before = compileGraph(b.g);
        QVERIFY2(before.ok, before.error.c_str());
        const int slot = slotOf(before, b.color, 0);
        QVERIFY(slot >= 0);
        QCOMPARE(before.values[size_t(slot)], glm::vec4(0.8f, 0.8f, 0.8f, 0.0f));
        QVERIFY(b.g.setInputValue(b.color, 0, {0.1f, 0.2f, 0.3f, 0.0f}));
        const CompiledGraph after = compileGraph(b.g);
        QCOMPARE(after.glsl, before.glsl);
        QVERIFY(after.valueSlots == before.valueSlots);
        QVERIFY(after.values != before.values);
        for (size_t i = 0; i < after.values.size(); ++i)
            if (int(i) != slot)
                QCOMPARE(after.values[i], before.values[i]);
        QCOMPARE(after.values[size_t(slot)], glm::vec4(0.1f, 0.2f, 0.3f, 0.0f));
        // The cheap path gives the same block without compiling.
        QVERIFY(graphValues(b.g, before.valueSlots) == after.values);
        // Moving a node and changing a texture's file change no text either.
        const NodeId t = add(b.g, "texture.image");
        mustConnect(b.g, link(b.g, t, "alpha", b.output, "metallic"));
        const CompiledGraph withTexture = compileGraph(b.g);
        QVERIFY(b.g.moveNode(b.mix, {300, 40}));
        QVERIFY(b.g.setSetting(t, "file", "other.png"));
        QVERIFY(b.g.setSetting(t, "colorSpace", "Raw"));
        const CompiledGraph rebound = compileGraph(b.g);
        QCOMPARE(rebound.glsl, withTexture.glsl);
        QCOMPARE(rebound.samplers.size(), size_t(1));
        QCOMPARE(rebound.samplers[0].file, std::string("other.png"));
        QCOMPARE(rebound.samplers[0].colorSpace, std::string("Raw"));
        QCOMPARE(rebound.samplers[0].unit, CompileOptions{}.firstSamplerUnit);
    }

    // Structural edits change the text; undoing them restores it exactly.
    void structuralEditChangesText() {
        Basic b = basicGraph();
        const std::string original = compileGraph(b.g).glsl;
        const Connection l = link(b.g, b.noise, "value", b.output, "sheenWeight");
        QVERIFY(b.g.connect(l));
        const CompiledGraph connected = compileGraph(b.g);
        QVERIFY(connected.glsl != original);
        QVERIFY(connected.glsl.find("m.sheenWeight = ") != std::string::npos);
        QVERIFY(b.g.disconnect(l));
        QCOMPARE(compileGraph(b.g).glsl, original);
        // Disconnecting the noise makes the mix factor a value slot instead.
        const Connection factor = *b.g.connectionTo(b.mix, 2);
        QVERIFY(b.g.disconnect(factor));
        const CompiledGraph noNoise = compileGraph(b.g);
        QVERIFY(noNoise.glsl != original);
        QVERIFY(slotOf(noNoise, b.mix, 2) >= 0);
        QVERIFY(noNoise.glsl.find("velvetGraphPerlin") == std::string::npos); // helpers on demand
        QVERIFY(b.g.connect(factor));
        QCOMPARE(compileGraph(b.g).glsl, original);
        QVERIFY(b.g.removeNode(b.value));
        QVERIFY(compileGraph(b.g).glsl != original);
    }

    // The noise helpers use the shaders' one hash (resources/shaders/common_hash.glsl) instead
    // of a copy of their own (test_render_shader_sources: the folder defines it once).
    void noiseUsesTheSharedHash() {
        const std::string glsl = compileGraph(basicGraph().g).glsl;
        QVERIFY(glsl.find("#include \"common_hash.glsl\"") != std::string::npos);
        QVERIFY(glsl.find("pcg2d(") != std::string::npos);
        QVERIFY(glsl.find("1013904223u") == std::string::npos); // no hash body of its own
    }

    // Same graph, byte-identical text: built in another order, copied, read back from JSON.
    void deterministic() {
        const Basic b = basicGraph();
        const CompiledGraph a = compileGraph(b.g);
        QCOMPARE(compileGraph(b.g).glsl, a.glsl);
        Graph other; // same ids and links, added in reverse order
        QVERIFY(other.addNodeWithId(b.value, "constant.float"));
        QVERIFY(other.addNodeWithId(b.mix, "math.mix"));
        QVERIFY(other.addNodeWithId(b.noise, "noise.perlin"));
        QVERIFY(other.addNodeWithId(b.color, "constant.color"));
        QVERIFY(other.addNodeWithId(b.output, kOutputTypeId));
        std::vector<Connection> links(b.g.connections().begin(), b.g.connections().end());
        for (auto it = links.rbegin(); it != links.rend(); ++it)
            QVERIFY(other.connect(*it));
        QVERIFY(other == b.g);
        QCOMPARE(compileGraph(other).glsl, a.glsl);
        Problems problems;
        const auto back = graphFromJsonText(graphToJsonText(b.g), "", problems);
        QVERIFY(back);
        QCOMPARE(compileGraph(*back).glsl, a.glsl);
        QVERIFY(compileGraph(*back).values == a.values);
    }

    // Nodes are emitted after everything they read, ties by id; nodes feeding nothing are left out.
    void topologicalOrder() {
        Graph g;
        const NodeId o = add(g, kOutputTypeId);     // 1
        const NodeId inv = add(g, "math.invert");   // 2
        const NodeId mul = add(g, "math.multiply"); // 3
        const NodeId dead = add(g, "math.add");     // 4
        const NodeId c = add(g, "constant.color");  // 5
        const NodeId f = add(g, "constant.float");  // 6
        mustConnect(g, link(g, c, "color", mul, "a"));
        mustConnect(g, link(g, f, "value", mul, "b"));
        mustConnect(g, link(g, mul, "result", inv, "value"));
        mustConnect(g, link(g, inv, "result", o, "baseColor"));
        mustConnect(g, link(g, c, "color", dead, "a"));
        const CompiledGraph r = compileGraph(g);
        QVERIFY2(r.ok, r.error.c_str());
        QCOMPARE(r.order, (std::vector<NodeId>{c, f, mul, inv, o}));
        for (const ValueSlot& s : r.valueSlots)
            QVERIFY(s.node != dead);
        QVERIFY(r.glsl.find("node " + std::to_string(dead)) == std::string::npos);
        const size_t posMul = r.glsl.find("n" + std::to_string(mul) + "_result =");
        const size_t posInv = r.glsl.find("n" + std::to_string(inv) + "_result =");
        QVERIFY(posMul != std::string::npos && posInv != std::string::npos && posMul < posInv);
        QCOMPARE(r.writtenFields, (std::vector<std::string>{"baseColor"}));
    }

    // Unconnected output inputs are not written: the material's value stays.
    void unconnectedKeepMaterial() {
        Graph g;
        const NodeId o = add(g, kOutputTypeId);
        const NodeId f = add(g, "constant.float");
        mustConnect(g, link(g, f, "value", o, "roughness"));
        const CompiledGraph r = compileGraph(g);
        QVERIFY(r.glsl.find("m.roughness = clamp(n2_value, 0.0, 1.0);") != std::string::npos);
        const std::string body = r.glsl.substr(r.glsl.find("void velvetGraph("));
        QVERIFY(body.find("m.baseColor =") == std::string::npos);
        QVERIFY(body.find("m.metallic =") == std::string::npos);
        // The interface: the struct, the defaults, the block, the function.
        QVERIFY(r.glsl.find("struct MaterialInputs {") != std::string::npos);
        QVERIFY(r.glsl.find("    vec3 baseColor;\n") != std::string::npos);
        QVERIFY(r.glsl.find("    vec3 normal;\n") != std::string::npos);
        QVERIFY(r.glsl.find("MaterialInputs velvetGraphDefaults()") != std::string::npos);
        QVERIFY(r.glsl.find("layout(std140, binding = 2) uniform VelvetGraphValues {\n"
                            "    vec4 u_graphValues[1];") != std::string::npos);
        QVERIFY(r.glsl.find("void velvetGraph(in vec2 uv, inout MaterialInputs m) {") !=
                std::string::npos);
        // No output node: a velvetGraph that writes nothing.
        Graph none;
        add(none, "constant.float");
        const CompiledGraph empty = compileGraph(none);
        QVERIFY(empty.ok && empty.order.empty() && empty.values.size() == 1);
        QVERIFY(empty.glsl.find("inout MaterialInputs m) {\n}") != std::string::npos);
    }

    void limits() {
        Graph g;
        const NodeId o = add(g, kOutputTypeId);
        const NodeId add1 = add(g, "math.add");
        mustConnect(g, link(g, add1, "result", o, "baseColor"));
        NodeId last = add1;
        for (int i = 0; i < 3; ++i) {
            const NodeId t = add(g, "texture.image");
            const NodeId a = add(g, "math.add");
            mustConnect(g, link(g, t, "color", last, "a"));
            mustConnect(g, link(g, a, "result", last, "b"));
            last = a;
        }
        CompileOptions opt;
        opt.maxSamplers = 2;
        CompiledGraph r = compileGraph(g, opt);
        QVERIFY(!r.ok);
        QVERIFY2(r.error.find("3 textures; at most 2") != std::string::npos, r.error.c_str());
        opt.maxSamplers = 3;
        opt.maxValueSlots = 4;
        r = compileGraph(g, opt);
        QVERIFY2(!r.ok && r.error.find("at most 4") != std::string::npos, r.error.c_str());
        opt.maxValueSlots = 1024;
        opt.firstSamplerUnit = 20;
        r = compileGraph(g, opt);
        QVERIFY(r.ok);
        QCOMPARE(r.samplers.back().unit, 22);
        QVERIFY(r.glsl.find("layout(binding = 22) uniform sampler2D u_graphTex2;") !=
                std::string::npos);
    }

    // compileGraphPreview: only the previewed node's upstream is compiled, the previewed output
    // is returned as RGBA by type, values stay uniforms (a value edit keeps the text), and an
    // unknown node or output is refused with a reason.
    void previewCompilesTheUpstreamOnly() {
        Graph g;
        const NodeId k = add(g, "constant.color");
        const NodeId inv = add(g, "math.invert");
        const NodeId noise = add(g, "noise.perlin");
        const NodeId o = add(g, kOutputTypeId);
        mustConnect(g, link(g, k, "color", inv, "value"));
        mustConnect(g, link(g, inv, "result", o, "baseColor"));
        const CompiledGraph r = compileGraphPreview(g, inv, 0);
        QVERIFY2(r.ok, r.error.c_str());
        QCOMPARE(r.order, (std::vector<NodeId>{k, inv}));
        QCOMPARE(r.previewType, PortType::Color);
        QVERIFY(r.glsl.find("vec4 velvetGraphPreview(in vec2 uv) {") != std::string::npos);
        QVERIFY(r.glsl.find("return vec4(n2_result, 1.0);") != std::string::npos);
        QVERIFY(r.glsl.find("void velvetGraph(") == std::string::npos);
        QVERIFY(r.glsl.find("velvetGraphPerlin") == std::string::npos); // noise is not upstream
        QCOMPARE(r.valueSlots.size(), size_t(1)); // the constant's colour (invert's is linked)
        QVERIFY(g.setInputValue(k, 0, glm::vec4(0.3f, 0.1f, 0.2f, 0.0f)).ok);
        const CompiledGraph edited = compileGraphPreview(g, inv, 0);
        QCOMPARE(edited.glsl, r.glsl);
        QCOMPARE(edited.values[0], glm::vec4(0.3f, 0.1f, 0.2f, 0.0f));

        const CompiledGraph f = compileGraphPreview(g, noise, 0);
        QVERIFY(f.ok && f.previewType == PortType::Float);
        QVERIFY(f.glsl.find("return vec4(vec3(n3_value), 1.0);") != std::string::npos);
        QVERIFY(f.glsl.find("velvetGraphPerlin01") != std::string::npos);

        const CompiledGraph unknown = compileGraphPreview(g, 42, 0);
        QVERIFY(!unknown.ok && unknown.error.find("no node 42") != std::string::npos);
        const CompiledGraph noOutput = compileGraphPreview(g, o, 0);
        QVERIFY2(!noOutput.ok && noOutput.error.find("has no output 0") != std::string::npos,
                 noOutput.error.c_str());
    }

    // ---- With a GL compiler ----

    void initTestCase() {
        std::string error;
        m_gl = test::headlessContext(&error) != nullptr;
        if (!m_gl)
            qWarning("no headless GL context (%s): GLSL compile checks skipped", error.c_str());
    }

    // Every node type compiles and links, fed by values and fed by links (each connectable
    // input from a constant of a convertible type, so the conversions are compiled too).
    void everyNodeTypeCompiles_data() {
        QTest::addColumn<QString>("type");
        QTest::addColumn<bool>("linked");
        for (const NodeType& t : nodeTypes()) {
            if (t.isOutput)
                continue;
            const QString id = QString::fromUtf8(t.id.data(), int(t.id.size()));
            QTest::newRow(qPrintable(id + " values")) << id << false;
            QTest::newRow(qPrintable(id + " linked")) << id << true;
        }
    }
    void everyNodeTypeCompiles() {
        QFETCH(QString, type);
        QFETCH(bool, linked);
        Graph g;
        const NodeId o = add(g, kOutputTypeId);
        const NodeId n = add(g, type.toStdString());
        const NodeType& t = *g.node(n)->type;
        for (PortIndex p = 0; p < t.outputs.size(); ++p) {
            const PortIndex target = outputInputFor(g, n, p, o);
            if (!g.connectionTo(o, target))
                mustConnect(g, {n, p, o, target});
        }
        if (linked)
            for (PortIndex i = 0; i < t.inputs.size(); ++i) {
                if (!t.inputs[i].connectable)
                    continue;
                const char* source = t.inputs[i].type == PortType::Vec2    ? "input.uv"
                                     : t.inputs[i].type == PortType::Float ? "constant.color"
                                                                           : "constant.float";
                const NodeId s = add(g, source);
                mustConnect(g, {s, 0, n, i});
            }
        const CompiledGraph c = compileGraph(g);
        QVERIFY2(c.ok, c.error.c_str());
        QVERIFY(c.glsl.find("// node " + std::to_string(n) + ": " + std::string(t.id)) !=
                std::string::npos);
        if (!m_gl)
            QFAIL("no headless GL context (EGL surfaceless); the render half of this test cannot "
                  "run");
        render::ShaderProgram program;
        const std::string error = buildProgram(c, program);
        if (!error.empty())
            qWarning("%s\n%s", error.c_str(), c.glsl.c_str());
        QVERIFY2(error.empty(), error.c_str());
    }

    // A graph with every node type at once (helpers emitted once, names not clashing).
    void everyNodeGraphCompiles() {
        Graph g;
        const NodeId o = add(g, kOutputTypeId);
        NodeId chain = add(g, "math.add");
        mustConnect(g, link(g, chain, "result", o, "baseColor"));
        for (const NodeType& t : nodeTypes()) {
            if (t.isOutput || t.outputs.empty())
                continue;
            const NodeId n = add(g, t.id);
            if (t.outputs[0].type == PortType::Normal) {
                mustConnect(g, {n, 0, o, PortIndex(g.node(o)->type->inputIndex("normal"))});
                continue;
            }
            const NodeId next = add(g, "math.add");
            mustConnect(g, link(g, n, t.outputs[0].name, chain, "a"));
            mustConnect(g, link(g, next, "result", chain, "b"));
            chain = next;
        }
        const CompiledGraph c = compileGraph(g);
        QVERIFY2(c.ok, c.error.c_str());
        QCOMPARE(c.order.size(), g.nodes().size());
        if (qEnvironmentVariableIsSet("VELVET_DUMP_GRAPH_GLSL")) // to read what the compiler writes
            qInfo("%s", c.glsl.c_str());
        if (!m_gl)
            QFAIL("no headless GL context (EGL surfaceless); the render half of this test cannot "
                  "run");
        render::ShaderProgram program;
        const std::string error = buildProgram(c, program);
        QVERIFY2(error.empty(), error.c_str());
    }

    // Known answer: a constant colour reaches baseColor; a value edit uploads a new block and the
    // same program draws the new colour; roughness, unconnected, keeps the value passed in.
    void renderValueEdit() {
        if (!m_gl)
            QFAIL("no headless GL context (EGL surfaceless); the render half of this test cannot "
                  "run");
        Graph g;
        const NodeId o = add(g, kOutputTypeId);
        const NodeId c = add(g, "constant.color");
        mustConnect(g, link(g, c, "color", o, "baseColor"));
        QVERIFY(g.setInputValue(c, 0, {0.25f, 0.5f, 0.75f, 0.0f}));
        const CompiledGraph compiled = compileGraph(g);
        render::ShaderProgram program;
        const std::string error = buildProgram(compiled, program);
        QVERIFY2(error.empty(), error.c_str());
        for (const glm::vec4& p : draw(program, compiled, compiled.values))
            QVERIFY(near(p, {0.25f, 0.5f, 0.75f, 0.5f}));
        QVERIFY(g.setInputValue(c, 0, {1.0f, 0.0f, 0.125f, 0.0f}));
        QCOMPARE(compileGraph(g).glsl, compiled.glsl); // no recompile needed
        for (const glm::vec4& p : draw(program, compiled, graphValues(g, compiled.valueSlots)))
            QVERIFY(near(p, {1.0f, 0.0f, 0.125f, 0.5f}));
    }

    // Known answer: a checker of scale 2 over the 4x4 target alternates every 2 pixels; its value
    // inputs (scale, colours) come from the block.
    void renderChecker() {
        if (!m_gl)
            QFAIL("no headless GL context (EGL surfaceless); the render half of this test cannot "
                  "run");
        Graph g;
        const NodeId o = add(g, kOutputTypeId);
        const NodeId k = add(g, "noise.checker");
        mustConnect(g, link(g, k, "color", o, "baseColor"));
        mustConnect(g, link(g, k, "mask", o, "roughness"));
        QVERIFY(g.setInputValue(k, 1, glm::vec4(2.0f)));
        QVERIFY(g.setInputValue(k, 2, {1.0f, 0.5f, 0.0f, 0.0f}));
        QVERIFY(g.setInputValue(k, 3, {0.0f, 0.25f, 1.0f, 0.0f}));
        const CompiledGraph compiled = compileGraph(g);
        render::ShaderProgram program;
        const std::string error = buildProgram(compiled, program);
        QVERIFY2(error.empty(), error.c_str());
        const std::vector<glm::vec4> px = draw(program, compiled, compiled.values);
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const bool odd = ((x / 2) + (y / 2)) % 2 == 1;
                const glm::vec4 want =
                    odd ? glm::vec4(0.0f, 0.25f, 1.0f, 1.0f) : glm::vec4(1.0f, 0.5f, 0.0f, 0.0f);
                QVERIFY2(near(px[size_t(y * kSize + x)], want),
                         qPrintable(QString("pixel %1,%2").arg(x).arg(y)));
            }
    }

    // Known answer: gradient noise is 0 (0.5 once mapped) on every lattice point — at scale 8
    // the 4x4 pixel centres all land on one. Off the lattice (a scale edit, no recompile) it stays
    // in [0, 1] and varies; FBM too.
    void renderNoise() {
        if (!m_gl)
            QFAIL("no headless GL context (EGL surfaceless); the render half of this test cannot "
                  "run");
        for (const char* type : {"noise.perlin", "noise.fbm"}) {
            Graph g;
            const NodeId o = add(g, kOutputTypeId);
            const NodeId n = add(g, type);
            mustConnect(g, link(g, n, "value", o, "roughness"));
            const CompiledGraph compiled = compileGraph(g);
            render::ShaderProgram program;
            const std::string error = buildProgram(compiled, program);
            QVERIFY2(error.empty(), error.c_str());
            if (std::string_view(type) == "noise.perlin")
                for (const glm::vec4& p : draw(program, compiled, compiled.values))
                    QVERIFY2(std::abs(p.w - 0.5f) < 1e-6f, qPrintable(QString::number(p.w)));
            QVERIFY(g.setInputValue(n, 1, glm::vec4(3.7f)));
            float lo = 1.0f, hi = 0.0f;
            for (const glm::vec4& p :
                 draw(program, compiled, graphValues(g, compiled.valueSlots))) {
                QVERIFY(p.w >= 0.0f && p.w <= 1.0f);
                lo = std::min(lo, p.w);
                hi = std::max(hi, p.w);
            }
            QVERIFY2(hi - lo > 0.05f, type);
        }
    }

private:
    bool m_gl = false;
};

QTEST_GUILESS_MAIN(TestCoreGraphCompiler)
#include "test_core_graph_compiler.moc"
