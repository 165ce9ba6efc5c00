#include "core/content_hash.h"

#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <vector>
#include <xxhash.h>

namespace velvet {

std::uint64_t xxhash64(const void* data, std::size_t size, std::uint64_t seed) {
    return XXH64(data, size, seed);
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
