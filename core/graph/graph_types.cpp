#include "core/graph/graph_types.h"

#include "core/graph/glsl_format.h"

#include <array>
#include <charconv>
#include <cmath>

namespace velvet::graph {
namespace {

// The conversion table of graph_types.h, rows: from, columns: to (Float, Vec2, Color, Vec4,
// Normal). Each entry is a GLSL template in which '$' stands for the expression; "" refuses.
constexpr int kTypes = int(PortType::Count);
constexpr std::array<std::array<std::string_view, kTypes>, kTypes> kConversions{{
    {"$", "vec2($)", "vec3($)", "vec4(vec3($), 1.0)", ""},
    {"", "$", "vec3($, 0.0)", "vec4($, 0.0, 1.0)", ""},
    {"dot($, vec3(0.2126, 0.7152, 0.0722))", "($).xy", "$", "vec4($, 1.0)", ""},
    {"dot(($).rgb, vec3(0.2126, 0.7152, 0.0722))", "($).xy", "($).rgb", "$", ""},
    {"", "", "", "", "$"},
}};

} // namespace

std::string toString(const Connection& c) {
    return std::to_string(c.outNode) + "." + std::to_string(c.outPort) + " -> " +
           std::to_string(c.inNode) + "." + std::to_string(c.inPort);
}

std::string_view portTypeName(PortType t) {
    constexpr std::array<std::string_view, kTypes> names{"float", "vec2", "color", "vec4",
                                                         "normal"};
    return names[size_t(t)];
}

std::string_view portTypeGlsl(PortType t) {
    constexpr std::array<std::string_view, kTypes> names{"float", "vec2", "vec3", "vec4", "vec3"};
    return names[size_t(t)];
}

int portTypeComponents(PortType t) {
    constexpr std::array<int, kTypes> n{1, 2, 3, 4, 3};
    return n[size_t(t)];
}

bool canConvert(PortType from, PortType to) {
    return !kConversions[size_t(from)][size_t(to)].empty();
}

std::optional<std::string> convertGlsl(const std::string& expr, PortType from, PortType to) {
    const std::string_view pattern = kConversions[size_t(from)][size_t(to)];
    if (pattern.empty())
        return std::nullopt;
    std::string out;
    for (char c : pattern) {
        if (c == '$')
            out += expr;
        else
            out += c;
    }
    return out;
}

std::string glslFloat(float v) {
    if (!std::isfinite(v))
        return "0.0";
    char buf[32];
    const auto res = std::to_chars(buf, buf + sizeof(buf), v);
    std::string s(buf, res.ptr);
    if (s.find_first_of(".e") == std::string::npos)
        s += ".0";
    return s;
}

} // namespace velvet::graph
