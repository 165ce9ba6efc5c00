#include "render/render_interface.h"

#include "render/material_table.h"
#include "render/post_effect.h"
#include "render/shader_program.h"

#include <array>
#include <cstddef>
#include <string_view>

namespace velvet::render {
namespace {

/// One member of a std140 block whose members are all 16-byte aligned (vec4, ivec4, mat4 and
/// arrays of them), so its std140 offset is the sum of the sizes before it.
struct Member {
    std::string_view glslType;
    std::string_view name;
    std::string_view count; ///< GLSL array length ("" : not an array)
    size_t offset, size;
    std::string_view comment;
};

#define VELVET_MEMBER(Block, type, name, count, comment)                                           \
    Member {                                                                                       \
        type, #name, count, offsetof(Block, name), sizeof(Block::name), comment                    \
    }

constexpr std::array kFrameMembers{
    VELVET_MEMBER(FrameBlock, "mat4", viewMatrix, "", ""),
    VELVET_MEMBER(FrameBlock, "mat4", projMatrix, "", ""),
    VELVET_MEMBER(FrameBlock, "mat4", invProjMatrix, "", ""),
    VELVET_MEMBER(FrameBlock, "mat4", invViewMatrix, "", ""),
    VELVET_MEMBER(FrameBlock, "mat4", viewProjMatrix, "", ""),
    VELVET_MEMBER(FrameBlock, "vec4", cameraPosition, "", "xyz world, w: 1 orthographic"),
    VELVET_MEMBER(FrameBlock, "vec4", viewport, "", "width, height, 1/width, 1/height"),
    VELVET_MEMBER(FrameBlock, "vec4", envSh, "9",
                  "SH9 of the environment radiance, intensity applied"),
    VELVET_MEMBER(FrameBlock, "vec4", envParams, "",
                  "cos(rotation), sin(rotation), intensity, max mip level"),
    VELVET_MEMBER(FrameBlock, "vec4", ambientRadiance, "",
                  "rgb: uniform radiance of ambient lights"),
    VELVET_MEMBER(FrameBlock, "vec4", backgroundColor, "", "rgb, w: background mip level"),
    VELVET_MEMBER(FrameBlock, "ivec4", modes, "",
                  "light count, debug view, tone mapper, background mode"),
    VELVET_MEMBER(FrameBlock, "vec4", post, "",
                  "exposure multiplier, depth view range, environment width, unused"),
    VELVET_MEMBER(FrameBlock, "vec4", lightDirection, "MAX_LIGHTS",
                  "xyz: towards the light, world"),
    VELVET_MEMBER(FrameBlock, "vec4", lightRadiance, "MAX_LIGHTS", "rgb: colour x illuminance"),
};

constexpr std::array kIblMembers{
    VELVET_MEMBER(IblBlock, "vec4", state, "",
                  "x: prefiltered cube ready, y: its last level, z: DFG LUT ready, w: "
                  "multiple-scattering compensation on"),
    VELVET_MEMBER(IblBlock, "vec4", background, "",
                  "x: level of the blurred background, y: time in seconds (FBM), zw unused"),
    VELVET_MEMBER(IblBlock, "vec4", reflection, "",
                  "x: reflection samples per pixel this frame (0: split sum), y: over the mean, "
                  "z: sample set, w: pixels per side of one output pixel"),
};

// std430 lays out a struct of vec4 / ivec4 members exactly as std140 does.
constexpr std::array kMaterialMembers{
    VELVET_MEMBER(GpuMaterial, "vec4", baseColorMetallic, "",
                  "rgb base colour (linear), a metallic"),
    VELVET_MEMBER(GpuMaterial, "vec4", specularColorWeight, "",
                  "rgb specular colour, a specular weight"),
    VELVET_MEMBER(GpuMaterial, "vec4", roughIorOcclusionNormal, "",
                  "roughness, IOR, occlusion strength, normal scale"),
    VELVET_MEMBER(GpuMaterial, "vec4", emissive, "",
                  "rgb colour, a strength (nits); drawn per pixel by gbuffer.frag"),
    VELVET_MEMBER(GpuMaterial, "vec4", sheenColorRoughness, "",
                  "rgb sheen colour (without its weight), a sheen roughness"),
    VELVET_MEMBER(GpuMaterial, "vec4", clearcoat, "",
                  "weight, roughness, normal scale, the IOR's lobe-channel entry "
                  "(render/lobe_channels.h; 15: per material)"),
    VELVET_MEMBER(GpuMaterial, "vec4", sheenWeightAnisotropy, "",
                  "sheen weight, anisotropy strength, anisotropy rotation (radians), unused"),
    VELVET_MEMBER(GpuMaterial, "ivec4", terms, "", "distribution, visibility, fresnel, diffuse"),
    VELVET_MEMBER(GpuMaterial, "ivec4", terms2, "",
                  "sheen model, texture-slot presence bits, atlas-region bits "
                  "(render/texture_set.h), lobe-channel map (render/lobe_channels.h)"),
    VELVET_MEMBER(GpuMaterial, "vec4", storedBaseColor, "",
                  "rgb the base colour as the G-buffer stores and decodes it, w unused"),
};

constexpr std::array kPostFrameMembers{
    VELVET_MEMBER(PostFrameBlock, "mat4", viewProj, "", ""),
    VELVET_MEMBER(PostFrameBlock, "mat4", invViewProj, "", ""),
    VELVET_MEMBER(PostFrameBlock, "mat4", prevViewProj, "", ""),
    VELVET_MEMBER(PostFrameBlock, "mat4", invProj, "", ""),
    VELVET_MEMBER(PostFrameBlock, "vec4", viewport, "",
                  "full-resolution width, height, 1/width, 1/height"),
    VELVET_MEMBER(PostFrameBlock, "vec4", misc, "",
                  "x: time in seconds, y: exposure multiplier of the frame settings"),
};

#undef VELVET_MEMBER

template <size_t N>
constexpr bool std140Packed(const std::array<Member, N>& members, size_t blockSize) {
    size_t offset = 0;
    for (const Member& m : members) {
        if (m.offset != offset || m.size % 16 != 0)
            return false;
        offset += m.size;
    }
    return offset == blockSize;
}
static_assert(std140Packed(kFrameMembers, sizeof(FrameBlock)),
              "FrameBlock: a member is not at its std140 offset");
static_assert(std140Packed(kIblMembers, sizeof(IblBlock)),
              "IblBlock: a member is not at its std140 offset");
static_assert(sizeof(FrameBlock) == 5 * 64 + 16 * 16 + 2 * kMaxDirectionalLights * 16);
static_assert(sizeof(IblBlock) == 48);
static_assert(std140Packed(kMaterialMembers, sizeof(GpuMaterial)),
              "GpuMaterial: a member is not at its std430 offset");
static_assert(std140Packed(kPostFrameMembers, sizeof(PostFrameBlock)),
              "PostFrameBlock: a member is not at its std140 offset");

/// DebugView's GLSL names, in enum order (the numbers are the enum's).
constexpr std::array<std::string_view, 21> kDebugViewNames{
    "DEBUG_FINAL",          "DEBUG_ALBEDO",           "DEBUG_NORMAL",
    "DEBUG_DEPTH",          "DEBUG_ROUGHNESS",        "DEBUG_METALLIC",
    "DEBUG_POSITION",       "DEBUG_SPECULAR",         "DEBUG_CLEARCOAT",
    "DEBUG_SHEEN",          "DEBUG_OCCLUSION",        "DEBUG_EMISSIVE",
    "DEBUG_MATERIAL_ID",    "DEBUG_LIGHTS_PER_PIXEL", "DEBUG_DIFFUSE_ONLY",
    "DEBUG_SPECULAR_ONLY",  "DEBUG_BASE_SPECULAR",    "DEBUG_SHEEN_ONLY",
    "DEBUG_CLEARCOAT_ONLY", "DEBUG_ANISOTROPY",       "DEBUG_SPECULAR_OCCLUSION"};
static_assert(kDebugViewNames.size() == size_t(DebugView::SpecularOcclusion) + 1,
              "every DebugView needs its GLSL name");

constexpr std::string_view debugName(DebugView v) {
    return kDebugViewNames[size_t(v)];
}

/// An enum value shared with GLSL as a `#define`.
template <typename E>
struct EnumName {
    E value;
    std::string_view glsl;
};

/// Whether @p names lists every value 0 .. N-1 in order (so the defines are the enum's numbers).
template <typename E, size_t N>
constexpr bool dense(const std::array<EnumName<E>, N>& names) {
    for (size_t i = 0; i < N; ++i)
        if (int(names[i].value) != int(i))
            return false;
    return true;
}

// The BRDF term ids (core/material.h), as packed in GpuMaterial.terms (D, V, F, diffuse) and
// terms2.x (sheen model); common_brdf.glsl dispatches on them.
constexpr std::array<EnumName<Distribution>, 3> kDistributions{{
    {Distribution::GGX, "DISTRIBUTION_GGX"},
    {Distribution::Beckmann, "DISTRIBUTION_BECKMANN"},
    {Distribution::BlinnPhong, "DISTRIBUTION_BLINN_PHONG"},
}};
constexpr std::array<EnumName<Visibility>, 7> kVisibilities{{
    {Visibility::SmithGGXSeparable, "VISIBILITY_SMITH_GGX_SEPARABLE"},
    {Visibility::SmithGGXCorrelated, "VISIBILITY_SMITH_GGX_CORRELATED"},
    {Visibility::SchlickGGX, "VISIBILITY_SCHLICK_GGX"},
    {Visibility::CookTorrance, "VISIBILITY_COOK_TORRANCE"},
    {Visibility::Implicit, "VISIBILITY_IMPLICIT"},
    {Visibility::Neumann, "VISIBILITY_NEUMANN"},
    {Visibility::Kelemen, "VISIBILITY_KELEMEN"},
}};
constexpr std::array<EnumName<Fresnel>, 3> kFresnels{{
    {Fresnel::Schlick, "FRESNEL_SCHLICK"},
    {Fresnel::SchlickSphericalGaussian, "FRESNEL_SCHLICK_SPHERICAL_GAUSSIAN"},
    {Fresnel::ExactDielectric, "FRESNEL_EXACT_DIELECTRIC"},
}};
constexpr std::array<EnumName<Diffuse>, 2> kDiffuses{{
    {Diffuse::Lambert, "DIFFUSE_LAMBERT"},
    {Diffuse::Burley, "DIFFUSE_BURLEY"},
}};
constexpr std::array<EnumName<SheenModel>, 3> kSheenModels{{
    {SheenModel::CharlieContyKulla, "SHEEN_CHARLIE_CONTY_KULLA"},
    {SheenModel::CharlieAshikhmin, "SHEEN_CHARLIE_ASHIKHMIN"},
    {SheenModel::CharlieNeubelt, "SHEEN_CHARLIE_NEUBELT"},
}};
// The viewport's built-in tone mappers (FrameBlock.modes.z; common_tonemap.glsl's toneMap()).
// The post chain's tonemap effect numbers its operators itself (renderer.cpp maps them).
constexpr std::array<EnumName<ToneMapper>, 4> kToneMappers{{
    {ToneMapper::KhronosPbrNeutral, "TONEMAP_PBR_NEUTRAL"},
    {ToneMapper::AcesFitted, "TONEMAP_ACES_FITTED"},
    {ToneMapper::Reinhard, "TONEMAP_REINHARD"},
    {ToneMapper::Linear, "TONEMAP_LINEAR"},
}};
static_assert(dense(kDistributions) && dense(kVisibilities) && dense(kFresnels) &&
                  dense(kDiffuses) && dense(kSheenModels) && dense(kToneMappers),
              "a GLSL name table skips or reorders an enum value");
static_assert(int(Distribution::BlinnPhong) + 1 == int(kDistributions.size()) &&
                  int(Fresnel::ExactDielectric) + 1 == int(kFresnels.size()) &&
                  int(Diffuse::Burley) + 1 == int(kDiffuses.size()) &&
                  int(Visibility::Kelemen) + 1 == int(kVisibilities.size()) &&
                  int(SheenModel::CharlieNeubelt) + 1 == int(kSheenModels.size()) &&
                  int(ToneMapper::Linear) + 1 == int(kToneMappers.size()),
              "an enum value has no GLSL name");

template <typename E, size_t N>
std::string defines(const std::array<EnumName<E>, N>& names) {
    std::string s;
    for (const auto& n : names)
        s += "#define " + std::string(n.glsl) + " " + std::to_string(int(n.value)) + "\n";
    return s;
}

template <size_t N>
std::string membersText(const std::array<Member, N>& members) {
    std::string s;
    for (const Member& m : members) {
        s += "    " + std::string(m.glslType) + " " + std::string(m.name);
        if (!m.count.empty())
            s += "[" + std::string(m.count) + "]";
        s += ";";
        if (!m.comment.empty())
            s += " // " + std::string(m.comment);
        s += "\n";
    }
    return s;
}

template <size_t N>
std::string block(std::string_view name, int binding, std::string_view instance,
                  const std::array<Member, N>& members) {
    return "layout(std140, binding = " + std::to_string(binding) + ") uniform " +
           std::string(name) + " {\n" + membersText(members) + "} " + std::string(instance) + ";\n";
}

} // namespace

bool isLobeView(DebugView view) {
    return view >= DebugView::DiffuseOnly && view <= DebugView::ClearcoatOnly;
}

bool isLightView(DebugView view) {
    return view == DebugView::Final || view == DebugView::LightsPerPixel || isLobeView(view);
}

std::string renderInterfaceGlsl() {
    std::string s = "// Generated from render/render_interface.cpp; do not edit.\n";
    s += "#define MAX_LIGHTS " + std::to_string(kMaxDirectionalLights) + "\n";
    s += "#define SAMPLED_REFLECTION_MAX_ROUGHNESS " +
         std::to_string(kSampledReflectionMaxRoughness) + "\n";
    s += block("FrameBlock", binding::kFrameUbo, "frame", kFrameMembers);
    s += block("IblBlock", binding::kIblUbo, "ibl", kIblMembers);
    for (size_t i = 0; i < kDebugViewNames.size(); ++i)
        s += "#define " + std::string(kDebugViewNames[i]) + " " + std::to_string(i) + "\n";
    // The C++ tests above, written with the generated names.
    s += "bool isLobeView(int view) { return view >= " +
         std::string(debugName(DebugView::DiffuseOnly)) +
         " && view <= " + std::string(debugName(DebugView::ClearcoatOnly)) + "; }\n";
    s += "bool isLightView(int view) { return view == " + std::string(debugName(DebugView::Final)) +
         " || view == " + std::string(debugName(DebugView::LightsPerPixel)) +
         " || isLobeView(view); }\n";
    s += defines(kDistributions) + defines(kVisibilities) + defines(kFresnels) +
         defines(kDiffuses) + defines(kSheenModels) + defines(kToneMappers);
    // The material record (the std430 table itself is common_material.glsl's).
    s += "struct GpuMaterial {\n" + membersText(kMaterialMembers) + "};\n";
    s += "#define RECORD_VALUES_PER_MATERIAL " + std::to_string(kRecordValuesPerMaterial) + "\n";
    return s;
}

std::string postInterfaceGlsl() {
    return "// Generated from render/render_interface.cpp; do not edit.\n" +
           block("PostFrame", kPostFrameUbo, "post", kPostFrameMembers);
}

} // namespace velvet::render
