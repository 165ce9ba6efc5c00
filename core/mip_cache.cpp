#include "core/mip_cache.h"

#include "core/atomic_file.h"
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

// OpenImageIO stays inside .cpp files (DESIGN.md, "Heavy dependencies behind a .cpp").
#include <OpenImageIO/hash.h>
#include <OpenImageIO/imageio.h>

namespace velvet {
namespace {

constexpr const char* kMagic = "velvet-mip-cache 1";
/// TIFF compression of entries (BENCHMARKS.md, "Texture loading": measured against "none").
constexpr const char* kCompression = "none";

std::string hex64(std::uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof text, "%016" PRIx64, v);
    return text;
}

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

OIIO::TypeDesc typeOf(MipFormat f) {
    return f == MipFormat::Rgba16F ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::UINT8;
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

std::string oneLine(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' '))
        s.pop_back();
    for (char& c : s)
        if (c == '\n')
            c = ' ';
    return s.empty() ? std::string("unknown OpenImageIO error") : s;
}

} // namespace

std::string fileContentHash(const std::filesystem::path& file, std::string* error) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        if (error)
            *error = file.string() + ": cannot open for reading";
        return {};
    }
    std::vector<char> block(size_t(1) << 20);
    unsigned long long h = 0x76656c766574ULL; // "velvet"
    std::uint64_t total = 0;
    while (in) {
        in.read(block.data(), std::streamsize(block.size()));
        const std::streamsize n = in.gcount();
        if (n <= 0)
            break;
        h = OIIO::xxhash::XXH64(block.data(), size_t(n), h);
        total += std::uint64_t(n);
    }
    if (in.bad()) {
        if (error)
            *error = file.string() + ": read error while hashing";
        return {};
    }
    return hex64(std::uint64_t(h)) + "-" + std::to_string(total);
}

std::filesystem::path mipCacheEntry(const std::filesystem::path& dir, const std::string& key) {
    return dir / (hex64(OIIO::xxhash::XXH64(key.data(), key.size(), 1771)) + ".tx");
}

bool readMipCache(const std::filesystem::path& entry, const std::string& key, MipTexture& out,
                  std::string* why) {
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
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1); // stored straight; never premultiplied
    auto in = OIIO::ImageInput::open(entry.string(), &config);
    if (!in)
        return fail("not a readable texture file (" + oneLine(OIIO::geterror()) + ")");
    const std::string description = in->spec().get_string_attribute("ImageDescription");
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
    const OIIO::ImageSpec top = in->spec(); // a copy: seek_subimage replaces in->spec()
    if (top.nchannels != 4 || top.format != typeOf(t.format) || top.width < 1 || top.height < 1)
        return fail("level 0 is not " + std::string(formatName(t.format)) + " RGBA");
    const int count = mipLevelCount(top.width, top.height);
    const int bpp = mipBytesPerPixel(t.format);
    for (int m = 0; m < count; ++m) {
        if (!in->seek_subimage(0, m))
            return fail("has " + std::to_string(m) + " of " + std::to_string(count) +
                        " mip levels");
        const OIIO::ImageSpec& s = in->spec();
        const int w = std::max(1, top.width >> m), h = std::max(1, top.height >> m);
        if (s.width != w || s.height != h || s.nchannels != 4)
            return fail("mip level " + std::to_string(m) + " is " + std::to_string(s.width) + "x" +
                        std::to_string(s.height) + ", expected " + std::to_string(w) + "x" +
                        std::to_string(h));
        MipLevel level;
        level.width = w;
        level.height = h;
        level.bytes.resize(size_t(w) * size_t(h) * size_t(bpp));
        if (!in->read_image(0, m, 0, 4, typeOf(t.format), level.bytes.data()) || in->has_error())
            return fail("mip level " + std::to_string(m) +
                        " is truncated or corrupt (OpenImageIO: " + oneLine(in->geterror()) + ")");
        t.levels.push_back(std::move(level));
    }
    out = std::move(t);
    return true;
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
    auto out = OIIO::ImageOutput::create("tiff");
    if (!out || !out->supports("tiles") ||
        !(out->supports("mipmap") || out->supports("multiimage")))
        return fail("OpenImageIO's TIFF writer cannot write tiled MIP-mapped files");
    // OpenImageIO's TIFF writer takes the levels as appended subimages, as maketx writes them:
    // with "textureformat" set its reader presents the reduced-resolution directories as MIP
    // levels of subimage 0.
    const auto appendMode = out->supports("mipmap") ? OIIO::ImageOutput::AppendMIPLevel
                                                    : OIIO::ImageOutput::AppendSubimage;

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

    const OIIO::TypeDesc type = typeOf(texture.format);
    for (size_t m = 0; m < texture.levels.size(); ++m) {
        const MipLevel& level = texture.levels[m];
        OIIO::ImageSpec spec(level.width, level.height, 4, type);
        // maketx's layout: 64x64 tiles, every level a MIP level of subimage 0.
        spec.tile_width = spec.tile_height = 64;
        spec.tile_depth = 1;
        spec.channelnames = {"R", "G", "B", "A"};
        spec.alpha_channel = 3;
        spec.attribute("oiio:UnassociatedAlpha", 1);
        spec.attribute("compression", kCompression);
        spec.attribute("textureformat", "Plain Texture");
        spec.attribute("wrapmodes", "periodic,periodic");
        if (texture.format == MipFormat::Srgb8Alpha8)
            spec.attribute("oiio:ColorSpace", "sRGB");
        spec.attribute("ImageDescription", describe(key, texture));
        const bool opened =
            out->open(tmp.string(), spec, m == 0 ? OIIO::ImageOutput::Create : appendMode);
        if (!opened || !out->write_image(type, level.bytes.data())) {
            const std::string why = oneLine(out->geterror());
            out->close();
            cleanup();
            return fail("cannot write the cache entry: " + why);
        }
    }
    if (!out->close()) {
        cleanup();
        return fail("cannot write the cache entry: " + oneLine(out->geterror()));
    }
    std::filesystem::rename(tmp, entry, ec);
    if (ec) {
        cleanup();
        return fail("cannot move the cache entry into place: " + ec.message());
    }
    return true;
}

} // namespace velvet
