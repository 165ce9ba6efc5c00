// core/mip_texture, mip_cache, texture_loader (issue 16, "Textures at the sizes artists use"):
// 8-bit files stay 8-bit (RGBA8 / SRGB8_ALPHA8), sRGB levels are filtered in scene-linear, the
// chain is cached on disk keyed by the file's content as a tiled MIP-mapped TIFF (maketx's
// layout), a damaged entry is rebuilt with a message naming it, a large level 0 can stay in the
// entry and be read back in bands, the loader works off the calling thread, and a 2048² map's
// load peaks under twice its GPU size.
#include "core/color_management.h"
#include "core/image.h"
#include "core/image_ops.h"
#include "core/mip_cache.h"
#include "core/mip_texture.h"
#include "core/texture_cache.h"
#include "core/texture_loader.h"

#include <OpenImageIO/imageio.h>
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

// clang says AddressSanitizer through __has_feature, GCC through __SANITIZE_ADDRESS__.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VELVET_HAS_ASAN 1
#endif
#endif
#ifndef VELVET_HAS_ASAN
#define VELVET_HAS_ASAN 0
#endif

using namespace velvet;
namespace fs = std::filesystem;

namespace {

/// A map with a step and texture, RGBA, 8-bit values.
Image pattern(int w, int h) {
    Image img(w, h, 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = img.at(x, y);
            p[0] = x < w / 2 ? 0.1f : 0.9f;
            p[1] = float((x * 37 + y * 11) % 256) / 255.0f;
            p[2] = float(y % 17) / 16.0f;
            p[3] = 1.0f;
        }
    return img;
}

double statusMb(const char* field) {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(field, 0) == 0)
            return std::stod(line.substr(line.find(':') + 1)) / 1024.0;
    return NAN;
}

bool mentions(const std::vector<Problem>& problems, const std::string& text) {
    for (const Problem& p : problems)
        if (p.toString().find(text) != std::string::npos)
            return true;
    return false;
}

} // namespace

