#pragma once
/// @file mip_texture.h
/// A texture as the GPU takes it: every mip level, already filtered, in the narrowest format
/// that carries the file's precision (issue 16, "Textures at the sizes artists use"):
/// - an 8-bit file in a data space (or any space whose conversion is the identity): RGBA8;
/// - an 8-bit file in the sRGB texture space: SRGB8_ALPHA8, the levels filtered in
///   scene-linear and encoded back (the GPU decodes sRGB exactly, before filtering);
/// - anything else (16-bit, float, other colour spaces, EXIF-rotated or downscaled files):
///   scene-linear RGBA16F, through the float path (readImage, OCIO, mipChain).
/// Levels are built once and kept in an on-disk cache keyed by the file's content
/// (core/mip_cache.h); the 8-bit path never holds a float copy of the image. No GL here.

#include "core/diagnostics.h"
#include "core/image.h"

#include <cstdint>
#include <filesystem>
#include <glm/vec4.hpp>
#include <memory>
#include <string>
#include <vector>

namespace velvet {

class ColorManagement;
enum class TextureUsage;

/// Storage of every level of a MipTexture (GL_RGBA8, GL_SRGB8_ALPHA8, GL_RGBA16F).
enum class MipFormat { Rgba8, Srgb8Alpha8, Rgba16F };
/// Bytes per pixel of @p format (4 or 8).
int mipBytesPerPixel(MipFormat format);

/// One level: width * height RGBA pixels, row 0 at the top (t = 0), tightly packed.
struct MipLevel {
    int width = 0, height = 0;
    std::vector<std::uint8_t> bytes;
};

struct MipTexture {
    MipFormat format = MipFormat::Rgba8;
    std::vector<MipLevel> levels; ///< the full chain, level 0 first (mipLevelCount levels)
    /// Scene-linear mean RGBA of level 0 (the material table's value for slots the G-buffer
    /// cannot carry per pixel).
    glm::vec4 mean{1.0f};
    /// Non-empty: level 0's bytes were left in this cache entry (MipLoadOptions::
    /// leaveFinestInCache) and levels[0].bytes is empty; read it in bands (readMipCacheRows).
    std::filesystem::path finestInCache;
    int width() const { return levels.empty() ? 0 : levels[0].width; }
    int height() const { return levels.empty() ? 0 : levels[0].height; }
    std::uint64_t byteSize() const; ///< all levels at their full size (held or not)
    /// The largest level held in memory whose sides are both at most @p maxSide, decoded to
    /// scene-linear float RGBA (means over an atlas region without touching level 0).
    Image linearLevel(int maxSide) const;
};

/// Options of loadMipTexture().
struct MipLoadOptions {
    ImageReadLimits limits; ///< refused before decoding when the header exceeds them
    int maxTextureSide = 0; ///< GL_MAX_TEXTURE_SIZE (larger: downscaled with a warning); 0: none
    /// The on-disk cache's folder; empty: defaultMipCacheDir(). Nothing is cached when the
    /// folder cannot be created (the load still works, with a warning).
    std::filesystem::path cacheDir;
    bool useCache = true;
    int threads = 2; ///< filter threads for a first build
    /// Write a fresh build to the cache before returning; false: the caller calls
    /// storeMipTexture() when it suits it (core/texture_loader.h: after the GPU has the levels).
    bool writeCache = true;
    /// Leave level 0 in the cache entry instead of memory (MipTexture::finestInCache) where
    /// there is one: a hit reads only the coarser levels, a fresh build is written first and
    /// then lets level 0 go. The editor's uploads stream it in bands, so the CPU never holds the
    /// whole chain while the GPU's storage for it exists (issue 16: a 4K map's peak <= 2x).
    bool leaveFinestInCache = false;
};

/// What loadMipTexture() did and found.
struct MipLoadResult {
    /// Null when the file is missing or broken. Not const: whoever holds the last reference may
    /// free levels as they reach the GPU (render/texture_set.cpp).
    std::shared_ptr<MipTexture> texture;
    std::vector<Problem> problems; ///< errors (texture null) and warnings
    bool decoded = false;          ///< the image file was decoded (a cache miss or no cache)
    bool fromCache = false;        ///< the levels came from the on-disk cache
    double milliseconds = 0;
    /// Where the time went: hashing the file, reading the cache entry, decoding, filtering the
    /// levels, writing the entry (0 for steps not taken).
    double hashMs = 0, cacheReadMs = 0, decodeMs = 0, filterMs = 0, cacheWriteMs = 0;
    std::filesystem::path cacheEntry; ///< where the entry is or goes ("" without a cache)
    std::string cacheKey;
};

/// The cache folder: velvetCacheDir()/textures (core/cache_dir.h: $VELVET_CACHE_DIR, else
/// $XDG_CACHE_HOME/velvet, else ~/.cache/velvet); empty when caching is off (VELVET_NO_CACHE) or
/// none of the variables is set.
std::filesystem::path defaultMipCacheDir();

/// Loads @p file as a GPU texture in @p colorSpace (already resolved: a canonical name of
/// @p colorManagement's config) for @p usage: from the cache when an entry for the file's
/// current content exists, else decoded and filtered (then written to the cache, atomically).
/// A cache entry that cannot be read is rebuilt, with a warning naming it. Thread-safe (one
/// call per file at a time is the caller's business: core/texture_loader.h).
MipLoadResult loadMipTexture(const std::filesystem::path& file, const std::string& colorSpace,
                             TextureUsage usage, const ColorManagement& colorManagement,
                             const MipLoadOptions& options = {});

/// Writes a fresh build of @p result to its cache entry (nothing for a cache hit or without a
/// cache); a failure becomes a warning in result.problems. True when the entry was written.
bool storeMipTexture(MipLoadResult& result);

} // namespace velvet
