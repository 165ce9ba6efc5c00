#pragma once
/// @file gbuffer_layout.h
/// The one definition of the G-buffer (DESIGN.md, "G-buffer"): attachments, formats, encodings.
/// C++ allocates from this table and the shader loader injects gbufferGlsl(), generated from the
/// same table, into every shader that includes "gbuffer_layout.glsl". Budget: 24 bytes per pixel
/// including depth: the 16 bytes every material fills, and 8 lobe channels each material maps its
/// per-pixel lobe values into (render/lobe_channels.h). The compact 16-byte layout without the
/// lobe channels stays available for comparison (velvet bench). Also the CPU twins of the normal
/// encoding. No GL types here.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <string>
#include <string_view>

namespace velvet::render {

/// Storage formats the G-buffer uses (mapped to GL enums in gbuffer.cpp).
enum class GBufferFormat { Depth32F, RGBA8, RG16 };

struct GBufferAttachment {
    std::string_view glslName; ///< output name in gbuffer.frag; the sampler is glslName + "Tex"
    std::string_view define;   ///< GLSL macro holding its location / texture unit
    GBufferFormat format;
    int bytesPerPixel;
    std::string_view contents; ///< channel meanings and encodings, for docs and debug views
    int unit;                  ///< texture unit the lighting passes sample it from
    bool lobeChannels;         ///< one of the two lobe-channel targets (absent when compact)
};

/// Colour attachments in location order, then the depth attachment (last).
std::span<const GBufferAttachment> gbufferAttachments();
/// Number of colour attachments (the depth attachment is gbufferAttachments().back()).
int gbufferColorAttachmentCount();
/// Sum over all attachments, depth included (asserted <= 24 at compile time in the .cpp);
/// @p compact: without the lobe-channel targets (16).
int gbufferBytesPerPixel(bool compact = false);
/// The texture unit of the attachment whose define is @p define ("GBUFFER_DEPTH"), or -1.
int gbufferUnit(std::string_view define);
/// The GLSL text of the virtual include "gbuffer_layout.glsl": location / binding macros,
/// `out` declarations when GBUFFER_WRITE is defined, samplers otherwise.
std::string gbufferGlsl();

/// Material ids stored in the G-buffer (8 bits, RT2.b).
inline constexpr int kMaxMaterials = 256;

/// @name Octahedral normal encoding (Cigolle et al. 2014, "A Survey of Efficient Representations
/// for Independent Unit Vectors"), stored as two 16-bit unorm values. CPU twins of
/// common_gbuffer.glsl.
/// @{
/// Unit vector -> [-1, 1]^2.
glm::vec2 octEncode(glm::vec3 n);
/// [-1, 1]^2 -> unit vector.
glm::vec3 octDecode(glm::vec2 e);
/// Unit vector -> 16-bit unorm pair, choosing among the four neighbouring quantised points the one
/// that decodes closest to @p n (the paper's "precise" variant, oct32P).
glm::uvec2 octEncodeUnorm16(glm::vec3 n);
/// 16-bit unorm pair -> unit vector.
glm::vec3 octDecodeUnorm16(glm::uvec2 q);
/// @}

} // namespace velvet::render
