// core/image_ops: resizing and mip chains through ImageBufAlgo, and fitting a texture to the GPU
// limit with a warning.
#include "core/image.h"
#include "core/image_ops.h"

#include <QtTest>
#include <cmath>

using namespace velvet;

namespace {

Image constant(int w, int h, int c, float v) {
    Image img(w, h, c);
    std::fill(img.pixels.begin(), img.pixels.end(), v);
    return img;
}

double mean(const Image& img, int channel) {
    double sum = 0.0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            sum += img.at(x, y)[channel];
    return sum / (double(img.width) * img.height);
}

} // namespace

class TestCoreImageOps : public QObject {
    Q_OBJECT

private slots:
    // A constant stays that constant whatever the filter (the filters are normalized) and the
    // size is the one asked for.
    void resizeKeepsConstants_data() {
        QTest::addColumn<int>("filter");
        QTest::newRow("box") << int(ResizeFilter::Box);
        QTest::newRow("triangle") << int(ResizeFilter::Triangle);
        QTest::newRow("mitchell") << int(ResizeFilter::Mitchell);
        QTest::newRow("blackman-harris") << int(ResizeFilter::BlackmanHarris);
        QTest::newRow("lanczos3") << int(ResizeFilter::Lanczos3);
    }
    void resizeKeepsConstants() {
        QFETCH(int, filter);
        std::string error;
        for (auto [w, h] : {std::pair{13, 7}, std::pair{64, 40}}) {
            const Image out = resize(constant(32, 20, 3, 0.3f), w, h, &error, ResizeFilter(filter));
            QVERIFY2(!out.empty(), error.c_str());
            QCOMPARE(out.width, w);
            QCOMPARE(out.height, h);
            QCOMPARE(out.channels, 3);
            for (float v : out.pixels)
                QVERIFY(std::abs(v - 0.3f) < 1e-5f);
        }
    }

