#include "core/mip_texture.h"

#include "core/cache_dir.h"
#include "core/color_management.h"
#include "core/half_float.h"
#include "core/image_ops.h"
#include "core/mip_cache.h"
#include "core/mip_filter.h"
#include "core/texture_cache.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <system_error>

namespace velvet {
namespace {

/// Version of what the builder produces: part of every cache key, so a change to the filter or
/// the formats makes old entries misses.
constexpr int kBuildVersion = 1;

double srgbDecode(double v) {
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

/// How an 8-bit file's values become scene-linear in a colour space.
enum class Conversion { Identity, Srgb, Other };

/// Classifies @p space by converting ramps of grey and of each primary through the config
/// (OCIO): the identity (data spaces, linear 8-bit files), the sRGB EOTF per channel (sRGB
/// texture with Rec.709 primaries in a Rec.709 scene-linear config), or anything else (other
/// curves, other primaries: the float path converts those exactly).
Conversion classify(const ColorManagement& cm, const std::string& space) {
    if (cm.isData(space))
        return Conversion::Identity;
    Image ramp(256, 4, 3);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 256; ++x)
            for (int c = 0; c < 3; ++c)
                ramp.at(x, y)[c] = (y == 0 || y - 1 == c) ? float(x) / 255.0f : 0.0f;
    Image linear = ramp;
    std::string error;
    if (!cm.toSceneLinear(linear, space, &error))
        return Conversion::Other;
    bool identity = true, srgb = true;
    for (size_t i = 0; i < ramp.pixels.size(); ++i) {
        const double in = ramp.pixels[i], out = linear.pixels[i];
        const double s = srgbDecode(in);
        identity = identity && std::abs(out - in) <= 1e-5;
        srgb = srgb && std::abs(out - s) <= 1e-3 * s + 1e-6;
    }
    return identity ? Conversion::Identity : srgb ? Conversion::Srgb : Conversion::Other;
}

/// Byte -> float for each channel of an 8-bit level (alpha is always linear).
struct Decode8 {
    std::array<float, 256> colour{}, alpha{};
    explicit Decode8(bool srgb) {
        for (int i = 0; i < 256; ++i) {
            alpha[size_t(i)] = float(i) / 255.0f;
            colour[size_t(i)] = srgb ? float(srgbDecode(i / 255.0)) : alpha[size_t(i)];
        }
    }
    float operator()(int channel, std::uint8_t v) const {
        return channel == 3 ? alpha[v] : colour[v];
    }
};

/// Float -> byte, rounding in the encoded space: for sRGB the byte whose decoded interval
/// holds the value (thresholds at the decoded half steps), else round(v * 255).
struct Encode8 {
    bool srgb;
    std::array<float, 255> thresholds{};
    explicit Encode8(bool s) : srgb(s) {
        for (int b = 0; b < 255; ++b)
            thresholds[size_t(b)] = float(srgbDecode((b + 0.5) / 255.0));
    }
    std::uint8_t operator()(int channel, float v) const {
        if (!srgb || channel == 3)
            return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
        return std::uint8_t(std::upper_bound(thresholds.begin(), thresholds.end(), v) -
                            thresholds.begin());
    }
};

/// Per-channel histograms of an 8-bit RGBA level: exact means and ranges without a float copy.
struct Histogram {
    std::array<std::array<std::uint64_t, 256>, 4> counts{};
    explicit Histogram(const MipLevel& level) {
        const std::uint8_t* p = level.bytes.data();
        const size_t n = size_t(level.width) * size_t(level.height);
        for (size_t i = 0; i < n; ++i, p += 4)
            for (int c = 0; c < 4; ++c)
                ++counts[size_t(c)][p[c]];
    }
    void range(const Decode8& decode, float lo[4], float hi[4]) const {
        for (int c = 0; c < 4; ++c) {
            int first = 0, last = 255;
            while (first < 255 && counts[size_t(c)][size_t(first)] == 0)
                ++first;
            while (last > 0 && counts[size_t(c)][size_t(last)] == 0)
                --last;
            lo[c] = decode(c, std::uint8_t(first));
            hi[c] = decode(c, std::uint8_t(last));
        }
    }
    glm::vec4 mean(const Decode8& decode) const {
        glm::dvec4 sum(0.0);
        std::uint64_t n = 0;
        for (int v = 0; v < 256; ++v)
            n += counts[0][size_t(v)];
        for (int c = 0; c < 4; ++c)
            for (int v = 0; v < 256; ++v)
                sum[c] += double(counts[size_t(c)][size_t(v)]) * decode(c, std::uint8_t(v));
        return glm::vec4(sum / double(std::max<std::uint64_t>(n, 1)));
    }
};

/// The 8-bit path: level 0 is the file's bytes, each next level filtered (in scene-linear for
/// sRGB) from the one above and encoded back.
std::shared_ptr<MipTexture> build8(std::vector<std::uint8_t>&& rgba, int width, int height,
                                   bool srgb, int threads) {
    auto t = std::make_shared<MipTexture>();
    t->format = srgb ? MipFormat::Srgb8Alpha8 : MipFormat::Rgba8;
    const Decode8 decode(srgb);
    const Encode8 encode(srgb);
    const int count = mipLevelCount(width, height);
    t->levels.reserve(size_t(count));
    t->levels.push_back({width, height, std::move(rgba)});
    for (int m = 1; m < count; ++m) {
        const MipLevel& above = t->levels.back();
        const Histogram histogram(above);
        if (m == 1)
            t->mean = histogram.mean(decode);
        float lo[4], hi[4];
        histogram.range(decode, lo, hi);
        MipLevel next;
        next.width = std::max(1, above.width / 2);
        next.height = std::max(1, above.height / 2);
        next.bytes.resize(size_t(next.width) * size_t(next.height) * 4);
        halveLevel(
            above.width, above.height,
            [&](int y, float* out) {
                const std::uint8_t* p = above.bytes.data() + size_t(y) * size_t(above.width) * 4;
                for (int x = 0; x < above.width; ++x, p += 4, out += 4) {
                    out[0] = decode.colour[p[0]];
                    out[1] = decode.colour[p[1]];
                    out[2] = decode.colour[p[2]];
                    out[3] = decode.alpha[p[3]];
                }
            },
            [&](int y, const float* in) {
                std::uint8_t* p = next.bytes.data() + size_t(y) * size_t(next.width) * 4;
                for (int i = 0; i < next.width * 4; ++i)
                    p[i] = encode(i & 3, in[i]);
            },
            lo, hi, threads);
        t->levels.push_back(std::move(next));
    }
    if (count == 1)
        t->mean = Histogram(t->levels[0]).mean(decode);
    return t;
}

void toHalf(const float* in, size_t n, std::uint8_t* out) {
    std::uint16_t chunk[1024];
    for (size_t i = 0; i < n; i += 1024) {
        const size_t count = std::min<size_t>(1024, n - i);
        floatsToHalves(in + i, count, chunk);
        std::memcpy(out + 2 * i, chunk, 2 * count);
    }
}

/// The float path for what the 8-bit one cannot carry exactly: @p image (scene-linear, any
/// channel count) to RGBA16F levels, two float levels alive at a time.
std::shared_ptr<MipTexture> buildHalf(Image image, int threads) {
    auto t = std::make_shared<MipTexture>();
    t->format = MipFormat::Rgba16F;
    Image above(image.width, image.height, 4);
    glm::dvec4 sum(0.0);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const glm::vec4 p = image.rgba(x, y);
            std::memcpy(above.at(x, y), &p.x, sizeof(float) * 4);
            sum += glm::dvec4(p);
        }
    image = Image();
    t->mean = glm::vec4(sum / double(std::max(above.width * above.height, 1)));
    const int count = mipLevelCount(above.width, above.height);
    for (int m = 0; m < count; ++m) {
        MipLevel level{above.width, above.height, {}};
        level.bytes.resize(above.pixels.size() * 2);
        toHalf(above.pixels.data(), above.pixels.size(), level.bytes.data());
        t->levels.push_back(std::move(level));
        if (m + 1 == count)
            break;
        float lo[4], hi[4];
        std::fill_n(lo, 4, std::numeric_limits<float>::max());
        std::fill_n(hi, 4, std::numeric_limits<float>::lowest());
        for (size_t i = 0; i < above.pixels.size(); ++i) {
            lo[i & 3] = std::min(lo[i & 3], above.pixels[i]);
            hi[i & 3] = std::max(hi[i & 3], above.pixels[i]);
        }
        Image next(std::max(1, above.width / 2), std::max(1, above.height / 2), 4);
        halveLevel(
            above.width, above.height,
            [&](int y, float* out) {
                std::memcpy(out, above.at(0, y), sizeof(float) * 4 * size_t(above.width));
            },
            [&](int y, const float* in) {
                std::memcpy(next.at(0, y), in, sizeof(float) * 4 * size_t(next.width));
            },
            lo, hi, threads);
        above = std::move(next);
    }
    return t;
}

/// readImage()'s message starts with the file name, which Problem::file already holds.
std::string withoutFilePrefix(std::string message, const std::filesystem::path& file) {
    const std::string prefix = file.string() + ": ";
    if (message.compare(0, prefix.size(), prefix) == 0)
        message.erase(0, prefix.size());
    return message;
}

/// Only a level 0 of more than 4 MiB (a 1024² RGBA8 map) is left in the cache entry: a smaller
/// one costs less than reopening the file, and atlas means read the levels up to 256 px.
bool leavesFinestInCache(const MipTexture& t) {
    return std::uint64_t(t.width()) * std::uint64_t(t.height()) *
               std::uint64_t(mipBytesPerPixel(t.format)) >
           (std::uint64_t(4) << 20);
}

bool readFinestFromCache(const std::filesystem::path& entry, MipTexture& t, std::string* why) {
    MipLevel& l = t.levels[0];
    l.bytes.resize(size_t(l.width) * size_t(l.height) * size_t(mipBytesPerPixel(t.format)));
    return readMipCacheRows(entry, t, 0, 0, l.height, l.bytes.data(), why);
}

} // namespace

