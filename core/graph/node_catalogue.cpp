#include "core/graph/node_catalogue.h"

#include "core/graph/glsl_format.h"
#include "core/graph/node_builders.h"

#include <algorithm>
#include <array>
#include <cctype>

namespace velvet::graph {
namespace {

using namespace detail;

// ---- Snippets ---------------------------------------------------------------------------------
// Each assigns its outputs (SnippetArgs::out) from its inputs (SnippetArgs::in).

void constantSnippet(const SnippetArgs& a, std::string& o) {
    line(o, a.out[0] + " = " + a.in[0] + ";");
}

void uvSnippet(const SnippetArgs& a, std::string& o) {
    line(o, a.out[0] + " = uv;");
}

// Scale, then rotate (degrees, counter-clockwise about the UV origin), then offset: the order of
// Blender's Mapping node (type Point), so artists' numbers carry over.
void imageSnippet(const SnippetArgs& a, std::string& o) {
    line(o, "vec2 t = velvetGraphUvTransform(" + a.in[0] + ", " + a.in[1] + ", " + a.in[2] + ", " +
                a.in[3] + ");");
    line(o, "vec4 s = texture(" + a.sampler + ", t);");
    line(o, a.out[0] + " = s.rgb;");
    line(o, a.out[1] + " = s.a;");
}

// The region is in pixels of the atlas image (x, y, width, height; row 0 is the image's first row
// as the renderer uploads it). UVs wrap inside the region, so a region tiles like a texture.
void atlasSnippet(const SnippetArgs& a, std::string& o) {
    line(o, "vec4 r = " + a.in[1] + ";");
    line(o, "vec2 size = vec2(textureSize(" + a.sampler + ", 0));");
    line(o, "vec2 t = (r.xy + fract(" + a.in[0] + ") * r.zw) / max(size, vec2(1.0));");
    line(o, "vec4 s = texture(" + a.sampler + ", t);");
    line(o, a.out[0] + " = s.rgb;");
    line(o, a.out[1] + " = s.a;");
}

void splitSnippet(const SnippetArgs& a, std::string& o) {
    line(o, "vec3 c = " + a.in[0] + ";");
    line(o, a.out[0] + " = c.r;");
    line(o, a.out[1] + " = c.g;");
    line(o, a.out[2] + " = c.b;");
}

void combineSnippet(const SnippetArgs& a, std::string& o) {
    line(o, a.out[0] + " = vec3(" + a.in[0] + ", " + a.in[1] + ", " + a.in[2] + ");");
}

void addSnippet(const SnippetArgs& a, std::string& o) {
    line(o, a.out[0] + " = " + a.in[0] + " + " + a.in[1] + ";");
}

void multiplySnippet(const SnippetArgs& a, std::string& o) {
    line(o, a.out[0] + " = " + a.in[0] + " * " + a.in[1] + ";");
}

void mixSnippet(const SnippetArgs& a, std::string& o) {
    line(o, a.out[0] + " = mix(" + a.in[0] + ", " + a.in[1] + ", " + a.in[2] + ");");
}

// Levels as in Photoshop / Substance: normalise [inLow, inHigh] (either order), apply gamma,
// map to [outLow, outHigh].
void remapSnippet(const SnippetArgs& a, std::string& o) {
    line(o, "float d = " + a.in[2] + " - " + a.in[1] + ";");
    line(o, "d = abs(d) < 1e-6 ? 1e-6 : d;");
    line(o, "vec3 t = clamp((" + a.in[0] + " - " + a.in[1] + ") / d, 0.0, 1.0);");
    line(o, "t = pow(t, vec3(1.0 / max(" + a.in[3] + ", 1e-3)));");
    line(o, a.out[0] + " = mix(vec3(" + a.in[4] + "), vec3(" + a.in[5] + "), t);");
}

void invertSnippet(const SnippetArgs& a, std::string& o) {
    line(o, a.out[0] + " = vec3(1.0) - " + a.in[0] + ";");
}

void clampSnippet(const SnippetArgs& a, std::string& o) {
    line(o, a.out[0] + " = clamp(" + a.in[0] + ", vec3(" + a.in[1] + "), vec3(" + a.in[2] + "));");
}

// pow() is undefined for negative bases in GLSL, so the base is clamped at 0.
void powerSnippet(const SnippetArgs& a, std::string& o) {
    line(o, a.out[0] + " = pow(max(" + a.in[0] + ", vec3(0.0)), vec3(" + a.in[1] + "));");
}

void perlinSnippet(const SnippetArgs& a, std::string& o) {
    line(o, a.out[0] + " = velvetGraphPerlin01(" + a.in[0] + " * " + a.in[1] + ");");
}

void fbmSnippet(const SnippetArgs& a, std::string& o) {
    line(o, a.out[0] + " = velvetGraphFbm(" + a.in[0] + " * " + a.in[1] + ", " + a.in[2] + ", " +
                a.in[3] + ", " + a.in[4] + ");");
}

void checkerSnippet(const SnippetArgs& a, std::string& o) {
    line(o, "vec2 c = floor(" + a.in[0] + " * " + a.in[1] + ");");
    line(o, "float k = mod(c.x + c.y, 2.0);");
    line(o, a.out[0] + " = mix(" + a.in[2] + ", " + a.in[3] + ", k);");
    line(o, a.out[1] + " = k;");
}

// A linear ramp from 0 to 1 across the unit square along the direction at @p angle (degrees,
// counter-clockwise from +U); 0 degrees gives U.
void gradientSnippet(const SnippetArgs& a, std::string& o) {
    line(o, "float r = radians(" + a.in[1] + ");");
    line(o, "vec2 dir = vec2(cos(r), sin(r));");
    line(o, "float extent = abs(dir.x) + abs(dir.y);");
    line(o, a.out[0] + " = clamp(dot(" + a.in[0] + " - vec2(0.5), dir) / extent + 0.5, 0.0, 1.0);");
}

// Tangent-space normal maps store n * 0.5 + 0.5 (OpenGL convention, +Y up; glTF 2.0 3.9.3);
// strength scales XY before renormalising, as glTF's normalTexture.scale does.
void normalMapSnippet(const SnippetArgs& a, std::string& o) {
    line(o, "vec3 n = " + a.in[0] + " * 2.0 - 1.0;");
    line(o, "n.xy *= " + a.in[1] + ";");
    line(o, "float len = length(n);");
    line(o, a.out[0] + " = len > 1e-6 ? n / len : vec3(0.0, 0.0, 1.0);");
}

// ---- The material output ----------------------------------------------------------------------

struct OutputNames {
    std::array<std::string, kParamCount> names; // "" for Choice parameters
    std::vector<ParamId> params;                // per output input; Count for the map inputs
    std::array<int, kParamCount> inputOf{};
};

// "lobes.base.color" -> "baseColor", "lobes.base.roughness" -> "roughness",
// "lobes.sheen.color" -> "sheenColor", "lobes.emission.strength" -> "emissionStrength".
std::string fieldName(std::string_view id) {
    constexpr std::string_view prefix = "lobes.";
    if (id.substr(0, prefix.size()) == prefix)
        id.remove_prefix(prefix.size());
    const size_t dot = id.find('.');
    if (dot == std::string_view::npos)
        return std::string(id);
    const std::string_view lobe = id.substr(0, dot);
    std::string field(id.substr(dot + 1));
    if (lobe == "base" && field != "color")
        return field;
    field[0] = char(std::toupper(static_cast<unsigned char>(field[0])));
    return std::string(lobe) + field;
}

const OutputNames& outputNames() {
    static const OutputNames names = [] {
        OutputNames n;
        n.inputOf.fill(-1);
        for (int i = 0; i < kParamCount; ++i) {
            const ParamMeta& m = paramMetas()[size_t(i)];
            if (m.type == ParamType::Choice)
                continue;
            n.names[size_t(i)] = fieldName(m.id);
            n.inputOf[size_t(i)] = int(n.params.size());
            n.params.push_back(ParamId(i));
        }
        for (int i = 0; i < 4; ++i) // occlusion, normal, clearcoatNormal, anisotropyDirection
            n.params.push_back(ParamId::Count);
        return n;
    }();
    return names;
}

void outputSnippet(const SnippetArgs& a, std::string& o) {
    const auto& params = outputNames().params;
    for (size_t i = 0; i < a.in.size(); ++i) {
        if (!a.connected[i])
            continue;
        const std::string& field = a.outputFields[i];
        std::string value = a.in[i];
        // Values leave the graph within the parameter's hard range, as Material::setValue keeps
        // them; the map inputs are already in range (occlusion is clamped to [0, 1]).
        if (params[i] != ParamId::Count) {
            const ParamMeta& m = paramMeta(params[i]);
            value = "clamp(" + value + ", " + glslFloat(m.min) + ", " + glslFloat(m.max) + ")";
        } else if (field == "occlusion") {
            value = "clamp(" + value + ", 0.0, 1.0)";
        }
        line(o, "m." + field + " = " + value + ";");
    }
}

NodeType outputType() {
    NodeType t;
    t.id = kOutputTypeId;
    t.label = "Material output";
    t.category = "Output";
    t.tooltip =
        "The material: each connected input replaces its parameter; unconnected inputs keep "
        "the material's value.";
    t.isOutput = true;
    t.glsl = outputSnippet;
    const OutputNames& names = outputNames();
    for (ParamId p : names.params) {
        if (p == ParamId::Count)
            continue;
        const ParamMeta& m = paramMeta(p);
        InputSpec s;
        s.name = names.names[size_t(p)];
        s.label = m.label;
        s.type = m.type == ParamType::Color ? PortType::Color : PortType::Float;
        s.fallback = Fallback::Material;
        s.defaultValue = glm::vec4(m.defaultValue, 0.0f);
        s.min = m.min;
        s.max = m.max;
        s.softMax = m.softMax;
        s.unit = m.unit;
        s.tooltip = m.tooltip;
        t.inputs.push_back(s);
    }
    InputSpec occlusion;
    occlusion.name = "occlusion";
    occlusion.label = "Ambient occlusion";
    occlusion.fallback = Fallback::Material;
    occlusion.defaultValue = glm::vec4(1, 0, 0, 0);
    occlusion.tooltip = "Ambient occlusion (1: none), before the occlusion strength.";
    t.inputs.push_back(occlusion);
    for (auto [name, label, tip] :
         {std::array<std::string_view, 3>{"normal", "Normal",
                                          "Tangent-space normal of the base (a Normal map node)."},
          std::array<std::string_view, 3>{"clearcoatNormal", "Clearcoat normal",
                                          "Tangent-space normal of the clear coat."}}) {
        InputSpec n;
        n.name = name;
        n.label = label;
        n.type = PortType::Normal;
        n.fallback = Fallback::Material;
        n.defaultValue = glm::vec4(0, 0, 1, 0);
        n.min = -1.0f;
        n.tooltip = tip;
        t.inputs.push_back(n);
    }
    // KHR_materials_anisotropy's direction (its texture's RG after remapping to [-1, 1]): a
    // tangent-space 2D vector, +X the mesh tangent; a Weave's yarn direction feeds it. The
    // renderer normalises it and rotates it by the anisotropy rotation.
    InputSpec direction;
    direction.name = "anisotropyDirection";
    direction.label = "Anisotropy direction";
    direction.type = PortType::Vec2;
    direction.fallback = Fallback::Material;
    direction.defaultValue = glm::vec4(1, 0, 0, 0);
    direction.min = -1.0f;
    direction.tooltip =
        "Tangent-space direction of the anisotropic stretch (+X: the tangent), before the "
        "anisotropy rotation.";
    t.inputs.push_back(direction);
    return t;
}

// ---- The catalogue ----------------------------------------------------------------------------

NodeType textureType(std::string_view id, std::string_view label, std::string_view tooltip,
                     std::vector<InputSpec> inputs, SnippetFn fn, unsigned helpers) {
    NodeType t = make(id, label, "Texture", tooltip, std::move(inputs),
                      {{"color", "Colour", PortType::Color}, {"alpha", "Alpha", PortType::Float}},
                      fn, helpers);
    t.samplesTexture = true;
    t.settings = {{"file", "File", "", "Image path (absolute, or relative to the document)."},
                  {"colorSpace", "Colour space", "",
                   "Input colour space of the image (an OCIO name, \"Raw\" for data); empty: the "
                   "configuration's file rules."}};
    return t;
}

std::vector<NodeType> buildCatalogue() {
    const glm::vec4 one(1.0f, 1.0f, 1.0f, 1.0f);
    std::vector<NodeType> types;
    // Input
    types.push_back(make("constant.float", "Value", "Input", "A constant number.",
                         {scalarIn("value", "Value", 0.5f, -kBig, kBig, "The number.", false, 1)},
                         {{"value", "Value", PortType::Float}}, constantSnippet));
    types.push_back(make("constant.color", "Colour", "Input", "A constant scene-linear colour.",
                         {colorIn("color", "Colour", 0.8f, 0, 1, "The colour (linear).", false)},
                         {{"color", "Colour", PortType::Color}}, constantSnippet));
    types.push_back(make("input.uv", "UV", "Input", "The mesh's texture coordinates.", {},
                         {{"uv", "UV", PortType::Vec2}}, uvSnippet));
    // Texture
    types.push_back(textureType(
        "texture.image", "Image texture", "Samples an image file through a UV transform.",
        {uvIn(),
         value("scale", "Scale", PortType::Vec2, one, -kBig, kBig, "UV scale (tiling).", false),
         value("offset", "Offset", PortType::Vec2, glm::vec4(0), -kBig, kBig,
               "UV offset, applied after scale and rotation.", false),
         scalarIn("rotation", "Rotation", 0, -360, 360,
                  "UV rotation in degrees, counter-clockwise, after scale.", false, 0, "°")},
        imageSnippet, HelperUvTransform));
    types.push_back(textureType(
        "texture.atlasRegion", "Atlas region",
        "Samples one rectangle of an atlas image; UVs wrap inside the rectangle.",
        {uvIn(), value("region", "Region", PortType::Vec4, glm::vec4(0, 0, 64, 64), 0, 65536,
                       "x, y, width, height in pixels of the atlas image.", false, 0, "px")},
        atlasSnippet, HelperNone));
    // Channels
    types.push_back(make(
        "channel.split", "Split RGB", "Channels", "A colour's three channels.",
        {colorIn("color", "Colour", 0, -kBig, kBig, "Colour to split.")},
        {{"r", "R", PortType::Float}, {"g", "G", PortType::Float}, {"b", "B", PortType::Float}},
        splitSnippet));
    types.push_back(make("channel.combine", "Combine RGB", "Channels", "Three numbers as a colour.",
                         {scalarIn("r", "R", 0, -kBig, kBig, "Red channel.", true, 1),
                          scalarIn("g", "G", 0, -kBig, kBig, "Green channel.", true, 1),
                          scalarIn("b", "B", 0, -kBig, kBig, "Blue channel.", true, 1)},
                         {{"color", "Colour", PortType::Color}}, combineSnippet));
    types.push_back(make("channel.unpackOrm", "Unpack ORM", "Channels",
                         "Unreal / glTF packing: R occlusion, G roughness, B metallic.",
                         {colorIn("packed", "ORM", 1, 0, 1, "A packed ORM texture (Raw).")},
                         {{"occlusion", "Occlusion", PortType::Float},
                          {"roughness", "Roughness", PortType::Float},
                          {"metallic", "Metallic", PortType::Float}},
                         splitSnippet));
    types.push_back(make("channel.packOrm", "Pack ORM", "Channels",
                         "R occlusion, G roughness, B metallic in one colour.",
                         {scalarIn("occlusion", "Occlusion", 1, 0, 1, "Ambient occlusion."),
                          scalarIn("roughness", "Roughness", 0.5f, 0, 1, "Roughness."),
                          scalarIn("metallic", "Metallic", 0, 0, 1, "Metallic.")},
                         {{"packed", "ORM", PortType::Color}}, combineSnippet));
    types.push_back(make("channel.unpackSrm", "Unpack spec/rough/metal", "Channels",
                         "The seed documents' material atlas: R specular, G roughness, B metallic.",
                         {colorIn("packed", "SRM", 1, 0, 1, "A packed material atlas (Raw).")},
                         {{"specular", "Specular", PortType::Float},
                          {"roughness", "Roughness", PortType::Float},
                          {"metallic", "Metallic", PortType::Float}},
                         splitSnippet));
    types.push_back(make("channel.packSrm", "Pack spec/rough/metal", "Channels",
                         "R specular, G roughness, B metallic in one colour.",
                         {scalarIn("specular", "Specular", 1, 0, 1, "Specular weight."),
                          scalarIn("roughness", "Roughness", 0.5f, 0, 1, "Roughness."),
                          scalarIn("metallic", "Metallic", 0, 0, 1, "Metallic.")},
                         {{"packed", "SRM", PortType::Color}}, combineSnippet));
    // Math: on colours, channel by channel; floats convert by splat and back by luminance, which
    // for a grey is the value itself (graph_types.h).
    const OutputSpec result{"result", "Result", PortType::Color};
    types.push_back(make("math.add", "Add", "Math", "a + b",
                         {colorIn("a", "A", 0, -kBig, kBig, "First term."),
                          colorIn("b", "B", 0, -kBig, kBig, "Second term.")},
                         {result}, addSnippet));
    types.push_back(make("math.multiply", "Multiply", "Math", "a × b",
                         {colorIn("a", "A", 1, -kBig, kBig, "First factor."),
                          colorIn("b", "B", 1, -kBig, kBig, "Second factor.")},
                         {result}, multiplySnippet));
    types.push_back(make("math.mix", "Mix", "Math", "Linear blend: a where factor is 0, b at 1.",
                         {colorIn("a", "A", 0, -kBig, kBig, "At factor 0."),
                          colorIn("b", "B", 1, -kBig, kBig, "At factor 1."),
                          scalarIn("factor", "Factor", 0.5f, 0, 1, "Blend factor.")},
                         {result}, mixSnippet));
    types.push_back(
        make("math.remap", "Levels", "Math",
             "Maps [in low, in high] to [out low, out high] with a gamma, clamping outside.",
             {colorIn("value", "Value", 0, -kBig, kBig, "Input."),
              scalarIn("inLow", "In low", 0, -kBig, kBig, "Input black point.", true, 1),
              scalarIn("inHigh", "In high", 1, -kBig, kBig, "Input white point.", true, 1),
              scalarIn("gamma", "Gamma", 1, 0.01f, 10, "Mid-tone gamma (1: linear)."),
              scalarIn("outLow", "Out low", 0, -kBig, kBig, "Output black point.", true, 1),
              scalarIn("outHigh", "Out high", 1, -kBig, kBig, "Output white point.", true, 1)},
             {result}, remapSnippet));
    types.push_back(make("math.invert", "Invert", "Math", "1 - value",
                         {colorIn("value", "Value", 0, -kBig, kBig, "Input.")}, {result},
                         invertSnippet));
    types.push_back(make("math.clamp", "Clamp", "Math", "Limits each channel to [min, max].",
                         {colorIn("value", "Value", 0, -kBig, kBig, "Input."),
                          scalarIn("min", "Min", 0, -kBig, kBig, "Lower bound.", true, 1),
                          scalarIn("max", "Max", 1, -kBig, kBig, "Upper bound.", true, 1)},
                         {result}, clampSnippet));
    types.push_back(make("math.power", "Power", "Math", "max(value, 0) ^ exponent",
                         {colorIn("value", "Value", 0.5f, -kBig, kBig, "Base."),
                          scalarIn("exponent", "Exponent", 2, 0, 100, "Exponent.", true, 8)},
                         {result}, powerSnippet));
    // Noise
    const InputSpec noiseScale =
        scalarIn("scale", "Scale", 8, 0, kBig, "Features per UV unit.", true, 64);
    types.push_back(make("noise.perlin", "Perlin noise", "Noise",
                         "Gradient noise (Perlin 2002) in [0, 1].", {uvIn(), noiseScale},
                         {{"value", "Value", PortType::Float}}, perlinSnippet, HelperNoise));
    types.push_back(
        make("noise.fbm", "FBM noise", "Noise", "Fractal Brownian motion: octaves of Perlin noise.",
             {uvIn(), noiseScale,
              scalarIn("octaves", "Octaves", 5, 1, 8, "Number of octaves (whole numbers).", false),
              scalarIn("lacunarity", "Lacunarity", 2, 1, 4, "Frequency ratio between octaves."),
              scalarIn("gain", "Gain", 0.5f, 0, 1, "Amplitude ratio between octaves.")},
             {{"value", "Value", PortType::Float}}, fbmSnippet, HelperNoise));
    types.push_back(make("noise.checker", "Checker", "Noise", "Alternating squares of two colours.",
                         {uvIn(), noiseScale, colorIn("colorA", "Colour A", 0.9f, 0, 1, "Even."),
                          colorIn("colorB", "Colour B", 0.1f, 0, 1, "Odd.")},
                         {{"color", "Colour", PortType::Color}, {"mask", "Mask", PortType::Float}},
                         checkerSnippet));
    types.push_back(make("noise.gradient", "Gradient", "Noise",
                         "A linear 0-to-1 ramp across the UV square.",
                         {uvIn(), scalarIn("angle", "Angle", 0, -360, 360,
                                           "Direction, counter-clockwise from +U.", true, 0, "°")},
                         {{"value", "Value", PortType::Float}}, gradientSnippet));
    // Vector
    types.push_back(
        make("normal.map", "Normal map", "Vector",
             "Decodes a tangent-space normal texture (sampled Raw, OpenGL +Y up).",
             {value("color", "Colour", PortType::Color, glm::vec4(0.5f, 0.5f, 1.0f, 0.0f), 0, 1,
                    "The normal texture's colour."),
              scalarIn("strength", "Strength", 1, 0, 2, "Scale of the normal's XY.")},
             {{"normal", "Normal", PortType::Normal}}, normalMapSnippet));
    appendFabricNodes(types);
    types.push_back(outputType());
    return types;
}

const std::vector<NodeType>& catalogue() {
    static const std::vector<NodeType> types = buildCatalogue();
    return types;
}

template <typename Spec>
int indexOf(const std::vector<Spec>& specs, std::string_view name) {
    for (size_t i = 0; i < specs.size(); ++i)
        if (specs[i].name == name)
            return int(i);
    return -1;
}

} // namespace

glm::vec4 constrainInputValue(const InputSpec& spec, glm::vec4 value) {
    const int count = portTypeComponents(spec.type);
    glm::vec4 v(0.0f);
    for (int i = 0; i < count; ++i)
        v[i] = std::clamp(value[i], spec.min, spec.max);
    return v;
}

int NodeType::inputIndex(std::string_view name) const {
    return indexOf(inputs, name);
}
int NodeType::outputIndex(std::string_view name) const {
    return indexOf(outputs, name);
}
int NodeType::settingIndex(std::string_view name) const {
    return indexOf(settings, name);
}

std::span<const NodeType> nodeTypes() {
    return catalogue();
}

const NodeType* findNodeType(std::string_view id) {
    for (const NodeType& t : catalogue())
        if (t.id == id)
            return &t;
    return nullptr;
}

std::span<const std::string_view> nodeTypeIds() {
    static const std::vector<std::string_view> ids = [] {
        std::vector<std::string_view> v;
        for (const NodeType& t : catalogue())
            v.push_back(t.id);
        return v;
    }();
    return ids;
}

int outputInputForParam(ParamId id) {
    if (id == ParamId::Count)
        return -1;
    return outputNames().inputOf[size_t(id)];
}

ParamId paramForOutputInput(PortIndex input) {
    const auto& params = outputNames().params;
    return input < params.size() ? params[input] : ParamId::Count;
}

} // namespace velvet::graph
