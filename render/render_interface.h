#pragma once
/// @file render_interface.h
/// Render-private: the C++ side of the contracts the renderer's shaders share with it, described
/// once here and generated into GLSL as the virtual include "render_interface.glsl" (the way
/// render/gbuffer_layout.cpp generates "gbuffer_layout.glsl"; Filament's UibStructs.h and
/// UibGenerator do the same for its per-view block). Members carry the same names on both sides;
/// render_interface.cpp static_asserts every member's std140 offset and each block's size.
///
/// Generated: the per-frame block (FrameBlock, binding kFrameUbo, instance `frame`), the IBL
/// block (IblBlock, binding kIblUbo, instance `ibl`), MAX_LIGHTS, the debug-view ids
/// (DEBUG_FINAL … from render::DebugView) and `bool isLightView(int)` / `bool isLobeView(int)`,
/// the same tests as the C++ isLightView() / isLobeView() below; the BRDF term ids
/// (DISTRIBUTION_*, VISIBILITY_*, FRESNEL_*, DIFFUSE_*, SHEEN_CHARLIE_*: core/material.h's enums)
/// and the built-in tone mappers (TONEMAP_*: ToneMapper); the material record
/// (`struct GpuMaterial`, render/material_table.h, read from the std430 material table). The post
/// chain's PostFrame block goes to its own include, "post_interface.glsl" (postInterfaceGlsl()).

#include "render/renderer.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <string>

namespace velvet::render {

/// The per-frame constants (std140; vec4 / mat4 members only).
struct FrameBlock {
    glm::mat4 viewMatrix, projMatrix, invProjMatrix, invViewMatrix, viewProjMatrix;
    glm::vec4 cameraPosition;
    glm::vec4 viewport;
    glm::vec4 envSh[9];
    glm::vec4 envParams;
    glm::vec4 ambientRadiance;
    glm::vec4 backgroundColor;
    glm::ivec4 modes;
    glm::vec4 post;
    glm::vec4 lightDirection[kMaxDirectionalLights];
    glm::vec4 lightRadiance[kMaxDirectionalLights];
};

/// The image-based lighting state (std140, vec4 only).
struct IblBlock {
    glm::vec4 state;      ///< cube ready, its last level, DFG LUT ready, multiple scattering on
    glm::vec4 background; ///< blurred background level, time (s), unused, unused
    /// Reflections sampled (FrameSettings::reflectionSamples): per pixel this frame (0: the split
    /// sum), over the whole mean, the sample set, pixels per side of one output pixel.
    glm::vec4 reflection;
};

/// The post chain's per-frame constants (std140, mat4 / vec4 only): the block PostFrame
/// (binding kPostFrameUbo, instance `post`) of the virtual include "post_interface.glsl".
struct PostFrameBlock {
    glm::mat4 viewProj, invViewProj, prevViewProj, invProj;
    glm::vec4 viewport; ///< full-resolution width, height, 1/width, 1/height
    glm::vec4 misc;     ///< x: time in seconds, y: exposure multiplier of the frame settings
};

/// Views the point, spot and area lights contribute to (the local-light passes run for these).
bool isLightView(DebugView view);
/// The lobe views: direct light through one lobe (DiffuseOnly .. ClearcoatOnly).
bool isLobeView(DebugView view);

/// The GLSL text of "render_interface.glsl".
std::string renderInterfaceGlsl();
/// The text of "post_interface.glsl": the PostFrame block (PostFrameBlock).
std::string postInterfaceGlsl();

} // namespace velvet::render
