#pragma once
/// @file stage_interface.h
/// Render-private: the look-dev stage's contract with the shaders — shadow maps, the ground and
/// screen-space ambient occlusion (docs/shadows.md) — generated into GLSL as the virtual include
/// "stage_interface.glsl", the way render/render_interface.cpp generates FrameBlock: the block
/// StageBlock (binding kStageUbo, instance `stage`), its texture units and the ground's material
/// ids. Same member names on both sides; offsets static_asserted in stage_interface.cpp.

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <string>

namespace velvet::render {

/// Lights that cast shadows at once (the strongest at the mesh; docs/shadows.md). Each has one
/// layer of a kShadowMapSize² depth array.
inline constexpr int kMaxShadowLights = 4;
inline constexpr int kShadowMapSize = 2048;

/// Full-resolution pixels per texel, each way, of the screen-space shadow masks and the
/// occlusion (render/shadow_mask.h, render/ao_pass.h): half the frame's size in a frame at rest,
/// a quarter in a frame drawn while the camera moves (FrameSettings::navigating), as DCC
/// viewports lower their resolution while navigating (BENCHMARKS.md, "The stage at a quarter
/// while the camera moves").
inline constexpr int kStageDownsample = 2;
inline constexpr int kNavigatingStageDownsample = 4;

/// Material ids of the ground in the G-buffer (ids 0 and 1 are the scene's material and the A/B
/// split's): the plain ground has its own record in the material table; the shadow catcher's
/// pixels show the background, darkened (lighting.frag).
inline constexpr int kGroundPlainMaterialId = 2;
inline constexpr int kGroundCatcherMaterialId = 3;

namespace stage_binding {
inline constexpr int kStageUbo = 5;
inline constexpr int kShadowCompareTex = 10; ///< sampler2DArrayShadow: hardware 2x2 PCF
inline constexpr int kShadowDepthTex = 11;   ///< sampler2DArray: raw depth, PCSS blocker search
inline constexpr int kOcclusionTex = 12;     ///< half-resolution GTAO (r) and its depth (g)
inline constexpr int kOcclusionRawTex = 13;  ///< the unblurred GTAO, read by the blur
/// The screen-space shadow mask (render/shadow_mask.h): slot s's visibility in channel s, what
/// the lighting passes read instead of the maps (unit 7 is free in the lighting passes).
inline constexpr int kShadowMaskTex = 7;
/// The mask's key (RG32F: view depth and material id of each texel's pixel), what its upsample
/// weighs texels by; above the OCIO LUTs' units (binding::kDisplayLutTexFirst = 16).
inline constexpr int kShadowKeyTex = 31;
/// The maps' depth bounds (render/shadow_depth_bounds.h), read by the mask's pass alone.
inline constexpr int kShadowBoundsTex = 30;
/// The ground's shadow mask (render/shadow_mask.h): the shadow catcher's, filtered bilinearly.
inline constexpr int kGroundShadowMaskTex = 29;
} // namespace stage_binding

/// std140, vec4 / mat4 members only. Slot s describes the s-th shadow-casting light.
struct StageBlock {
    glm::mat4 shadowViewProj[kMaxShadowLights]; ///< world -> the light's clip space
    glm::mat4 shadowView[kMaxShadowLights];     ///< world -> the light's view (looks down -z)
    /// x: 1 perspective, 0 orthographic; y near, z far (m); w source size: perspective the
    /// diameter in metres, orthographic 2 tan(angular diameter / 2)
    glm::vec4 shadowParams[kMaxShadowLights];
    /// x: metres per unit of map uv (orthographic) or per uv per metre of depth (perspective:
    /// 2 tan(fov / 2)); y: 1 / map size; zw unused
    glm::vec4 shadowScale[kMaxShadowLights];
    /// The light, for the shadow catcher: xyz position (local) or direction towards it
    /// (directional), w: 0 directional, 1 point/spot, 2 area
    glm::vec4 shadowLight[kMaxShadowLights];
    /// rgb colour x intensity (x area for area lights), w range (m)
    glm::vec4 shadowRadiance[kMaxShadowLights];
    /// xyz the way the light travels, w cos of the outer cone (-2: no cone)
    glm::vec4 shadowSpot[kMaxShadowLights];
    /// x ground height (m), y ground mode (0 off, 1 catcher, 2 plain), z fade start, w fade end (m
    /// from the mesh's centre)
    glm::vec4 ground;
    /// xyz the mesh's bounding-sphere centre, w its radius
    glm::vec4 meshSphere;
    /// x: occlusion on, y: radius (m), z: its target's width, w: height (texels)
    glm::vec4 occlusion;
    /// x: shadow slots in use; y: the frame's stage downsample (kStageDownsample or
    /// kNavigatingStageDownsample: the masks' and the occlusion's texel t stands for pixel y t);
    /// z: 1 where the occlusion rides in the shadow masks' fourth channel (render/ao_pass.h,
    /// OcclusionPass::packInto), else 0; w unused
    glm::ivec4 counts;
    /// The ground's square (stage.cpp): x, z its centre, w its half size (m); y unused. The
    /// shadow lookups test a light under the floor against it (shadow_sampling.glsl).
    glm::vec4 groundSquare;
    /// The occlusion's texels its passes drew (render/ao_pass.h's texelRect()): x0, y0, x1, y1
    /// (exclusive). Every other texel is exactly 1, so a pixel that reads none of these skips the
    /// upsample (stage_shading.glsl).
    glm::ivec4 occlusionTexels;
};

/// The GLSL text of "stage_interface.glsl".
std::string stageInterfaceGlsl();

} // namespace velvet::render
