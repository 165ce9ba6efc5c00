#include "core/mip_cache.h"

#include "core/atomic_file.h"
#include "core/content_hash.h"
#include "core/image_codec.h"
#include "core/image_ops.h"
#include "core/mip_texture.h"

#include <atomic>
#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <system_error>
#include <unistd.h>
#include <vector>

namespace velvet {
namespace {

constexpr const char* kMagic = "velvet-mip-cache 1";

const char* formatName(MipFormat f) {
    switch (f) {
    case MipFormat::Rgba8:
        return "rgba8";
    case MipFormat::Srgb8Alpha8:
        return "srgb8_alpha8";
    case MipFormat::Rgba16F:
        return "rgba16f";
    }
    return "rgba8";
}

/// The entry's ImageDescription (TIFF tag 270, where maketx puts its own "SHA-1=" hash): the
/// magic line, the key, the format and the mean.
std::string describe(const std::string& key, const MipTexture& t) {
    char mean[160];
    std::snprintf(mean, sizeof mean, "mean=%.9g %.9g %.9g %.9g", double(t.mean.r), double(t.mean.g),
                  double(t.mean.b), double(t.mean.a));
    return std::string(kMagic) + "\nkey=" + key + "\nformat=" + formatName(t.format) + "\n" + mean +
           "\n";
}

} // namespace

std::filesystem::path mipCacheEntry(const std::filesystem::path& dir, const std::string& key) {
    return dir / (hex64(xxhash64(key.data(), key.size(), 1771)) + ".tx");
}

bool readMipCache(const std::filesystem::path& entry, const std::string& key, MipTexture& out,
                  std::string* why, int firstLevel) {
    std::error_code ec;
    if (!std::filesystem::exists(entry, ec)) {
        if (why)
            why->clear();
        return false;
    }
    auto fail = [&](const std::string& what) {
        if (why)
            *why = what;
        return false;
    };
    std::string codecError;
    const codec::ImageCodec* imageCodec = codec::imageCodec(&codecError);
    if (!imageCodec)
        return fail(codecError);
    std::string description;
    bool half = false;
    std::vector<MipLevel> levels;
    if (!imageCodec->readMipFile(entry, description, half, levels, firstLevel, why))
        return false;
    std::istringstream lines(description);
    std::string magic, keyLine, formatLine, meanLine;
    std::getline(lines, magic);
    std::getline(lines, keyLine);
    std::getline(lines, formatLine);
    std::getline(lines, meanLine);
    if (magic != kMagic)
        return fail("not a Velvet cache entry (no \"" + std::string(kMagic) + "\" description)");
    if (keyLine != "key=" + key)
        return fail("made for another file or version (" + keyLine + ")");
    MipTexture t;
    bool known = false;
    for (MipFormat f : {MipFormat::Rgba8, MipFormat::Srgb8Alpha8, MipFormat::Rgba16F})
        if (formatLine == std::string("format=") + formatName(f))
            t.format = f, known = true;
    if (!known)
        return fail("unknown pixel format line \"" + formatLine + "\"");
    if (std::sscanf(meanLine.c_str(), "mean=%f %f %f %f", &t.mean.r, &t.mean.g, &t.mean.b,
                    &t.mean.a) != 4)
        return fail("no mean line");
    if (levels.empty() || half != (t.format == MipFormat::Rgba16F))
        return fail("level 0 is not " + std::string(formatName(t.format)) + " RGBA");
    const int width = levels[0].width, height = levels[0].height;
    const int count = mipLevelCount(width, height);
    if (int(levels.size()) < count)
        return fail("has " + std::to_string(levels.size()) + " of " + std::to_string(count) +
                    " mip levels");
    levels.resize(size_t(count));
    for (int m = 0; m < count; ++m) {
        const MipLevel& s = levels[size_t(m)];
        const int w = std::max(1, width >> m), h = std::max(1, height >> m);
        if (s.width != w || s.height != h)
            return fail("mip level " + std::to_string(m) + " is " + std::to_string(s.width) + "x" +
                        std::to_string(s.height) + ", expected " + std::to_string(w) + "x" +
                        std::to_string(h));
    }
    t.levels = std::move(levels);
    out = std::move(t);
    return true;
}

bool readMipCacheRows(const std::filesystem::path& entry, const MipTexture& texture, int level,
                      int y0, int rows, std::uint8_t* out, std::string* why) {
    std::string codecError;
    const codec::ImageCodec* imageCodec = codec::imageCodec(&codecError);
    if (!imageCodec) {
        if (why)
            *why = codecError;
        return false;
    }
    if (level < 0 || level >= int(texture.levels.size()) || y0 % kMipCacheTileSide != 0) {
        if (why)
            *why = "no band of rows " + std::to_string(y0) + "+" + std::to_string(rows) +
                   " in mip level " + std::to_string(level);
        return false;
    }
    return imageCodec->readMipRows(entry, level, texture.levels[size_t(level)].width, y0, rows,
                                   texture.format == MipFormat::Rgba16F, out, why);
}

bool writeMipCache(const std::filesystem::path& entry, const std::string& key,
                   const MipTexture& texture, std::string* error) {
    auto fail = [&](const std::string& what) {
        if (error)
            *error = entry.string() + ": " + what;
        return false;
    };
    if (texture.levels.empty())
        return fail("nothing to write");
    std::error_code ec;
    std::filesystem::create_directories(entry.parent_path(), ec);
    if (ec)
        return fail("cannot create the cache folder: " + ec.message());
    std::string codecError;
    const codec::ImageCodec* imageCodec = codec::imageCodec(&codecError);
    if (!imageCodec)
        return fail(codecError);

    // A named temporary beside the entry (same file system: the rename is atomic), named as
    // core/atomic_file names its temporaries so the next write sweeps one a killed run left.
    static std::atomic<unsigned> counter{0};
    sweepStaleTemporaries(entry);
    std::filesystem::path tmp = entry;
    std::string tmpName(1, '.');
    tmpName += entry.filename().string();
    tmpName += ".velvet-tmp-" + std::to_string(::getpid()) + "-m" + std::to_string(counter++);
    tmp.replace_filename(tmpName);
    auto cleanup = [&] { std::filesystem::remove(tmp, ec); };

    std::string why;
    if (!imageCodec->writeMipFile(tmp, describe(key, texture), texture.format == MipFormat::Rgba16F,
                                  texture.format == MipFormat::Srgb8Alpha8, texture.levels, &why)) {
        cleanup();
        return fail("cannot write the cache entry: " + why);
    }
    std::filesystem::rename(tmp, entry, ec);
    if (ec) {
        cleanup();
        return fail("cannot move the cache entry into place: " + ec.message());
    }
    return true;
}

} // namespace velvet