int mipBytesPerPixel(MipFormat format) {
    return format == MipFormat::Rgba16F ? 8 : 4;
}

std::uint64_t MipTexture::byteSize() const {
    std::uint64_t bytes = 0;
    for (const MipLevel& l : levels)
        bytes += std::uint64_t(l.width) * std::uint64_t(l.height) *
                 std::uint64_t(mipBytesPerPixel(format));
    return bytes;
}

Image MipTexture::linearLevel(int maxSide) const {
    const MipLevel* pick = nullptr;
    for (const MipLevel& l : levels)
        if (l.width <= maxSide && l.height <= maxSide && !l.bytes.empty()) {
            pick = &l;
            break;
        }
    if (!pick)
        return {};
    Image out(pick->width, pick->height, 4);
    const size_t n = out.pixels.size();
    if (format == MipFormat::Rgba16F) {
        std::vector<std::uint16_t> halves(n);
        std::memcpy(halves.data(), pick->bytes.data(), 2 * n);
        halvesToFloats(halves.data(), n, out.pixels.data());
    } else {
        const Decode8 decode(format == MipFormat::Srgb8Alpha8);
        for (size_t i = 0; i < n; ++i)
            out.pixels[i] = decode(int(i & 3), pick->bytes[i]);
    }
    return out;
}