    // A hard edge filtered with a sharp (negative-lobed) filter does not ring outside the data's
    // own range: a roughness map stays in [0, 1].
    void resizeDoesNotRingOutsideTheSourceRange() {
        Image edge(64, 8, 1);
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 64; ++x)
                edge.at(x, y)[0] = x < 32 ? 0.0f : 1.0f;
        std::string error;
        const Image out = resize(edge, 24, 8, &error, ResizeFilter::Lanczos3);
        QVERIFY2(!out.empty(), error.c_str());
        for (float v : out.pixels)
            QVERIFY2(v >= 0.0f && v <= 1.0f, qPrintable(QString::number(v)));
        QCOMPARE(out.at(0, 0)[0], 0.0f);
        QCOMPARE(out.at(23, 0)[0], 1.0f);
    }

    void resizeRefusesBadSizes() {
        std::string error;
        QVERIFY(resize(constant(4, 4, 1, 1.0f), 0, 4, &error).empty());
        QVERIFY2(error.find("0x4") != std::string::npos, error.c_str());
        QVERIFY(resize(Image(), 4, 4, &error).empty());
    }

    // Supersampling's box filter: each output pixel the exact mean of its block, every channel.
    void boxDownsampleAveragesEachBlock() {
        Image image(4, 2, 2);
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 4; ++x) {
                image.at(x, y)[0] = float(x + 4 * y); // 0 1 2 3 / 4 5 6 7
                image.at(x, y)[1] = x < 2 ? 1.0f : 0.0f;
            }
        const Image half = boxDownsample(image, 2);
        QCOMPARE(half.width, 2);
        QCOMPARE(half.height, 1);
        QCOMPARE(half.channels, 2);
        QCOMPARE(half.at(0, 0)[0], (0.0f + 1.0f + 4.0f + 5.0f) / 4.0f);
        QCOMPARE(half.at(1, 0)[0], (2.0f + 3.0f + 6.0f + 7.0f) / 4.0f);
        QCOMPARE(half.at(0, 0)[1], 1.0f);
        QCOMPARE(half.at(1, 0)[1], 0.0f);
        QCOMPARE(boxDownsample(image, 1).pixels, image.pixels);
        QVERIFY(boxDownsample(image, 3).empty()); // 4 is not a multiple of 3
        QVERIFY(boxDownsample(image, 0).empty());
    }

    // The running mean of frames: each pixel the average of the images added; an image of
    // another size starts it again; clear() empties it.
    void imageMeanAveragesAndRestartsOnAnotherSize() {
        ImageMean mean;
        QCOMPARE(mean.count(), 0);
        QVERIFY(mean.mean().empty());
        Image a(2, 1, 1), b(2, 1, 1), c(3, 1, 1);
        a.pixels = {1.0f, 2.0f};
        b.pixels = {3.0f, 6.0f};
        c.pixels = {5.0f, 5.0f, 5.0f};
        mean.add(a);
        QCOMPARE(mean.mean().pixels, a.pixels);
        mean.add(b);
        QCOMPARE(mean.count(), 2);
        QCOMPARE(mean.mean().pixels, (std::vector<float>{2.0f, 4.0f}));
        mean.add(c);
        QCOMPARE(mean.count(), 1);
        QCOMPARE(mean.mean().pixels, c.pixels);
        // takeMean() gives the same mean and leaves it empty.
        mean.add(c);
        QCOMPARE(mean.takeMean().pixels, c.pixels);
        QCOMPARE(mean.count(), 0);
        QVERIFY(mean.mean().empty());
        mean.add(a);
        mean.clear();
        QCOMPARE(mean.count(), 0);
        QVERIFY(mean.mean().empty());
    }

    // Full chain: floor(log2(max side)) + 1 levels, each side halved rounding down (OpenGL 4.5
    // section 8.14.3), down to 1x1; a checkerboard averages to its mean.
    void mipChainHasEveryLevel() {
        Image checker(37, 16, 2);
        for (int y = 0; y < checker.height; ++y)
            for (int x = 0; x < checker.width; ++x) {
                checker.at(x, y)[0] = float((x + y) % 2);
                checker.at(x, y)[1] = 0.75f;
            }
        QCOMPARE(mipLevelCount(37, 16), 6);
        QCOMPARE(mipLevelCount(1, 1), 1);
        QCOMPARE(mipLevelCount(512, 512), 10);
        std::string error;
        const std::vector<Image> chain = mipChain(checker, &error);
        QCOMPARE(int(chain.size()), 6);
        const int sizes[6][2] = {{37, 16}, {18, 8}, {9, 4}, {4, 2}, {2, 1}, {1, 1}};
        for (size_t i = 0; i < chain.size(); ++i) {
            QCOMPARE(chain[i].width, sizes[i][0]);
            QCOMPARE(chain[i].height, sizes[i][1]);
            QCOMPARE(chain[i].channels, 2);
        }
        QCOMPARE(chain[0].pixels, checker.pixels);
        QVERIFY(std::abs(mean(chain[2], 0) - 0.5) < 0.05);
        QVERIFY(std::abs(chain.back().at(0, 0)[0] - 0.5f) < 0.05f);
        QVERIFY(std::abs(chain.back().at(0, 0)[1] - 0.75f) < 1e-5f);
    }

    // A 512x512 texture against a 256 limit is halved, with a warning naming the file and both
    // sizes; a non-square one keeps its aspect ratio; one that fits is left alone, silently.
    void fitToLimitDownscalesWithAWarning() {
        Image big = constant(512, 512, 4, 0.5f);
        std::string warning;
        QVERIFY(fitToLimit(big, 256, &warning, "albedo.png"));
        QCOMPARE(big.width, 256);
        QCOMPARE(big.height, 256);
        qInfo("%s", warning.c_str());
        QVERIFY2(warning.find("albedo.png") != std::string::npos &&
                     warning.find("512x512") != std::string::npos &&
                     warning.find("256x256") != std::string::npos,
                 warning.c_str());
        QVERIFY(std::abs(big.at(100, 100)[2] - 0.5f) < 1e-5f);

        Image wide = constant(1000, 250, 1, 1.0f);
        QVERIFY(fitToLimit(wide, 256, &warning, "wide.exr"));
        QCOMPARE(wide.width, 256);
        QCOMPARE(wide.height, 64);

        Image small = constant(200, 100, 3, 1.0f);
        warning.clear();
        QVERIFY(!fitToLimit(small, 256, &warning, "small.png"));
        QCOMPARE(small.width, 200);
        QVERIFY(warning.empty());
    }
};

QTEST_GUILESS_MAIN(TestCoreImageOps)
#include "test_core_image_ops.moc"
