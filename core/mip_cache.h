#pragma once
/// @file mip_cache.h
/// The on-disk cache of built mip chains (core/mip_texture.h): one tiled, MIP-mapped TIFF per
/// entry, the layout OpenImageIO's make_texture / maketx writes (64x64 tiles, every level a
/// MIP level of subimage 0, "textureformat" = "Plain Texture"), so oiiotool, iinfo and any
/// OpenImageIO TextureSystem read it. Named by a hash of the entry's key (the source file's
/// content hash, colour space, usage, size limit, format version); the key is stored inside
/// and checked on read, so a hash collision or a stale file is a miss, never a wrong image.
/// Written to a temporary beside the entry and renamed into place (atomic).

#include "core/content_hash.h" // fileContentHash, named the entries

#include <cstdint>
#include <filesystem>
#include <string>

namespace velvet {

struct MipTexture;

/// The entry file for @p key in @p dir.
std::filesystem::path mipCacheEntry(const std::filesystem::path& dir, const std::string& key);

/// Reads the entry at @p entry into @p out. False when it does not exist (@p why empty) or
/// cannot be used (@p why says why: unreadable, truncated, another key, inconsistent levels).
/// Levels finer than @p firstLevel get their size but no bytes: they stay in the file, for
/// readMipCacheRows().
bool readMipCache(const std::filesystem::path& entry, const std::string& key, MipTexture& out,
                  std::string* why, int firstLevel = 0);

/// The rows of the entry's levels are stored in tiles of this height: a band read by
/// readMipCacheRows() starts on a multiple of it.
inline constexpr int kMipCacheTileSide = 64;

/// Rows @p y0 .. @p y0 + @p rows of level @p level of @p texture (its levels' sizes and format,
/// as readMipCache() or a build gave them) from the entry at @p entry into @p out (tightly
/// packed, mipBytesPerPixel each). @p y0 is a multiple of kMipCacheTileSide; the band ends on
/// one or at the level's last row. False + why (the entry gone, truncated, or another image).
bool readMipCacheRows(const std::filesystem::path& entry, const MipTexture& texture, int level,
                      int y0, int rows, std::uint8_t* out, std::string* why);
/// Writes @p texture as the entry at @p entry (creating its folder). False + message naming
/// the file on failure; no partial entry is ever left under the entry's name.
bool writeMipCache(const std::filesystem::path& entry, const std::string& key,
                   const MipTexture& texture, std::string* error);

} // namespace velvet
