// core/content_hash, half_float, ibl_cache, cache_dir (issue 16, "a preview image in one second"):
// the hashes and half conversions Velvet takes from libxxhash and Imath (so that they do not load
// OpenImageIO) equal OpenImageIO's (linked here only to compare), the prefiltered environment's
// cache file round-trips and refuses truncated, damaged and foreign entries with the reason, and
// its key follows the HDRI's content.
#include "core/cache_dir.h"
#include "core/content_hash.h"
#include "core/half_float.h"
#include "core/ibl_cache.h"

#include <OpenImageIO/hash.h>
#include <OpenImageIO/imageio.h>
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>

using namespace velvet;

namespace {

void writeBytes(const std::filesystem::path& file, const std::string& bytes) {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

std::string readBytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

/// A small entry with every value distinct, so a misplaced block shows.
IblCacheEntry sampleEntry() {
    IblCacheEntry e;
    e.width = 8, e.height = 4, e.faceSize = 4, e.levels = 3;
    for (int i = 0; i < 8 * 4 * 3; ++i)
        e.equirect.push_back(std::uint16_t(i * 7 + 1));
    for (int i = 0; i < 9; ++i)
        e.sh[size_t(i)] = glm::vec3(float(i), float(i) * 0.5f, -float(i));
    for (int l = 0; l < e.levels; ++l) {
        const int size = std::max(e.faceSize >> l, 1);
        std::vector<std::uint16_t> level(size_t(size * size * 6 * 4));
        for (size_t i = 0; i < level.size(); ++i)
            level[i] = std::uint16_t(1000 * l + int(i));
        e.specular.push_back(level);
    }
    return e;
}

} // namespace

class TestCoreIblCache : public QObject {
    Q_OBJECT
private slots:
    // xxHash64's published values, then OpenImageIO's copy of the same function on every length
    // from 0 to 100 bytes (all tails) and a long buffer, with seeds.
    void xxhash64MatchesTheReference() {
        QCOMPARE(xxhash64("", 0, 0), std::uint64_t(0xEF46DB3751D8E999ULL));
        std::mt19937 rng(7);
        std::string data(1 << 20, '\0');
        for (char& c : data)
            c = char(rng());
        for (size_t n = 0; n <= 100; ++n)
            for (std::uint64_t seed : {std::uint64_t(0), std::uint64_t(1771)})
                QCOMPARE(xxhash64(data.data(), n, seed),
                         std::uint64_t(OIIO::xxhash::XXH64(data.data(), n, seed)));
        QCOMPARE(xxhash64(data.data(), data.size(), 0x76656c766574ULL),
                 std::uint64_t(OIIO::xxhash::XXH64(data.data(), data.size(), 0x76656c766574ULL)));
    }

    // The key of a file's cache entry follows its bytes: a copy has the same, one byte changed
    // gives another (and so another entry file).
    void contentHashFollowsTheBytes() {
        QTemporaryDir dir;
        const std::filesystem::path a = dir.filePath("a.exr").toStdString(),
                                    b = dir.filePath("b.exr").toStdString();
        std::string bytes(300000, 'x');
        bytes[1234] = 'y';
        writeBytes(a, bytes);
        writeBytes(b, bytes);
        std::string error;
        const std::string ha = fileContentHash(a, &error), hb = fileContentHash(b, &error);
        QVERIFY2(!ha.empty(), error.c_str());
        QCOMPARE(ha, hb);
        bytes[200000] = 'z';
        writeBytes(b, bytes);
        const std::string changed = fileContentHash(b, &error);
        QVERIFY(changed != ha);
        QVERIFY(iblCacheFile("c", changed + "\nsig") != iblCacheFile("c", ha + "\nsig"));
        QVERIFY(iblCacheFile("c", ha + "\nsig") != iblCacheFile("c", ha + "\nother bake"));
        QVERIFY(fileContentHash(dir.filePath("missing").toStdString(), &error).empty());
    }

