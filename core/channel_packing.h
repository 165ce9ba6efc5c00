#pragma once
/// @file channel_packing.h
/// Packing single-channel material maps into one RGB(A) texture and back, in the layouts
/// engines expect. Used by the atlas panel and by export. Pure C++ on velvet::Image.

#include "core/image.h"

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace velvet {

/// Where each map goes. Roughness is perceptual roughness (alpha = roughness^2, glTF 2.0
/// Appendix B); smoothness is 1 - roughness (Unity HDRP's perceptual smoothness).
enum class PackLayout {
    /// glTF 2.0 pbrMetallicRoughness.metallicRoughnessTexture (section 3.9.2): G roughness,
    /// B metallic. R holds occlusion, which glTF's occlusionTexture may share (it reads R).
    GltfMetallicRoughness,
    /// Unreal Engine "ORM": R ambient occlusion, G roughness, B metallic.
    UnrealOrm,
    /// Unity HDRP mask map "MODS": R metallic, G ambient occlusion, B detail mask,
    /// A smoothness = 1 - roughness.
    HdrpMaskMap,
    /// The seed documents' material atlas: R specular, G roughness, B metallic.
    SpecRoughMetal,
    Count
};

/// The layout's id for files and the command line: "gltf-mr", "unreal-orm", "hdrp-mask",
/// "srm"; and its label for the UI.
std::string_view packLayoutId(PackLayout layout);
std::string_view packLayoutLabel(PackLayout layout);
std::optional<PackLayout> packLayoutFromId(std::string_view id);

/// Single-channel maps. An empty Image is an absent map. When packing, the first channel of
/// each present map is used (a grey file, or a colour file's R); unpacking fills the maps the
/// layout holds with one-channel images and leaves the others empty.
struct ChannelMaps {
    Image occlusion;  ///< 1 = unoccluded
    Image roughness;  ///< perceptual roughness
    Image metallic;   ///< 0 dielectric, 1 metal
    Image specular;   ///< specular level (0.5 = F0 of 4 %, Unreal's convention)
    Image detailMask; ///< where detail maps apply (HDRP)
};

/// Values used for absent maps when packing. The defaults are Velvet's material defaults
/// (metallic 0, roughness 0.5) and each convention's neutral value.
struct ChannelDefaults {
    float occlusion = 1.0f;  ///< no occlusion
    float roughness = 0.5f;  ///< Velvet's default roughness (lobes.base.roughness)
    float metallic = 0.0f;   ///< dielectric
    float specular = 0.5f;   ///< F0 = 0.08 * 0.5 = 4 %
    float detailMask = 1.0f; ///< detail everywhere (HDRP's default white mask)
};

/// Packs @p maps into @p out (3 channels; 4 for HdrpMaskMap) in @p layout. Absent maps are
/// filled with @p defaults; maps the layout has no place for are ignored. All present maps must
/// have the same size, else an error naming two of them and their sizes; at least one must be
/// present (it gives the size). Returns false with @p error set on failure.
bool packChannels(PackLayout layout, const ChannelMaps& maps, Image& out, std::string* error,
                  const ChannelDefaults& defaults = {});

/// Splits @p packed (in @p layout) back into one-channel maps. HdrpMaskMap needs 4 channels,
/// the others 3 (an error says what is missing otherwise).
bool unpackChannels(PackLayout layout, const Image& packed, ChannelMaps& out, std::string* error);

} // namespace velvet
