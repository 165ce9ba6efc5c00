#include "core/ibl_cache.h"

#include "core/atomic_file.h"
#include "core/content_hash.h"

#include <algorithm>
#include <cstring>
#include <system_error>

namespace velvet {
namespace {

/// Header after the two text lines: width, height, faceSize, levels (int32), then SH9 (27
/// floats); then the halves; then the checksum (uint64). Little-endian, as the machine.
constexpr size_t kHeaderInts = 4;
constexpr size_t kShFloats = 27;
constexpr int kMaxSide = 1 << 16; ///< refuses absurd sizes before allocating
constexpr int kMaxFaceSize = 4096;

std::string magic() {
    return "velvet-ibl-cache " + std::to_string(kIblCacheVersion) + "\n";
}

size_t levelHalves(int faceSize, int level) {
    const size_t size = size_t(std::max(faceSize >> level, 1));
    return size * size * 6u * 4u;
}

/// Halves in the payload for these sizes (0 when they are out of range).
size_t payloadHalves(int width, int height, int faceSize, int levels) {
    if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide || faceSize < 1 ||
        faceSize > kMaxFaceSize || levels < 1 || levels > 16)
        return 0;
    size_t n = size_t(width) * size_t(height) * 3u;
    for (int l = 0; l < levels; ++l)
        n += levelHalves(faceSize, l);
    return n;
}

template <typename T>
void append(std::string& out, const T* data, size_t count) {
    out.append(reinterpret_cast<const char*>(data), count * sizeof(T));
}

} // namespace

std::filesystem::path iblCacheFile(const std::filesystem::path& dir, const std::string& key) {
    return dir / "environments" / (hex64(xxhash64(key, 1771)) + ".ibl");
}

bool writeIblCache(const std::filesystem::path& file, const std::string& key,
                   const IblCacheEntry& e, std::string* error) {
    const size_t halves = payloadHalves(e.width, e.height, e.faceSize, e.levels);
    size_t given = e.equirect.size();
    for (const auto& level : e.specular)
        given += level.size();
    if (halves == 0 || given != halves || int(e.specular.size()) != e.levels ||
        e.equirect.size() != size_t(e.width) * size_t(e.height) * 3u) {
        if (error)
            *error = file.string() + ": inconsistent environment cache entry (not written)";
        return false;
    }
    std::string out = magic() + "key=" + key + "\n";
    out.reserve(out.size() + kHeaderInts * 4 + kShFloats * 4 + halves * 2 + 8);
    const std::int32_t header[kHeaderInts] = {e.width, e.height, e.faceSize, e.levels};
    append(out, header, kHeaderInts);
    for (const glm::vec3& c : e.sh)
        append(out, &c.x, 3);
    append(out, e.equirect.data(), e.equirect.size());
    for (const auto& level : e.specular)
        append(out, level.data(), level.size());
    const std::uint64_t sum = xxhash64(out, 0);
    append(out, &sum, 1);
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
    if (ec) {
        if (error)
            *error = file.string() + ": cannot create the cache folder: " + ec.message();
        return false;
    }
    return writeFileAtomically(file, out, error);
}

bool readIblCache(const std::filesystem::path& file, const std::string& key, IblCacheEntry& out,
                  std::string* why) {
    auto fail = [&](const std::string& what) {
        if (why)
            *why = what;
        return false;
    };
    std::error_code ec;
    if (!std::filesystem::exists(file, ec))
        return fail({});
    std::string reason;
    // The largest entry payloadHalves() accepts is far below this; a bigger file is not ours.
    const auto data = readFileWithLimit(file, std::uintmax_t(1) << 34, &reason);
    if (!data)
        return fail("cannot be read (" + reason + ")");
    const std::string& d = *data;
    const std::string head = magic(), keyLine = "key=" + key + "\n";
    if (d.compare(0, head.size(), head) != 0)
        return fail("not a Velvet environment cache entry of version " +
                    std::to_string(kIblCacheVersion));
    // The key may hold line breaks (content hash, then the bake's signature): compared whole.
    if (d.compare(head.size(), keyLine.size(), keyLine) != 0)
        return fail("made for another file or bake");
    size_t at = head.size() + keyLine.size();
    const size_t fixed = kHeaderInts * 4 + kShFloats * 4;
    if (d.size() < at + fixed + 8)
        return fail("truncated (" + std::to_string(d.size()) + " bytes)");
    std::int32_t header[kHeaderInts];
    std::memcpy(header, d.data() + at, sizeof header);
    const size_t halves = payloadHalves(header[0], header[1], header[2], header[3]);
    if (halves == 0)
        return fail("damaged header (sizes out of range)");
    const size_t expected = at + fixed + halves * 2 + 8;
    if (d.size() != expected)
        return fail((d.size() < expected ? "truncated (" : "damaged (") + std::to_string(d.size()) +
                    " bytes, expected " + std::to_string(expected) + ")");
    std::uint64_t sum;
    std::memcpy(&sum, d.data() + expected - 8, 8);
    if (xxhash64(d.data(), expected - 8, 0) != sum)
        return fail("damaged (checksum mismatch)");

    IblCacheEntry e;
    e.width = header[0], e.height = header[1], e.faceSize = header[2], e.levels = header[3];
    at += kHeaderInts * 4;
    for (glm::vec3& c : e.sh) {
        std::memcpy(&c.x, d.data() + at, 12);
        at += 12;
    }
    e.equirect.resize(size_t(e.width) * size_t(e.height) * 3u);
    std::memcpy(e.equirect.data(), d.data() + at, e.equirect.size() * 2);
    at += e.equirect.size() * 2;
    for (int l = 0; l < e.levels; ++l) {
        std::vector<std::uint16_t> level(levelHalves(e.faceSize, l));
        std::memcpy(level.data(), d.data() + at, level.size() * 2);
        at += level.size() * 2;
        e.specular.push_back(std::move(level));
    }
    out = std::move(e);
    return true;
}

} // namespace velvet
