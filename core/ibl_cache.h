#pragma once
/// @file ibl_cache.h
/// The on-disk cache of prefiltered environments (issue 16: a whole `velvet render` in a
/// second). One file per HDRI content and bake: what render/ibl_bake.h and
/// render/environment_map.h make from an HDRI (its equirect as the GPU holds it, RGB half; the
/// radiance SH9; the GGX-prefiltered specular cube, every level and face, RGBA half), so that a
/// later process uploads it without decoding the HDRI or running the bake.
///
/// Named by xxHash64 of the key (the HDRI's content hash, core/content_hash.h, and the bake's
/// signature: sizes, sample count, the bake shaders' hash, this format's version), which is
/// also stored inside and compared on read, so a hash collision or a stale file is a miss. The
/// payload ends with an xxHash64 of everything before it: a truncated or damaged entry is
/// refused with the reason (the caller rebuilds it and says so), never used. Written atomically
/// (core/atomic_file.h). docs/file-formats.md, "Prefiltered environment cache".

#include "core/spherical_harmonics.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace velvet {

/// The file format's version: part of every key and of the magic line.
inline constexpr int kIblCacheVersion = 1;

struct IblCacheEntry {
    int width = 0, height = 0;           ///< the equirect's size
    std::vector<std::uint16_t> equirect; ///< RGB half, width * height * 3, row 0 at the top
    SH9 sh{};                            ///< radiance SH9 (intensity not applied)
    int faceSize = 0, levels = 0;        ///< the prefiltered cube: level 0's face size, levels
    /// Per level: the six faces (GL order +X, -X, +Y, -Y, +Z, -Z), each size^2 RGBA half,
    /// size = max(faceSize >> level, 1).
    std::vector<std::vector<std::uint16_t>> specular;
};

/// The entry file for @p key in @p dir (dir/environments/HASH.ibl).
std::filesystem::path iblCacheFile(const std::filesystem::path& dir, const std::string& key);

/// Reads @p file into @p out. False with @p why empty when there is no such file; false with
/// @p why saying what is wrong (another key, truncated, damaged, inconsistent sizes) otherwise.
bool readIblCache(const std::filesystem::path& file, const std::string& key, IblCacheEntry& out,
                  std::string* why);

/// Writes @p entry as @p file (creating its folder), atomically. False + message naming the file.
bool writeIblCache(const std::filesystem::path& file, const std::string& key,
                   const IblCacheEntry& entry, std::string* error);

} // namespace velvet
