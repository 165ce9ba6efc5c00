#pragma once
/// @file glsl_format.h
/// Internal to core/graph: numbers as GLSL literals, written the same on every machine so that
/// the same graph always compiles to byte-identical text.

#include <string>

namespace velvet::graph {

/// The shortest decimal that reads back as @p v, always with a '.' or an exponent so GLSL reads
/// a float: 1 -> "1.0", 0.03 -> "0.03", 1e+30 -> "1e+30". Non-finite values become "0.0".
std::string glslFloat(float v);

} // namespace velvet::graph
