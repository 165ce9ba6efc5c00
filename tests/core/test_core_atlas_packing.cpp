// core/atlas_packing: regions inside the atlas and apart (padding included), each region's
// texels equal to its source, the padding replicating the source's edge, refusals when the
// images do not fit.
#include "core/atlas_packing.h"

#include <QtTest>
#include <random>

using namespace velvet;

namespace {

Image pattern(int w, int h, int c, int seed) {
    Image img(w, h, c);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < c; ++k)
                img.at(x, y)[k] = float(seed * 1000 + y * w + x) + 0.1f * float(k);
    return img;
}

bool overlap(const AtlasRegion& a, const AtlasRegion& b, int pad) {
    return a.x - pad < b.x + b.width + pad && b.x - pad < a.x + a.width + pad &&
           a.y - pad < b.y + b.height + pad && b.y - pad < a.y + a.height + pad;
}

bool isPowerOfTwo(int v) {
    return v > 0 && (v & (v - 1)) == 0;
}

/// Regions inside the atlas with their padding, and no two padded regions overlapping.
void checkLayout(const AtlasLayout& layout, size_t count, int pad, int maxW, int maxH) {
    QCOMPARE(layout.regions.size(), count);
    QVERIFY(layout.width <= maxW && layout.height <= maxH);
    for (size_t i = 0; i < count; ++i) {
        const AtlasRegion& r = layout.regions[i];
        QVERIFY2(r.x - pad >= 0 && r.y - pad >= 0 && r.x + r.width + pad <= layout.width &&
                     r.y + r.height + pad <= layout.height,
                 qPrintable(QString("region %1 outside").arg(i)));
        for (size_t j = i + 1; j < count; ++j)
            QVERIFY2(!overlap(r, layout.regions[j], pad),
                     qPrintable(QString("regions %1 and %2 overlap").arg(i).arg(j)));
    }
}

} // namespace

class TestCoreAtlasPacking : public QObject {
    Q_OBJECT

private slots:
    void packsAndReplicatesEdges_data() {
        QTest::addColumn<int>("padding");
        QTest::addColumn<bool>("powerOfTwo");
        QTest::newRow("pad 4, power of two") << 4 << true;
        QTest::newRow("pad 2, tight") << 2 << false;
        QTest::newRow("pad 0, power of two") << 0 << true;
    }
    void packsAndReplicatesEdges() {
        QFETCH(int, padding);
        QFETCH(bool, powerOfTwo);
        const std::vector<Image> images = {pattern(64, 32, 3, 1), pattern(17, 40, 3, 2),
                                           pattern(1, 1, 3, 3),   pattern(30, 30, 3, 4),
                                           pattern(50, 9, 3, 5),  pattern(8, 8, 3, 6)};
        AtlasOptions options;
        options.padding = padding;
        options.powerOfTwo = powerOfTwo;
        options.maxWidth = options.maxHeight = 256;
        Image atlas;
        AtlasLayout layout;
        std::string error;
        QVERIFY2(packAtlas(images, options, atlas, layout, &error), error.c_str());
        QCOMPARE(atlas.width, layout.width);
        QCOMPARE(atlas.height, layout.height);
        QCOMPARE(atlas.channels, 3);
        if (powerOfTwo)
            QVERIFY(isPowerOfTwo(atlas.width) && isPowerOfTwo(atlas.height));
        checkLayout(layout, images.size(), padding, 256, 256);

        for (size_t i = 0; i < images.size(); ++i) {
            const Image& src = images[i];
            const AtlasRegion& r = layout.regions[i];
            QCOMPARE(r.width, src.width);
            QCOMPARE(r.height, src.height);
            // The region's texels are the source's.
            QCOMPARE(extractRegion(atlas, r).pixels, src.pixels);
            // Every padding texel repeats the nearest edge texel (corners the corner texel).
            for (int y = -padding; y < r.height + padding; ++y)
                for (int x = -padding; x < r.width + padding; ++x) {
                    if (x >= 0 && y >= 0 && x < r.width && y < r.height)
                        continue;
                    const float* got = atlas.at(r.x + x, r.y + y);
                    const float* want =
                        src.at(std::clamp(x, 0, src.width - 1), std::clamp(y, 0, src.height - 1));
                    for (int k = 0; k < 3; ++k)
                        QCOMPARE(got[k], want[k]);
                }
        }
    }

