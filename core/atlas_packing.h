#pragma once
/// @file atlas_packing.h
/// Packing several images into one atlas image (the seed documents keep each element's maps in
/// a shared atlas and store its region). Used by the atlas panel and by export.
///
/// Placement is a skyline bottom-left packer (J. Jylänki, "A Thousand Ways to Pack the Bin",
/// 2010, section "Skyline"), inputs sorted by height. Each image is surrounded by @p padding
/// texels copied from its nearest edge texel (clamp-to-edge), so bilinear filtering and mip
/// levels up to log2(padding) + 1 do not bleed a neighbour into it.

#include "core/image.h"
#include "core/texture_ref.h"

#include <span>
#include <string>
#include <vector>

namespace velvet {

/// How the atlas is sized.
struct AtlasOptions {
    int padding = 4;      ///< texels around each image, replicated from its edge (>= 0)
    int maxWidth = 4096;  ///< the atlas never exceeds this ...
    int maxHeight = 4096; ///< ... nor this
    /// true: both sides are powers of two, the smallest area that fits (square preferred);
    /// false: the tightest size found with any width and height (the shortest longest side,
    /// then the smallest area).
    bool powerOfTwo = true;
};

/// Width and height of one input.
struct AtlasItemSize {
    int width = 0;
    int height = 0;
};

/// Where every input goes.
struct AtlasLayout {
    int width = 0;
    int height = 0;
    /// One per input, in input order: the input's own texels (its padding lies around it).
    std::vector<AtlasRegion> regions;
};

/// Places images of @p sizes without touching pixels (for previews in the atlas panel).
/// Returns false and sets @p error when they do not fit in the maximum size (the message says
/// how many, the limit and what they need) or a size is bad.
bool planAtlas(std::span<const AtlasItemSize> sizes, const AtlasOptions& options, AtlasLayout& out,
               std::string* error);

/// Packs @p images into @p atlas (see planAtlas()). Texels outside every padded region are 0.
/// The atlas has the inputs' channel count; with mixed counts grey is widened to RRR and a
/// missing alpha to 1 (as Image::rgba() reads them). Returns false and sets @p error on failure.
bool packAtlas(std::span<const Image> images, const AtlasOptions& options, Image& atlas,
               AtlasLayout& layout, std::string* error);

/// The texels of @p region of @p atlas as an image of their own (e.g. to unpack an atlas).
Image extractRegion(const Image& atlas, const AtlasRegion& region);

/// The mean RGBA of @p region (texels of a @p width x @p height atlas) read from @p level, a
/// smaller version of that atlas (exact when it is the atlas itself; otherwise the mean of the
/// level's texels under the region's footprint).
glm::vec4 regionMean(const Image& level, const AtlasRegion& region, int width, int height);

} // namespace velvet