std::filesystem::path defaultMipCacheDir() {
    const std::filesystem::path root = velvetCacheDir();
    return root.empty() ? root : root / "textures";
}

MipLoadResult loadMipTexture(const std::filesystem::path& file, const std::string& colorSpace,
                             TextureUsage usage, const ColorManagement& colorManagement,
                             const MipLoadOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    MipLoadResult result;
    auto problem = [&](Problem::Severity severity, std::string message) {
        result.problems.push_back({severity, file.string(), std::string(), std::move(message)});
    };
    auto finish = [&] {
        result.milliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        return result;
    };
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) {
        problem(Problem::Severity::Error, "no such file");
        return finish();
    }

    // The cache, keyed by the file's content (not its name or date: a copy hits, an edit
    // misses) and by everything that shapes the levels.
    const std::filesystem::path dir =
        options.useCache ? (options.cacheDir.empty() ? defaultMipCacheDir() : options.cacheDir)
                         : std::filesystem::path();
    std::string key;
    auto lap = [last = std::chrono::steady_clock::now()]() mutable {
        const auto now = std::chrono::steady_clock::now();
        const double ms = std::chrono::duration<double, std::milli>(now - last).count();
        last = now;
        return ms;
    };
    if (!dir.empty()) {
        std::string error;
        const std::string hash = fileContentHash(file, &error);
        result.hashMs = lap();
        if (!hash.empty()) {
            key = "v" + std::to_string(kBuildVersion) + " " + hash + " space=" + colorSpace +
                  (usage == TextureUsage::Color ? " color" : " data") +
                  " max=" + std::to_string(options.maxTextureSide) +
                  " config=" + colorManagement.configPath().string();
            result.cacheEntry = mipCacheEntry(dir, key);
            result.cacheKey = key;
            auto cached = std::make_shared<MipTexture>();
            std::string why;
            bool hit = readMipCache(result.cacheEntry, key, *cached, &why,
                                    options.leaveFinestInCache ? 1 : 0);
            if (hit && options.leaveFinestInCache) {
                if (leavesFinestInCache(*cached))
                    cached->finestInCache = result.cacheEntry;
                else
                    hit = readFinestFromCache(result.cacheEntry, *cached, &why);
            }
            result.cacheReadMs = lap();
            if (hit) {
                result.texture = std::move(cached);
                result.fromCache = true;
                return finish();
            }
            if (!why.empty())
                problem(Problem::Severity::Warning,
                        "texture cache entry " + result.cacheEntry.string() +
                            " could not be used (" + why + "); rebuilt from the file");
        }
    }

    result.decoded = true;
    ImageInfo info;
    std::string error;
    if (!readImageInfo(file, info, &error, options.limits)) {
        problem(Problem::Severity::Error, withoutFilePrefix(error, file));
        return finish();
    }
    const bool fits = options.maxTextureSide < 1 || (info.width <= options.maxTextureSide &&
                                                     info.height <= options.maxTextureSide);
    const Conversion conversion =
        info.bitsPerSample == 8 && !info.isFloat && info.orientation == 1 && fits
            ? classify(colorManagement, colorSpace)
            : Conversion::Other;
    if (conversion != Conversion::Other) {
        std::vector<std::uint8_t> rgba;
        if (!readImage8(file, rgba, info, &error, options.limits)) {
            problem(Problem::Severity::Error, withoutFilePrefix(error, file));
            return finish();
        }
        result.decodeMs = lap();
        result.texture = build8(std::move(rgba), info.width, info.height,
                                conversion == Conversion::Srgb, options.threads);
    } else {
        Image image;
        if (!readImage(file, image, &error, options.limits)) {
            problem(Problem::Severity::Error, withoutFilePrefix(error, file));
            return finish();
        }
        std::string warning;
        if (fitToLimit(image, options.maxTextureSide, &warning, file.string()))
            problem(Problem::Severity::Warning, withoutFilePrefix(warning, file));
        if (!colorManagement.toSceneLinear(image, colorSpace, &error)) {
            problem(Problem::Severity::Error,
                    "cannot convert from colour space \"" + colorSpace + "\": " + error);
            return finish();
        }
        result.decodeMs = lap();
        result.texture = buildHalf(std::move(image), options.threads);
    }
    result.filterMs = lap();
    if ((options.writeCache || options.leaveFinestInCache) && !key.empty() &&
        storeMipTexture(result) && options.leaveFinestInCache &&
        leavesFinestInCache(*result.texture)) {
        std::vector<std::uint8_t>().swap(result.texture->levels[0].bytes);
        result.texture->finestInCache = result.cacheEntry;
    }
    return finish();
}

bool storeMipTexture(MipLoadResult& result) {
    if (!result.texture || result.cacheKey.empty() || result.fromCache)
        return false;
    std::string error;
    const auto start = std::chrono::steady_clock::now();
    const bool written = writeMipCache(result.cacheEntry, result.cacheKey, *result.texture, &error);
    result.cacheWriteMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!written)
        result.problems.push_back({Problem::Severity::Warning, std::string(), std::string(),
                                   "texture not cached: " + error});
    return written;
}

} // namespace velvet
