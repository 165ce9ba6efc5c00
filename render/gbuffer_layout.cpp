#include "render/gbuffer_layout.h"

#include "render/lobe_channels.h"
#include "render/shader_program.h"

#include <array>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

namespace velvet::render {
namespace {

// RT0..RT4 then depth. Changing this table changes C++ allocation and GLSL together. RT0..RT2
// and depth keep units 0..3; the lobe channels take their own units (render/shader_program.h).
constexpr std::array<GBufferAttachment, 6> kAttachments{{
    {"gBaseColorOcclusion", "GBUFFER_BASE_COLOR_OCCLUSION", GBufferFormat::RGBA8, 4,
     "rgb: base colour, sRGB-encoded in the shader (8-bit precision where it is seen); "
     "a: occlusion",
     0, false},
    {"gNormal", "GBUFFER_NORMAL", GBufferFormat::RG16, 4,
     "rg: world normal, octahedral, 16-bit unorm each (precise encoding)", 1, false},
    {"gMaterial", "GBUFFER_MATERIAL", GBufferFormat::RGBA8, 4,
     "r: metallic, g: perceptual roughness, b: material id / 255, a: specular occlusion", 2, false},
    {"gLobes0", "GBUFFER_LOBES0", GBufferFormat::RGBA8, 4,
     "lobe channels 0..3: the material's per-pixel lobe values, placed by its lobe-channel map "
     "(render/lobe_channels.h)",
     binding::kGBufferLobes0Tex, true},
    {"gLobes1", "GBUFFER_LOBES1", GBufferFormat::RGBA8, 4, "lobe channels 4..7 (as gLobes0)",
     binding::kGBufferLobes1Tex, true},
    {"gDepth", "GBUFFER_DEPTH", GBufferFormat::Depth32F, 4,
     "hardware depth; positions are reconstructed with the inverse projection", 3, false},
}};

constexpr int sumBytes(bool compact) {
    int s = 0;
    for (const auto& a : kAttachments)
        if (!(compact && a.lobeChannels))
            s += a.bytesPerPixel;
    return s;
}
static_assert(sumBytes(false) <= 24, "G-buffer budget is 24 bytes per pixel including depth");
static_assert(sumBytes(true) == 16, "the compact layout is the 16-byte one");

std::string_view glslOutType(GBufferFormat f) {
    return f == GBufferFormat::RG16 ? "vec2" : "vec4";
}

} // namespace

std::span<const GBufferAttachment> gbufferAttachments() {
    return kAttachments;
}
int gbufferColorAttachmentCount() {
    return int(kAttachments.size()) - 1;
}
int gbufferBytesPerPixel(bool compact) {
    return sumBytes(compact);
}

int gbufferUnit(std::string_view define) {
    for (const auto& a : kAttachments)
        if (a.define == define)
            return a.unit;
    return -1;
}

std::string gbufferGlsl() {
    std::string s = "// Generated from render/gbuffer_layout.cpp; do not edit.\n";
    s += "#define GBUFFER_BYTES_PER_PIXEL " + std::to_string(sumBytes(false)) + "\n";
    s += lobeChannelsGlsl();
    for (size_t i = 0; i < kAttachments.size(); ++i)
        s += "#define " + std::string(kAttachments[i].define) + " " + std::to_string(i) + "\n";
    s += "#ifdef GBUFFER_WRITE\n";
    for (int i = 0; i < gbufferColorAttachmentCount(); ++i) {
        const auto& a = kAttachments[i];
        s += "layout(location = " + std::to_string(i) + ") out " +
             std::string(glslOutType(a.format)) + " " + std::string(a.glslName) + "; // " +
             std::string(a.contents) + "\n";
    }
    // The geometry pass also writes emission straight into the HDR target, bound after the
    // G-buffer's colour attachments (renderer.cpp, "1. G-buffer"): no G-buffer byte.
    s += "layout(location = " + std::to_string(gbufferColorAttachmentCount()) +
         ") out vec4 gEmission; // rgb emitted radiance, a 1 (the HDR target)\n";
    s += "#else\n";
    for (size_t i = 0; i < kAttachments.size(); ++i) {
        const auto& a = kAttachments[i];
        s += "layout(binding = " + std::to_string(a.unit) + ") uniform sampler2D " +
             std::string(a.glslName) + "Tex;\n";
    }
    s += "#endif\n";
    return s;
}

// Cigolle et al. 2014, "A Survey of Efficient Representations for Independent Unit Vectors"
glm::vec2 octEncode(glm::vec3 n) {
    n /= std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    glm::vec2 e(n.x, n.y);
    if (n.z < 0.0f) {
        e = glm::vec2((1.0f - std::abs(n.y)) * (n.x >= 0.0f ? 1.0f : -1.0f),
                      (1.0f - std::abs(n.x)) * (n.y >= 0.0f ? 1.0f : -1.0f));
    }
    return e;
}

glm::vec3 octDecode(glm::vec2 e) {
    glm::vec3 n(e.x, e.y, 1.0f - std::abs(e.x) - std::abs(e.y));
    if (n.z < 0.0f) {
        n.x = (1.0f - std::abs(e.y)) * (e.x >= 0.0f ? 1.0f : -1.0f);
        n.y = (1.0f - std::abs(e.x)) * (e.y >= 0.0f ? 1.0f : -1.0f);
    }
    return glm::normalize(n);
}

glm::vec3 octDecodeUnorm16(glm::uvec2 q) {
    return octDecode(glm::vec2(q) / 65535.0f * 2.0f - 1.0f);
}

glm::uvec2 octEncodeUnorm16(glm::vec3 n) {
    const glm::vec2 e = (octEncode(n) * 0.5f + 0.5f) * 65535.0f;
    const glm::vec2 base = glm::floor(e);
    // Compare squared distances, not dot products: 1 - cos of 0.005 degrees is 4e-9, below
    // float resolution near 1, while |d - n|^2 keeps full relative precision.
    glm::uvec2 best(0);
    float bestDist = 1e30f;
    for (int i = 0; i < 4; ++i) {
        const glm::vec2 c =
            glm::clamp(base + glm::vec2(float(i & 1), float(i >> 1)), 0.0f, 65535.0f);
        const glm::vec3 d = octDecodeUnorm16(glm::uvec2(c)) - n;
        const float dist = glm::dot(d, d);
        if (dist < bestDist) {
            bestDist = dist;
            best = glm::uvec2(c);
        }
    }
    return best;
}

} // namespace velvet::render
