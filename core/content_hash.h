#pragma once
/// @file content_hash.h
/// xxHash64 (Yann Collet, "xxHash - Extremely fast hash algorithm", XXH64): the fast content
/// hash that names the disk caches' entries (core/mip_cache.h, core/ibl_cache.h). From the
/// reference library (Debian's libxxhash) rather than OpenImageIO's copy (OIIO::xxhash, the same
/// function), so that hashing a file does not load the image library (core/image_codec.h).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace velvet {

/// XXH64 of @p size bytes at @p data with @p seed.
std::uint64_t xxhash64(const void* data, std::size_t size, std::uint64_t seed);
inline std::uint64_t xxhash64(std::string_view bytes, std::uint64_t seed) {
    return xxhash64(bytes.data(), bytes.size(), seed);
}

/// @p v as 16 lower-case hex digits.
std::string hex64(std::uint64_t v);

/// A 64-bit hash (xxHash64, chained over 1 MiB blocks) of @p file's bytes, as 16 hex digits,
/// a '-' and the byte count; "" and @p error set when the file cannot be read.
std::string fileContentHash(const std::filesystem::path& file, std::string* error);

} // namespace velvet
