#include "render/stage_interface.h"

#include "render/shadow_depth_bounds.h"

#include <cstddef>

namespace velvet::render {

// std140 with 16-byte members: each member starts where the one before ends.
static_assert(offsetof(StageBlock, shadowView) == 64 * kMaxShadowLights);
static_assert(offsetof(StageBlock, shadowParams) == 128 * kMaxShadowLights);
static_assert(offsetof(StageBlock, shadowScale) == 144 * kMaxShadowLights);
static_assert(offsetof(StageBlock, shadowLight) == 160 * kMaxShadowLights);
static_assert(offsetof(StageBlock, shadowRadiance) == 176 * kMaxShadowLights);
static_assert(offsetof(StageBlock, shadowSpot) == 192 * kMaxShadowLights);
static_assert(offsetof(StageBlock, ground) == 208 * kMaxShadowLights);
static_assert(offsetof(StageBlock, meshSphere) == 208 * kMaxShadowLights + 16);
static_assert(offsetof(StageBlock, occlusion) == 208 * kMaxShadowLights + 32);
static_assert(offsetof(StageBlock, counts) == 208 * kMaxShadowLights + 48);
static_assert(offsetof(StageBlock, groundSquare) == 208 * kMaxShadowLights + 64);
static_assert(offsetof(StageBlock, occlusionTexels) == 208 * kMaxShadowLights + 80);
static_assert(sizeof(StageBlock) == 208 * kMaxShadowLights + 96);

std::string stageInterfaceGlsl() {
    const std::string n = std::to_string(kMaxShadowLights);
    std::string s = "// Generated from render/stage_interface.cpp; do not edit.\n";
    s += "#define MAX_SHADOW_LIGHTS " + n + "\n";
    s += "#define GROUND_PLAIN_MATERIAL_ID " + std::to_string(kGroundPlainMaterialId) + "\n";
    s += "#define GROUND_CATCHER_MATERIAL_ID " + std::to_string(kGroundCatcherMaterialId) + "\n";
    s += "#define BINDING_SHADOW_COMPARE_TEX " + std::to_string(stage_binding::kShadowCompareTex) +
         "\n";
    s +=
        "#define BINDING_SHADOW_DEPTH_TEX " + std::to_string(stage_binding::kShadowDepthTex) + "\n";
    s += "#define BINDING_OCCLUSION_TEX " + std::to_string(stage_binding::kOcclusionTex) + "\n";
    s += "#define BINDING_OCCLUSION_RAW_TEX " + std::to_string(stage_binding::kOcclusionRawTex) +
         "\n";
    s += "#define BINDING_SHADOW_MASK_TEX " + std::to_string(stage_binding::kShadowMaskTex) + "\n";
    s += "#define BINDING_SHADOW_KEY_TEX " + std::to_string(stage_binding::kShadowKeyTex) + "\n";
    s += "#define BINDING_SHADOW_BOUNDS_TEX " + std::to_string(stage_binding::kShadowBoundsTex) +
         "\n";
    s += "#define BINDING_GROUND_SHADOW_MASK_TEX " +
         std::to_string(stage_binding::kGroundShadowMaskTex) + "\n";
    s += "#define SHADOW_BOUNDS_SIZE " + std::to_string(kShadowMapSize / kShadowBoundsBlock) + "\n";
    s += "#define SHADOW_BOUNDS_LEVELS " +
         std::to_string(shadowBoundsLevels(kShadowMapSize / kShadowBoundsBlock)) + "\n";
    s += "layout(std140, binding = " + std::to_string(stage_binding::kStageUbo) +
         ") uniform StageBlock {\n"
         "    mat4 shadowViewProj[" +
         n +
         "];\n"
         "    mat4 shadowView[" +
         n +
         "];\n"
         "    vec4 shadowParams[" +
         n + "]; // perspective, near, far, source size\n    vec4 shadowScale[" + n +
         "]; // metres per uv (per metre of depth if perspective), 1 / size\n"
         "    vec4 shadowLight[" +
         n + "]; // position or direction to the light, w kind\n    vec4 shadowRadiance[" + n +
         "]; // rgb radiance, w range\n    vec4 shadowSpot[" + n +
         "]; // direction travelled, w cos outer (-2: none)\n"
         "    vec4 ground; // height, mode, fade start, fade end\n"
         "    vec4 meshSphere; // centre, radius\n"
         "    vec4 occlusion; // on, radius, width, height (texels)\n"
         "    ivec4 counts; // shadow slots, downsample (pixels per texel each way)\n"
         "    vec4 groundSquare; // centre x, unused, centre z, half size\n"
         "    ivec4 occlusionTexels; // the texels the occlusion drew: x0, y0, x1, y1 (exclusive)\n"
         "} stage;\n";
    return s;
}

} // namespace velvet::render