    // Round to nearest even, as OpenImageIO's (Imath's) conversion: every half is exact, and
    // floats between halves (ties included), subnormals, overflow, infinities and NaN convert
    // the same.
    void halfConversionsMatchOpenImageIo() {
        std::vector<float> values;
        for (std::uint32_t h = 0; h < 65536; ++h) { // every half, and the midpoints above each
            std::uint16_t bits = std::uint16_t(h);
            float f = 0.0f;
            OIIO::convert_pixel_values(OIIO::TypeDesc::HALF, &bits, OIIO::TypeDesc::FLOAT, &f, 1);
            const float mine = halfToFloat(bits);
            if (std::isnan(f))
                QVERIFY(std::isnan(mine));
            else
                QCOMPARE(std::memcmp(&mine, &f, 4), 0);
            values.push_back(f);
            if (std::isfinite(f)) {
                std::uint32_t u;
                std::memcpy(&u, &f, 4);
                const std::uint32_t mid = u + (1u << 12); // half an ulp of a normal half
                float m;
                std::memcpy(&m, &mid, 4);
                values.push_back(m);
            }
        }
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> exponent(-30.0f, 17.0f);
        for (int i = 0; i < 200000; ++i)
            values.push_back((i & 1 ? -1.0f : 1.0f) * std::exp2(exponent(rng)));
        values.push_back(65519.0f);
        values.push_back(65520.0f);
        values.push_back(1e9f);
        values.push_back(std::numeric_limits<float>::infinity());
        values.push_back(std::numeric_limits<float>::denorm_min());
        std::vector<std::uint16_t> theirs(values.size());
        OIIO::convert_pixel_values(OIIO::TypeDesc::FLOAT, values.data(), OIIO::TypeDesc::HALF,
                                   theirs.data(), int(values.size()));
        int different = 0;
        for (size_t i = 0; i < values.size(); ++i)
            if (!std::isnan(values[i]) && floatToHalf(values[i]) != theirs[i] && different++ < 5)
                qWarning("%.9g: %04x, OpenImageIO %04x", double(values[i]),
                         unsigned(floatToHalf(values[i])), unsigned(theirs[i]));
        QCOMPARE(different, 0);
        QVERIFY(std::isnan(halfToFloat(floatToHalf(std::nanf("")))));
        // The bulk forms (textures, read-backs) convert as the single ones do.
        std::vector<std::uint16_t> bulk(values.size());
        floatsToHalves(values.data(), values.size(), bulk.data());
        std::vector<float> back(values.size());
        halvesToFloats(bulk.data(), bulk.size(), back.data());
        for (size_t i = 0; i < values.size(); ++i) {
            QCOMPARE(bulk[i], floatToHalf(values[i]));
            const float single = halfToFloat(bulk[i]);
            QVERIFY(std::memcmp(&back[i], &single, 4) == 0);
        }
    }

    void entryRoundTrips() {
        QTemporaryDir dir;
        const auto file = iblCacheFile(dir.path().toStdString(), "content\nbake");
        const IblCacheEntry e = sampleEntry();
        std::string error;
        QVERIFY2(writeIblCache(file, "content\nbake", e, &error), error.c_str());
        IblCacheEntry back;
        std::string why;
        QVERIFY2(readIblCache(file, "content\nbake", back, &why), why.c_str());
        QCOMPARE(back.width, e.width);
        QCOMPARE(back.height, e.height);
        QCOMPARE(back.faceSize, e.faceSize);
        QCOMPARE(back.levels, e.levels);
        QVERIFY(back.equirect == e.equirect);
        QVERIFY(back.specular == e.specular);
        for (size_t i = 0; i < 9; ++i)
            QCOMPARE(back.sh[i], e.sh[i]);
        // A missing entry is a plain miss: no reason.
        QVERIFY(!readIblCache(file.string() + ".none", "content\nbake", back, &why));
        QVERIFY(why.empty());
    }

    // Truncated, damaged and foreign entries are refused with what is wrong, never used.
    void badEntriesAreRefusedWithTheReason() {
        QTemporaryDir dir;
        const std::string key = "content\nbake";
        const auto file = iblCacheFile(dir.path().toStdString(), key);
        std::string error;
        QVERIFY(writeIblCache(file, key, sampleEntry(), &error));
        const std::string good = readBytes(file);
        IblCacheEntry out;
        std::string why;

        writeBytes(file, good.substr(0, good.size() / 2));
        QVERIFY(!readIblCache(file, key, out, &why));
        QVERIFY2(why.find("truncated") != std::string::npos, why.c_str());

        std::string flipped = good;
        flipped[good.size() - 100] ^= 0x10; // one bit inside the specular levels
        writeBytes(file, flipped);
        QVERIFY(!readIblCache(file, key, out, &why));
        QVERIFY2(why.find("checksum") != std::string::npos, why.c_str());

        writeBytes(file, good);
        QVERIFY(!readIblCache(file, "other content\nbake", out, &why));
        QVERIFY2(why.find("another") != std::string::npos, why.c_str());

        writeBytes(file, "velvet-mip-cache 1\nnot this\n");
        QVERIFY(!readIblCache(file, key, out, &why));
        QVERIFY2(why.find("not a Velvet environment cache entry") != std::string::npos,
                 why.c_str());

        writeBytes(file, good);
        QVERIFY2(readIblCache(file, key, out, &why), why.c_str());
    }

    void cacheFolderFromTheEnvironment() {
        qputenv("VELVET_CACHE_DIR", "/tmp/velvet-cache-test");
        qunsetenv("VELVET_NO_CACHE");
        QCOMPARE(velvetCacheDir(), std::filesystem::path("/tmp/velvet-cache-test"));
        qunsetenv("VELVET_CACHE_DIR");
        qputenv("XDG_CACHE_HOME", "/tmp/xdg");
        QCOMPARE(velvetCacheDir(), std::filesystem::path("/tmp/xdg/velvet"));
        qputenv("VELVET_NO_CACHE", "1");
        QVERIFY(velvetCacheDir().empty());
        qputenv("VELVET_NO_CACHE", "0");
        QCOMPARE(velvetCacheDir(), std::filesystem::path("/tmp/xdg/velvet"));
        qunsetenv("VELVET_NO_CACHE");
    }
};

QTEST_GUILESS_MAIN(TestCoreIblCache)
#include "test_core_ibl_cache.moc"
