// The fabric nodes of the material graph (category "Fabric", the leather Grain with them): their
// inputs with metadata, their outputs and the GLSL they compile to. The functions they call are
// core/graph/fabric_source.inl and grain_source.inl, stringified here for the GPU and compiled as
// C++ in fabric.cpp for the CPU twin.
#include "core/graph/fabric.h"
#include "core/graph/node_builders.h"

namespace velvet::graph {
namespace fabric {

std::string_view fabricGlsl() {
#define VELVET_FABRIC_SOURCE(...) #__VA_ARGS__
    // The macro argument arrives as one line with comments removed (the C preprocessor's
    // stringification); GLSL reads it the same. VELVET_OUT is what C++ spells as a reference.
    static const std::string text =
        std::string("// Fabric nodes: core/graph/fabric_source.inl.\n"
                    "#define VELVET_OUT(T) out T\n") +
#include "core/graph/fabric_source.inl"
        +std::string("\n// The leather grain: core/graph/grain_source.inl.\n") +
#include "core/graph/grain_source.inl"
        +"\n";
#undef VELVET_FABRIC_SOURCE
    return text;
}

} // namespace fabric

namespace detail {
namespace {

InputSpec vec2In(std::string_view name, std::string_view label, glm::vec2 def, float min, float max,
                 std::string_view tooltip, bool connectable, float softMax = 0.0f,
                 std::string_view unit = {}) {
    return value(name, label, PortType::Vec2, glm::vec4(def, 0, 0), min, max, tooltip, connectable,
                 softMax, unit);
}

InputSpec rgbIn(std::string_view name, std::string_view label, glm::vec3 def,
                std::string_view tooltip) {
    return value(name, label, PortType::Color, glm::vec4(def, 0), 0, 1, tooltip);
}

std::string args(const SnippetArgs& a, size_t from = 0) {
    std::string s;
    for (size_t i = from; i < a.in.size(); ++i)
        s += (i > from ? ", " : "") + a.in[i];
    return s;
}

/// Assigns each output from the field of the same name of the struct @p var.
void assignOutputs(const SnippetArgs& a, const NodeType& type, const std::string& var,
                   std::string& o) {
    for (size_t i = 0; i < a.out.size(); ++i)
        line(o, a.out[i] + " = " + var + "." + std::string(type.outputs[i].name) + ";");
}

const NodeType& typeOf(std::string_view id) {
    return *findNodeType(id);
}

void weaveSnippet(const SnippetArgs& a, std::string& o) {
    // The pixel's UV footprint filters the pattern (fabric_source.inl): fwidth of the UV input.
    line(o, "VelvetWeave w = velvetWeave(" + args(a) + ", fwidth(" + a.in[0] + "));");
    assignOutputs(a, typeOf("fabric.weave"), "w", o);
}

void knitSnippet(const SnippetArgs& a, std::string& o) {
    line(o, "VelvetKnit k = velvetKnit(" + args(a) + ");");
    assignOutputs(a, typeOf("fabric.knit"), "k", o);
}

void fuzzSnippet(const SnippetArgs& a, std::string& o) {
    line(o, "VelvetFuzz f = velvetFuzz(" + args(a) + ");");
    assignOutputs(a, typeOf("fabric.fuzz"), "f", o);
}

void pileSnippet(const SnippetArgs& a, std::string& o) {
    line(o, "VelvetPile p = velvetPile(" + args(a) + ");");
    assignOutputs(a, typeOf("fabric.pile"), "p", o);
}

void grainSnippet(const SnippetArgs& a, std::string& o) {
    // Filtered by the pixel's UV footprint, as the Weave (grain_source.inl).
    line(o, "VelvetGrain g = velvetGrain(" + args(a) + ", fwidth(" + a.in[0] + "));");
    assignOutputs(a, typeOf("fabric.grain"), "g", o);
}

constexpr unsigned kHelpers = HelperNoise | HelperFabric;

// The inputs are in the order of the GLSL functions' parameters (the snippets pass them as they
// come), and their defaults are the C++ twin's (fabric.h), so node and twin cannot disagree.
NodeType weaveType() {
    const fabric::WeaveParams d;
    return make(
        "fabric.weave", "Weave", "Fabric",
        "Woven cloth: warp ends along V and weft picks along U interlaced as plain, twill, satin, "
        "basket or herringbone weave, with each yarn's colour, relief and direction.",
        {uvIn(),
         scalarIn("pattern", "Pattern", d.pattern, 0, 4,
                  "0 plain, 1 twill (over/under), 2 satin (harness, step), 3 basket (group), 4 "
                  "herringbone (over/under, group). Whole numbers.",
                  false),
         scalarIn("over", "Over", d.over, 1, 16,
                  "Twill and herringbone: picks each warp end floats over (the n of n/m).", false),
         scalarIn("under", "Under", d.under, 1, 16,
                  "Twill and herringbone: picks it then passes under (the m of n/m).", false),
         scalarIn("harness", "Satin harness", d.harness, 3, 16,
                  "Satin: N of the N-harness satin; each end floats over N - 1 picks.", false),
         scalarIn("step", "Step", d.step, -16, 16,
                  "Picks the interlacing moves from one end to the next: 1 for a regular twill, "
                  "the satin counter (2 for 5-harness, 3 for 8-harness) for a satin.",
                  false),
         scalarIn("group", "Group", d.group, 1, 16,
                  "Basket: ends and picks woven as one. Herringbone: ends before the twill turns.",
                  false),
         vec2In("density", "Thread density", d.density, 0.01f, kBig,
                "Warp ends per UV unit (along U) and weft picks per UV unit (along V).", false,
                200),
         scalarIn("width", "Yarn width", d.width, 0.05f, 1,
                  "Yarn width as a fraction of the thread spacing (1: no gaps)."),
         scalarIn("roundness", "Roundness", d.roundness, 0, 2,
                  "Yarn cross-section: 0 flat tape, 1 elliptical, 2 parabolic."),
         rgbIn("warpColor", "Warp colour", d.warpColor, "Colour of the warp ends (linear)."),
         rgbIn("weftColor", "Weft colour", d.weftColor, "Colour of the weft picks (linear)."),
         scalarIn("crossingHeight", "Crossing height", d.crossingHeight, 0, 2,
                  "Height of a yarn's crown over the cloth, in thread spacings: the relief of "
                  "the normal.",
                  true, 1),
         scalarIn("roughness", "Roughness", d.roughness, 0, 1,
                  "Roughness of the yarn's crowns; hollows are a little rougher.")},
        {{"color", "Base colour", PortType::Color},
         {"height", "Height", PortType::Float},
         {"normal", "Normal", PortType::Normal},
         {"roughness", "Roughness", PortType::Float},
         {"sheen", "Sheen mask", PortType::Float},
         {"direction", "Yarn direction", PortType::Vec2},
         {"thread", "Thread id", PortType::Float},
         {"warp", "Warp mask", PortType::Float},
         {"occlusion", "Occlusion", PortType::Float}},
        weaveSnippet, kHelpers);
}

NodeType knitType() {
    const fabric::KnitParams d;
    return make(
        "fabric.knit", "Knit", "Fabric",
        "Plain jersey's face: columns of V-shaped stitches (wales along V, courses "
        "along U).",
        {uvIn(),
         vec2In("density", "Stitch density", d.density, 0.01f, kBig,
                "Wales per UV unit (along U) and courses per UV unit (along V).", false, 100),
         scalarIn("width", "Yarn width", d.width, 0.05f, 1,
                  "Yarn width as a fraction of half a wale."),
         scalarIn("roundness", "Roundness", d.roundness, 0, 2,
                  "Yarn cross-section: 0 flat tape, 1 elliptical, 2 parabolic."),
         scalarIn("lean", "Lean", d.lean, 0, 1,
                  "How far the legs of a stitch lean in (0: upright ribs)."),
         scalarIn("stitchHeight", "Stitch height", d.stitchHeight, 0, 2,
                  "Height of the yarn's crown in stitch spacings: the normal's relief.", true, 1),
         rgbIn("color", "Colour", d.color, "Yarn colour (linear).")},
        {{"color", "Base colour", PortType::Color},
         {"height", "Height", PortType::Float},
         {"normal", "Normal", PortType::Normal},
         {"direction", "Yarn direction", PortType::Vec2},
         {"occlusion", "Occlusion", PortType::Float}},
        knitSnippet, kHelpers);
}

NodeType fuzzType() {
    const fabric::FuzzParams d;
    return make(
        "fabric.fuzz", "Fibre fuzz", "Fabric",
        "Hairiness: loose fibres lying along the yarn, as streaks of colour, roughness and sheen.",
        {uvIn(),
         vec2In("direction", "Yarn direction", d.direction, -1, 1,
                "The way the fibres lie (a Weave or Knit node's yarn direction).", true),
         rgbIn("baseColor", "Base colour", d.baseColor, "The cloth's colour under the fuzz."),
         scalarIn("roughness", "Roughness", d.roughness, 0, 1, "The cloth's roughness."),
         rgbIn("fuzzColor", "Fuzz colour", d.fuzzColor, "Colour of the stray fibres (linear)."),
         scalarIn("density", "Density", d.density, 1, kBig, "Fibres per UV unit across the yarn.",
                  true, 1000),
         scalarIn("stretch", "Stretch", d.stretch, 1, 64,
                  "How many times longer than wide a streak is.", true, 16),
         scalarIn("amount", "Amount", d.amount, 0, 1, "How hairy the yarn is.")},
        {{"color", "Base colour", PortType::Color},
         {"roughness", "Roughness", PortType::Float},
         {"sheen", "Sheen mask", PortType::Float},
         {"mask", "Fuzz mask", PortType::Float}},
        fuzzSnippet, kHelpers);
}

NodeType pileType() {
    const fabric::PileParams d;
    return make("fabric.pile", "Pile", "Fabric",
                "Cut pile (velvet): fibres leaning one way, optionally crushed flat in patches.",
                {uvIn(),
                 scalarIn("angle", "Lay direction", d.angle, -360, 360,
                          "The way the pile leans, counter-clockwise from +U.", true, 0, "°"),
                 scalarIn("lean", "Lean", d.lean, 0, 2, "Tangent of the fibres' tilt (0: upright).",
                          true, 1),
                 scalarIn("crush", "Crush", d.crush, 0, 1,
                          "0: plain velvet; 1: crushed velvet, patches pressed flat."),
                 scalarIn("scale", "Crush scale", d.scale, 0, kBig, "Crushed patches per UV unit.",
                          true, 32)},
                {{"sheen", "Sheen mask", PortType::Float},
                 {"normal", "Normal", PortType::Normal},
                 {"roughness", "Roughness", PortType::Float},
                 {"crush", "Crush mask", PortType::Float}},
                pileSnippet, kHelpers);
}

NodeType grainType() {
    const fabric::GrainParams d;
    return make(
        "fabric.grain", "Leather grain", "Fabric",
        "Pebbled leather: domed cells of a cellular (Voronoi) pattern parted by creases, with "
        "their relief, colour, roughness and a crease (cavity) mask.",
        {uvIn(),
         scalarIn("scale", "Scale", d.scale, 0.01f, kBig,
                  "Cells per UV unit along U and V (the mean cell spacing is 1 / scale).", true,
                  200),
         scalarIn("irregularity", "Irregularity", d.irregularity, 0, 1,
                  "How far each cell's centre strays from a square grid (0: squares)."),
         scalarIn("creaseWidth", "Crease width", d.creaseWidth, 0.01f, 0.5f,
                  "Width of a crease's rounded shoulder, as a fraction of the cell spacing."),
         scalarIn("dome", "Dome", d.dome, 0, 1,
                  "How domed the cells' tops are (0: flat tops with rounded edges)."),
         scalarIn("depth", "Depth", d.depth, 0, 2,
                  "Height of a cell's top over its creases, in cell spacings: the relief of the "
                  "normal.",
                  true, 0.5f),
         rgbIn("color", "Colour", d.color, "Colour of the cells' tops (linear)."),
         rgbIn("creaseColor", "Crease colour", d.creaseColor,
               "Colour at the bottom of the creases (linear)."),
         scalarIn("roughness", "Roughness", d.roughness, 0, 1,
                  "Roughness of the cells' tops (polished by wear)."),
         scalarIn("creaseRoughness", "Crease roughness", d.creaseRoughness, 0, 1,
                  "Roughness at the bottom of the creases.")},
        {{"color", "Base colour", PortType::Color},
         {"height", "Height", PortType::Float},
         {"normal", "Normal", PortType::Normal},
         {"roughness", "Roughness", PortType::Float},
         {"cavity", "Cavity", PortType::Float},
         {"occlusion", "Occlusion", PortType::Float},
         {"cell", "Cell id", PortType::Float}},
        grainSnippet, kHelpers);
}

} // namespace

void appendFabricNodes(std::vector<NodeType>& types) {
    types.push_back(weaveType());
    types.push_back(knitType());
    types.push_back(fuzzType());
    types.push_back(pileType());
    types.push_back(grainType());
}

} // namespace detail
} // namespace velvet::graph
