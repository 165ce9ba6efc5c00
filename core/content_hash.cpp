#include "core/content_hash.h"

#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <vector>

namespace velvet {
namespace {

// The five primes and the round of XXH64 (xxhash_spec.md, "XXH64 algorithm description").
constexpr std::uint64_t kP1 = 0x9E3779B185EBCA87ULL;
constexpr std::uint64_t kP2 = 0xC2B2AE3D27D4EB4FULL;
constexpr std::uint64_t kP3 = 0x165667B19E3779F9ULL;
constexpr std::uint64_t kP4 = 0x85EBCA77C2B2AE63ULL;
constexpr std::uint64_t kP5 = 0x27D4EB2F165667C5ULL;

constexpr std::uint64_t rotl(std::uint64_t x, int r) {
    return (x << r) | (x >> (64 - r));
}
std::uint64_t read64(const unsigned char* p) { // the spec reads little-endian; so does x86-64
    std::uint64_t v;
    std::memcpy(&v, p, 8);
    return v;
}
std::uint32_t read32(const unsigned char* p) {
    std::uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}
constexpr std::uint64_t xxRound(std::uint64_t acc, std::uint64_t lane) {
    return rotl(acc + lane * kP2, 31) * kP1;
}
constexpr std::uint64_t mergeRound(std::uint64_t acc, std::uint64_t v) {
    return (acc ^ xxRound(0, v)) * kP1 + kP4;
}

} // namespace

std::uint64_t xxhash64(const void* data, std::size_t size, std::uint64_t seed) {
    const auto* p = static_cast<const unsigned char*>(data);
    const unsigned char* const end = p + size;
    std::uint64_t h;
    if (size >= 32) { // four accumulators over 32-byte stripes
        std::uint64_t v1 = seed + kP1 + kP2, v2 = seed + kP2, v3 = seed, v4 = seed - kP1;
        for (; p + 32 <= end; p += 32) {
            v1 = xxRound(v1, read64(p));
            v2 = xxRound(v2, read64(p + 8));
            v3 = xxRound(v3, read64(p + 16));
            v4 = xxRound(v4, read64(p + 24));
        }
        h = rotl(v1, 1) + rotl(v2, 7) + rotl(v3, 12) + rotl(v4, 18);
        h = mergeRound(h, v1);
        h = mergeRound(h, v2);
        h = mergeRound(h, v3);
        h = mergeRound(h, v4);
    } else {
        h = seed + kP5;
    }
    h += std::uint64_t(size);
    for (; p + 8 <= end; p += 8)
        h = rotl(h ^ xxRound(0, read64(p)), 27) * kP1 + kP4;
    if (p + 4 <= end) {
        h = rotl(h ^ (std::uint64_t(read32(p)) * kP1), 23) * kP2 + kP3;
        p += 4;
    }
    for (; p < end; ++p)
        h = rotl(h ^ (std::uint64_t(*p) * kP5), 11) * kP1;
    // Avalanche.
    h ^= h >> 33;
    h *= kP2;
    h ^= h >> 29;
    h *= kP3;
    h ^= h >> 32;
    return h;
}

std::string hex64(std::uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof text, "%016" PRIx64, v);
    return text;
}

std::string fileContentHash(const std::filesystem::path& file, std::string* error) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        if (error)
            *error = file.string() + ": cannot open for reading";
        return {};
    }
    std::vector<char> block(size_t(1) << 20);
    std::uint64_t h = 0x76656c766574ULL; // "velvet"
    std::uint64_t total = 0;
    while (in) {
        in.read(block.data(), std::streamsize(block.size()));
        const std::streamsize n = in.gcount();
        if (n <= 0)
            break;
        h = xxhash64(block.data(), size_t(n), h);
        total += std::uint64_t(n);
    }
    if (in.bad()) {
        if (error)
            *error = file.string() + ": read error while hashing";
        return {};
    }
    return hex64(h) + "-" + std::to_string(total);
}

} // namespace velvet
