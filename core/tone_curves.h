#pragma once
/// @file tone_curves.h
/// C++ twins of the GPU tone curves (resources/shaders/common_tonemap.glsl), for the tests that
/// compare rendered pixels with the formula and for CPU-side image work.

#include <glm/vec3.hpp>

namespace velvet::tone {

/// Khronos PBR Neutral (Khronos Group 2024, "PBR Neutral" tone mapping specification): the
/// reference formula, scene-linear in, display-linear out. Unclamped, and defined for
/// non-negative input: callers clamp negatives first and the result to [0, 1] as the GPU's
/// output does.
glm::vec3 khronosPbrNeutral(glm::vec3 color);

} // namespace velvet::tone