class TestCoreMipTexture : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;
    ColorManagement m_cm;
    fs::path path(const std::string& name) { return fs::path(m_dir.path().toStdString()) / name; }
    MipLoadOptions options(const std::string& cache) {
        MipLoadOptions o;
        o.cacheDir = path(cache);
        return o;
    }
    std::string srgb() {
        return resolveTextureColorSpace(m_cm, "x.png", TextureUsage::Color, "sRGB texture");
    }
    std::string raw() { return resolveTextureColorSpace(m_cm, "x.png", TextureUsage::Data, {}); }

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(m_cm.loadDefault(&error), error.c_str());
    }

    // An 8-bit file keeps its bytes as level 0; data is RGBA8, sRGB colour SRGB8_ALPHA8, a
    // 16-bit file (more precision than 8 bits) RGBA16F; every chain is complete.
    void eightBitStaysEightBit() {
        const fs::path file = path("eight.png");
        std::string error;
        QVERIFY2(writeImage(file, pattern(32, 16), PixelFormat::UInt8, &error), error.c_str());
        const MipLoadResult data =
            loadMipTexture(file, raw(), TextureUsage::Data, m_cm, options("c1"));
        QVERIFY(data.texture);
        QCOMPARE(int(data.texture->format), int(MipFormat::Rgba8));
        QCOMPARE(int(data.texture->levels.size()), mipLevelCount(32, 16));
        Image decoded;
        QVERIFY(readImage(file, decoded, &error));
        for (int y = 0; y < 16; ++y) // level 0 is the file's bytes
            for (int x = 0; x < 32; ++x)
                for (int c = 0; c < 4; ++c)
                    QCOMPARE(int(data.texture->levels[0].bytes[(size_t(y) * 32 + x) * 4 + c]),
                             int(std::lround(decoded.rgba(x, y)[c] * 255.0f)));
        const MipLoadResult colour =
            loadMipTexture(file, srgb(), TextureUsage::Color, m_cm, options("c1"));
        QVERIFY(colour.texture);
        QCOMPARE(int(colour.texture->format), int(MipFormat::Srgb8Alpha8));
        const fs::path deep = path("sixteen.png");
        QVERIFY2(writeImage(deep, pattern(32, 16), PixelFormat::UInt16, &error), error.c_str());
        const MipLoadResult half =
            loadMipTexture(deep, srgb(), TextureUsage::Color, m_cm, options("c1"));
        QVERIFY(half.texture);
        QCOMPARE(int(half.texture->format), int(MipFormat::Rgba16F));
        QCOMPARE(int(half.texture->levels.size()), mipLevelCount(32, 16));
    }

    // A 2x2 checker of sRGB 0 and 255 averages to scene-linear 0.5, whose sRGB byte is 188, not
    // the 128 an average of the encoded bytes would give (GL 4.5 section 8.24: sRGB textures
    // are filtered after decoding; so are their levels here).
    void srgbLevelsAreFilteredInLinear() {
        Image checker(2, 2, 3);
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 2; ++x)
                for (int c = 0; c < 3; ++c)
                    checker.at(x, y)[c] = float((x + y) % 2);
        const fs::path file = path("checker.png");
        std::string error;
        QVERIFY(writeImage(file, checker, PixelFormat::UInt8, &error));
        const MipLoadResult r =
            loadMipTexture(file, srgb(), TextureUsage::Color, m_cm, options("c2"));
        QVERIFY(r.texture);
        QCOMPARE(int(r.texture->levels.size()), 2);
        const int byte = r.texture->levels[1].bytes[0];
        qInfo("1x1 level of a black/white checker: sRGB byte %d", byte);
        QVERIFY2(std::abs(byte - 188) <= 1, qPrintable(QString::number(byte)));
        QVERIFY(std::abs(r.texture->mean.r - 0.5f) < 1e-6f);
    }

    // The second load of the same content is a cache hit with the same levels, also under
    // another name (keyed by content, not by path); an edited file is a miss.
    void cacheIsKeyedByContent() {
        const fs::path file = path("map.png");
        std::string error;
        QVERIFY(writeImage(file, pattern(64, 64), PixelFormat::UInt8, &error));
        const MipLoadResult first =
            loadMipTexture(file, srgb(), TextureUsage::Color, m_cm, options("c3"));
        QVERIFY(first.texture && first.decoded && !first.fromCache);
        QVERIFY(first.problems.empty());
        const MipLoadResult second =
            loadMipTexture(file, srgb(), TextureUsage::Color, m_cm, options("c3"));
        QVERIFY(second.texture && !second.decoded && second.fromCache);
        QCOMPARE(second.texture->levels.size(), first.texture->levels.size());
        for (size_t m = 0; m < first.texture->levels.size(); ++m)
            QVERIFY(second.texture->levels[m].bytes == first.texture->levels[m].bytes);
        QVERIFY(std::abs(second.texture->mean.g - first.texture->mean.g) < 1e-6f);
        const fs::path copy = path("copy of map.png");
        fs::copy_file(file, copy);
        QVERIFY(loadMipTexture(copy, srgb(), TextureUsage::Color, m_cm, options("c3")).fromCache);
        // Another colour space of the same file is another entry.
        QVERIFY(!loadMipTexture(file, raw(), TextureUsage::Data, m_cm, options("c3")).fromCache);
        QVERIFY(writeImage(file, pattern(64, 32), PixelFormat::UInt8, &error));
        const MipLoadResult edited =
            loadMipTexture(file, srgb(), TextureUsage::Color, m_cm, options("c3"));
        QVERIFY(edited.decoded && edited.texture->height() == 32);
    }

    // The entry is what maketx writes: a tiled (64x64) TIFF whose levels are MIP levels of
    // subimage 0, "Plain Texture", so OpenImageIO's tools and TextureSystem read it.
    void entryIsATiledMipMappedTiff() {
        const fs::path file = path("tiff.png");
        std::string error;
        QVERIFY(writeImage(file, pattern(128, 64), PixelFormat::UInt8, &error));
        const MipLoadResult r =
            loadMipTexture(file, srgb(), TextureUsage::Color, m_cm, options("c4"));
        QVERIFY(fs::exists(r.cacheEntry));
        auto in = OIIO::ImageInput::open(r.cacheEntry.string());
        QVERIFY(in);
        QCOMPARE(std::string(in->format_name()), std::string("tiff"));
        QCOMPARE(in->spec().tile_width, 64);
        QCOMPARE(in->spec().get_string_attribute("textureformat"), std::string("Plain Texture"));
        int levels = 0;
        while (in->seek_subimage(0, levels))
            ++levels;
        QCOMPARE(levels, mipLevelCount(128, 64));
        QVERIFY(!in->seek_subimage(1, 0)); // one subimage: the levels are its MIP levels
    }

    // A truncated or foreign entry is not used: the file is decoded again, a warning names the
    // entry and says it was rebuilt, and the rebuilt entry is a hit next time.
    void damagedEntryIsRebuiltWithAMessage() {
        const fs::path file = path("damaged.png");
        std::string error;
        QVERIFY(writeImage(file, pattern(64, 64), PixelFormat::UInt8, &error));
        const MipLoadResult first =
            loadMipTexture(file, srgb(), TextureUsage::Color, m_cm, options("c5"));
        const auto size = fs::file_size(first.cacheEntry);
        fs::resize_file(first.cacheEntry, size / 2);
        const MipLoadResult second =
            loadMipTexture(file, srgb(), TextureUsage::Color, m_cm, options("c5"));
        QVERIFY(second.texture && second.decoded);
        QVERIFY(mentions(second.problems, first.cacheEntry.string()));
        QVERIFY(mentions(second.problems, "rebuilt"));
        for (const Problem& p : second.problems)
            qInfo("%s", p.toString().c_str());
        QCOMPARE(second.problems[0].severity, Problem::Severity::Warning);
        QVERIFY(second.texture->levels[0].bytes == first.texture->levels[0].bytes);
        const MipLoadResult third =
            loadMipTexture(file, srgb(), TextureUsage::Color, m_cm, options("c5"));
        QVERIFY(third.fromCache && third.problems.empty());
        // Garbage under the entry's name: the same.
        std::ofstream(first.cacheEntry, std::ios::trunc) << "not a tiff";
        const MipLoadResult fourth =
            loadMipTexture(file, srgb(), TextureUsage::Color, m_cm, options("c5"));
        QVERIFY(fourth.decoded && mentions(fourth.problems, "rebuilt"));
        // No temporary is left beside the entry.
        int files = 0;
        for (const auto& e : fs::directory_iterator(first.cacheEntry.parent_path()))
            files += e.is_regular_file() ? 1 : 0;
        QCOMPARE(files, 1);
    }

    // Missing and broken files: an error naming the problem, no texture.
    void badFilesAreProblems() {
        const MipLoadResult missing =
            loadMipTexture(path("none.png"), srgb(), TextureUsage::Color, m_cm, options("c6"));
        QVERIFY(!missing.texture && mentions(missing.problems, "no such file"));
        const fs::path junk = path("junk.png");
        std::ofstream(junk) << "definitely not a png";
        const MipLoadResult broken =
            loadMipTexture(junk, srgb(), TextureUsage::Color, m_cm, options("c6"));
        QVERIFY(!broken.texture && !broken.problems.empty());
        QCOMPARE(broken.problems[0].severity, Problem::Severity::Error);
    }

    // An asynchronous loader returns at once and finishes on its own thread; the caller's
    // thread is free meanwhile (it counts how often it ran).
    void loaderRunsOffTheCallersThread() {
        const fs::path file = path("async.png");
        std::string error;
        QVERIFY(writeImage(file, pattern(1024, 1024), PixelFormat::UInt8, &error));
        TextureLoader loader(m_cm, options("c7"), /*async=*/true);
        const auto job = loader.request(file, srgb(), TextureUsage::Color);
        int spins = 0;
        while (!job->ready()) {
            ++spins;
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        qInfo("the caller ran %d times while the worker loaded 1024x1024", spins);
        QVERIFY(spins > 0);
        QVERIFY(job->result().texture);
        QCOMPARE(loader.decodeCount(), std::uint64_t(1));
        // The cache entry follows the published result (written after, on the worker).
        QTRY_VERIFY(fs::exists(job->result().cacheEntry));
        const auto again = loader.request(file, srgb(), TextureUsage::Color);
        loader.wait(*again);
        QCOMPARE(loader.cacheHits(), std::uint64_t(1));
    }

    // MipLoadOptions::leaveFinestInCache: a map whose level 0 is over 4 MiB comes back without
    // level 0's bytes, which the entry gives band by band (whole 64-row tiles), equal to a full
    // load's; on a first build (the entry written first) and on a hit alike. A smaller map, or no
    // cache, keeps level 0 in memory; a band outside the level or off the tiles is refused.
    void largeLevelZeroStaysInTheEntry() {
        const fs::path file = path("stream.png");
        std::string error;
        QVERIFY(writeImage(file, pattern(1280, 1000), PixelFormat::UInt8, &error));
        const MipLoadResult full =
            loadMipTexture(file, srgb(), TextureUsage::Color, m_cm, options("c9"));
        QVERIFY(full.texture && full.texture->finestInCache.empty());
        const std::vector<std::uint8_t>& expected = full.texture->levels[0].bytes;
        QCOMPARE(expected.size(), size_t(1280 * 1000 * 4));
        for (const char* cache : {"c9", "c10"}) { // c9: a hit; c10: a first build
            MipLoadOptions o = options(cache);
            o.leaveFinestInCache = true;
            o.writeCache = false; // the entry is written all the same: level 0 lives there
            const MipLoadResult r = loadMipTexture(file, srgb(), TextureUsage::Color, m_cm, o);
            QVERIFY(r.texture);
            QCOMPARE(r.fromCache, std::string(cache) == "c9");
            const MipTexture& t = *r.texture;
            QCOMPARE(t.finestInCache, r.cacheEntry);
            QVERIFY(t.levels[0].bytes.empty());
            QCOMPARE(t.width(), 1280);
            QCOMPARE(t.byteSize(), full.texture->byteSize());
            QVERIFY(t.levels[1].bytes == full.texture->levels[1].bytes);
            QVERIFY(t.linearLevel(256).width == 160); // the level of 160x125, not level 0
            std::vector<std::uint8_t> rows;
            for (int y0 = 0; y0 < 1000; y0 += 192) { // three tiles a band; the last one short
                const int n = std::min(192, 1000 - y0);
                std::vector<std::uint8_t> band(size_t(1280) * size_t(n) * 4);
                QVERIFY2(readMipCacheRows(t.finestInCache, t, 0, y0, n, band.data(), &error),
                         error.c_str());
                rows.insert(rows.end(), band.begin(), band.end());
            }
            QVERIFY(rows == expected);
            std::vector<std::uint8_t> band(size_t(1280) * 64 * 4);
            QVERIFY(!readMipCacheRows(t.finestInCache, t, 0, 32, 64, band.data(), &error));
            QVERIFY(!readMipCacheRows(t.finestInCache, t, 0, 960, 64, band.data(), &error));
            QVERIFY2(error.find("level 0") != std::string::npos, error.c_str());
        }
        // 1024² RGBA8 is 4 MiB: kept in memory, from a hit too.
        const fs::path small = path("small.png");
        QVERIFY(writeImage(small, pattern(1024, 1024), PixelFormat::UInt8, &error));
        MipLoadOptions o = options("c9");
        o.leaveFinestInCache = true;
        for (int pass = 0; pass < 2; ++pass) {
            const MipLoadResult r = loadMipTexture(small, srgb(), TextureUsage::Color, m_cm, o);
            QCOMPARE(r.fromCache, pass == 1);
            QVERIFY(r.texture->finestInCache.empty());
            QCOMPARE(r.texture->levels[0].bytes.size(), size_t(1024 * 1024 * 4));
        }
        o.useCache = false;
        const MipLoadResult uncached = loadMipTexture(file, srgb(), TextureUsage::Color, m_cm, o);
        QVERIFY(uncached.texture->finestInCache.empty());
        QVERIFY(uncached.texture->levels[0].bytes == expected);
    }

    // Peak memory of a first load of a 2048² RGBA8 map (no float copy): under twice its GPU
    // size with mips (the levels themselves are one such size).
    void peakMemoryStaysUnderTwiceTheGpuSize() {
#if defined(__SANITIZE_ADDRESS__) || VELVET_HAS_ASAN
        // ASan's redzones and freed-memory quarantine add to the resident peak (2.24x measured
        // under make test-asan-core): the figure is the allocator's, not the loader's.
        QSKIP("peak memory is not Velvet's under AddressSanitizer");
#endif
        const fs::path file = path("big.png");
        std::string error;
        QVERIFY(writeImage(file, pattern(2048, 2048), PixelFormat::UInt8, &error));
        double gpu = 0;
        for (int s = 2048; s >= 1; s /= 2)
            gpu += double(s) * s * 4 / (1 << 20);
        const double before = statusMb("VmRSS:");
        std::ofstream("/proc/self/clear_refs") << "5"; // resets VmHWM (proc(5))
        MipLoadResult r = loadMipTexture(file, srgb(), TextureUsage::Color, m_cm, options("c8"));
        const double peak = statusMb("VmHWM:") - before;
        QVERIFY(r.texture);
        qInfo("2048² first load: peak +%.1f MB, GPU size %.1f MB, ratio %.2f", peak, gpu,
              peak / gpu);
        QVERIFY2(peak <= 2.0 * gpu, qPrintable(QString::number(peak / gpu)));
    }
};

QTEST_GUILESS_MAIN(TestCoreMipTexture)
#include "test_core_mip_texture.moc"