    // Many random sizes: the skyline packer never overlaps nor leaves the atlas, and a
    // power-of-two atlas is no larger than needed by more than a factor of 4 in area.
    void manyRandomRects() {
        std::mt19937 rng(7);
        std::uniform_int_distribution<int> side(1, 60);
        std::vector<AtlasItemSize> sizes(150);
        std::uint64_t area = 0;
        for (auto& s : sizes) {
            s = {side(rng), side(rng)};
            area += std::uint64_t(s.width + 2) * (s.height + 2);
        }
        for (bool pot : {true, false}) {
            AtlasOptions options;
            options.padding = 1;
            options.powerOfTwo = pot;
            options.maxWidth = options.maxHeight = 2048;
            AtlasLayout layout;
            std::string error;
            QVERIFY2(planAtlas(sizes, options, layout, &error), error.c_str());
            checkLayout(layout, sizes.size(), 1, 2048, 2048);
            const double used = double(area) / (double(layout.width) * layout.height);
            qInfo("%s: %dx%d, %.0f %% used", pot ? "power of two" : "tight", layout.width,
                  layout.height, used * 100.0);
            QVERIFY(used > (pot ? 0.25 : 0.6));
        }
    }

    // Mixed channel counts: grey widens to RRR, a missing alpha becomes 1.
    void mixedChannels() {
        Image grey(2, 2, 1);
        grey.pixels = {0.1f, 0.2f, 0.3f, 0.4f};
        Image rgba(2, 2, 4);
        std::fill(rgba.pixels.begin(), rgba.pixels.end(), 0.5f);
        Image atlas;
        AtlasLayout layout;
        std::string error;
        const std::vector<Image> images = {grey, rgba};
        QVERIFY2(packAtlas(images, {}, atlas, layout, &error), error.c_str());
        QCOMPARE(atlas.channels, 4);
        const float* p = atlas.at(layout.regions[0].x + 1, layout.regions[0].y + 1);
        QCOMPARE(p[0], 0.4f);
        QCOMPARE(p[1], 0.4f);
        QCOMPARE(p[2], 0.4f);
        QCOMPARE(p[3], 1.0f);
    }

    void refusesWhatDoesNotFit() {
        AtlasOptions options;
        options.padding = 4;
        options.maxWidth = 256;
        options.maxHeight = 128;
        std::string error;
        AtlasLayout layout;
        // 60x60 images need 68x68 with padding: one row of three fits in 256x128, four do not.
        const std::vector<AtlasItemSize> four(4, AtlasItemSize{60, 60});
        QVERIFY(!planAtlas(four, options, layout, &error));
        qInfo("%s", error.c_str());
        QVERIFY2(error.find("4 images") != std::string::npos &&
                     error.find("do not fit in 256x128") != std::string::npos,
                 error.c_str());
        QVERIFY2(planAtlas(std::span(four).first(3), options, layout, &error), error.c_str());
        QCOMPARE(layout.width, 256);
        QCOMPARE(layout.height, 128);
        checkLayout(layout, 3, 4, 256, 128);

        const std::vector<AtlasItemSize> wide = {{10, 10}, {253, 4}};
        QVERIFY(!planAtlas(wide, options, layout, &error));
        qInfo("%s", error.c_str());
        QVERIFY2(error.find("image 2 (253x4") != std::string::npos, error.c_str());

        QVERIFY(!planAtlas({}, options, layout, &error));
        const std::vector<Image> empty = {Image()};
        Image atlas;
        QVERIFY(!packAtlas(empty, options, atlas, layout, &error));
    }
};

QTEST_GUILESS_MAIN(TestCoreAtlasPacking)
#include "test_core_atlas_packing.moc"
