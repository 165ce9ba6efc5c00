#pragma once
/// @file lobe_channels.h
/// Which of a material's lobe values travel through the G-buffer per pixel, and where.
///
/// The 16 bytes of base colour, occlusion, normal, metallic, roughness and material id are the
/// same for every material. The other lobes (sheen, clearcoat and its own normal, specular,
/// anisotropy) and the IOR need 15 values between them, but a material varies only a few of them
/// per pixel: a velvet its sheen colour, a car paint its coat, silk its anisotropy. So the G-buffer
/// has eight 8-bit "lobe channels" (two RGBA8 targets, 24 bytes per pixel in all) and each material
/// gets a map saying which of its varying values sit in which channels; the values it does not vary
/// come from the material table as before. The map is 4 bits per value in the material record
/// (GpuMaterial::terms2.w for the first eight values, clearcoat.w for the IOR's entry), written by
/// the geometry pass and read by the lighting passes
/// (gbuffer.frag, gbuffer_read.glsl). docs/architecture.md, "G-buffer", has the measurements.
///
/// A value varies when a texture slot or a connected graph input drives it; the anisotropy
/// direction always varies with the surface (it is stored in the normal's own frame). If a
/// material varies more than eight channels' worth, the values later in LobeValue's order stay
/// per material (their texture's mean, as before this layout) and a warning names them.
/// No GL here: the assignment is pure and tested on its own (test_render_lobe_channels).

#include "core/material.h"

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace velvet::render {

/// The per-pixel lobe values in assignment priority (first served first).
enum class LobeValue : int {
    Anisotropy,         ///< strength, direction angle in the normal's frame / pi (2 channels)
    SheenColor,         ///< weight x colour x texture, sRGB-encoded (3)
    SheenRoughness,     ///< (1)
    Clearcoat,          ///< weight (1)
    ClearcoatRoughness, ///< (1)
    ClearcoatNormal,    ///< the coat's normal in the base normal's frame, xy (2)
    SpecularWeight,     ///< (1)
    SpecularColor,      ///< sRGB-encoded (3)
    Ior,                ///< (ior - 1) / 2: IORs 1 .. 3 (1; only a graph drives it)
    Count
};
inline constexpr int kLobeValueCount = static_cast<int>(LobeValue::Count);
/// 8-bit channels of the two lobe targets.
inline constexpr int kLobeChannelCount = 8;
/// The 4-bit map entry of a value that stays per material.
inline constexpr int kLobePerMaterial = 15;

/// Channels a value takes.
int lobeValueChannels(LobeValue value);
/// "sheen colour", for messages and docs.
std::string_view lobeValueLabel(LobeValue value);
/// GLSL macro name, "LOBE_SHEEN_COLOR".
std::string_view lobeValueMacro(LobeValue value);

/// A set of LobeValues (bit i: LobeValue i).
using LobeValueSet = std::uint32_t;
inline constexpr LobeValueSet lobeBit(LobeValue v) {
    return LobeValueSet(1) << static_cast<int>(v);
}

/// The values @p material varies per pixel, given the texture slots present on the GPU
/// (@p presentSlots, bit i: TextureSlot i) and the material output inputs its graph connects
/// (@p graphFields, MaterialInputs field names such as "sheenColor").
LobeValueSet varyingLobeValues(const Material& material, std::uint32_t presentSlots,
                               const std::vector<std::string>& graphFields);

/// Whether the shading normal of a material with @p presentSlots and @p graphFields (as above)
/// differs from the mesh's per pixel: a normal map, or a graph that writes the normal (the
/// fabric nodes' weave relief). The lighting then keeps light from below the surface's geometric
/// horizon out (gbuffer_read.glsl's geometricHorizon).
bool perturbsNormal(std::uint32_t presentSlots, const std::vector<std::string>& graphFields);

/// Where each value sits: the first channel (0 .. 7) or kLobePerMaterial.
struct LobeChannelMap {
    std::array<int, kLobeValueCount> firstChannel{};
    /// Values that varied but found no room (kept per material, with their texture's mean).
    LobeValueSet overflow = 0;
    int channelsUsed = 0;

    bool perPixel(LobeValue v) const { return firstChannel[size_t(v)] != kLobePerMaterial; }
    /// 4 bits per value, value i at bits 4i .. 4i+3, for the first eight values
    /// (GpuMaterial::terms2.w).
    std::int32_t packed() const;
    /// The IOR's entry (GpuMaterial::clearcoat.w, a small whole number in a float slot).
    int iorEntry() const { return firstChannel[size_t(LobeValue::Ior)]; }
};

/// Assigns channels to @p varying in LobeValue order, each value's channels contiguous.
/// @p channels: kLobeChannelCount, or 0 for the compact 16-byte layout (everything per material).
LobeChannelMap assignLobeChannels(LobeValueSet varying, int channels = kLobeChannelCount);

/// "sheen colour, specular colour" of @p set, in order.
std::string lobeValueNames(LobeValueSet set);

/// The GLSL defines of the contract (LOBE_* ids, LOBE_PER_MATERIAL), for gbuffer_layout.glsl.
std::string lobeChannelsGlsl();

} // namespace velvet::render
