// core/color_difference and core/image_compare (issue 15, velvet compare): CIEDE2000 against
// all 34 published test pairs of Sharma, Wu and Dalal (2005), Table 1, to 1e-4 and in both
// orders; sRGB -> L*a*b* at known points; the statistics and the heat map's known colours.
#include "core/color_difference.h"
#include "core/image_compare.h"

#include <QtTest>
#include <cmath>

using namespace velvet;

namespace {

/// Sharma, Wu and Dalal, "The CIEDE2000 Color-Difference Formula: Implementation Notes,
/// Supplementary Test Data, and Mathematical Observations", Color Res. Appl. 30(1), 2005,
/// Table 1: L1, a1, b1, L2, a2, b2, ΔE00 (published to 4 decimals).
constexpr double kPairs[34][7] = {
    {50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425},
    {50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615},
    {50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412},
    {50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669},
    {50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461},
    {50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065},
    {50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492},
    {50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977},
    {50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030},
    {50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000},
    {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644},
    {63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630},
    {61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731},
    {35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645},
    {22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373},
    {36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146},
    {90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441},
    {90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381},
    {6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377},
    {2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082},
};

Image flatImage(int w, int h, glm::vec3 c) {
    Image img(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            std::copy(&c.x, &c.x + 3, img.at(x, y));
    return img;
}

} // namespace

class TestColorDifference : public QObject {
    Q_OBJECT
private slots:
    void sharmaWuDalalPairs() {
        double worst = 0.0;
        for (int i = 0; i < 34; ++i) {
            const double* p = kPairs[i];
            const Lab x{p[0], p[1], p[2]}, y{p[3], p[4], p[5]};
            const double forward = ciede2000(x, y), backward = ciede2000(y, x);
            worst = std::max({worst, std::abs(forward - p[6]), std::abs(backward - p[6])});
            QVERIFY2(std::abs(forward - p[6]) <= 1e-4,
                     qPrintable(QString("pair %1: %2, published %3")
                                    .arg(i + 1)
                                    .arg(forward, 0, 'f', 6)
                                    .arg(p[6], 0, 'f', 4)));
            QVERIFY2(std::abs(backward - p[6]) <= 1e-4,
                     qPrintable(QString("pair %1 reversed: %2").arg(i + 1).arg(backward)));
        }
        qInfo("worst |ΔE00 - published| over the 34 pairs, both orders: %.2e", worst);
        QCOMPARE(ciede2000({40, 10, -20}, {40, 10, -20}), 0.0);
    }

    void srgbToLabKnownPoints() {
        const Lab white = srgbToLab({1, 1, 1});
        QVERIFY(std::abs(white.L - 100.0) < 1e-3 && std::abs(white.a) < 1e-3 &&
                std::abs(white.b) < 1e-3);
        const Lab black = srgbToLab({0, 0, 0});
        QVERIFY(std::abs(black.L) < 1e-9);
        // sRGB mid grey 0.5 encoded = linear 0.21404: L* = 116 * 0.21404^(1/3) - 16 = 53.389.
        QVERIFY(std::abs(srgbToLab({0.5f, 0.5f, 0.5f}).L - 53.389) < 2e-3);
        // sRGB red (1, 0, 0): L* 53.24, a* 80.09, b* 67.20 (the sRGB matrix, D65).
        const Lab red = srgbToLab({1, 0, 0});
        QVERIFY2(std::abs(red.L - 53.24) < 0.02 && std::abs(red.a - 80.09) < 0.05 &&
                     std::abs(red.b - 67.20) < 0.05,
                 qPrintable(QString("%1 %2 %3").arg(red.L).arg(red.a).arg(red.b)));
    }

    void statisticsAndHeatMap() {
        // 20 pixels: 19 equal, one differs: the mean is 1/20 of that ΔE, p95 (the 19th smallest)
        // is 0, the maximum is the one difference.
        Image a = flatImage(5, 4, {0.5f, 0.5f, 0.5f}), b = a;
        b.at(2, 1)[0] = 0.6f;
        Image deltaE;
        DeltaEStats stats;
        std::string error;
        QVERIFY(compareImages(a, b, deltaE, stats, &error));
        const double one = ciede2000(srgbToLab({0.5f, 0.5f, 0.5f}), srgbToLab({0.6f, 0.5f, 0.5f}));
        QVERIFY(one > 1.0);
        QCOMPARE(stats.pixels, size_t(20));
        QVERIFY(std::abs(stats.max - one) < 1e-4);
        QVERIFY(std::abs(stats.mean - one / 20.0) < 1e-5);
        QCOMPARE(stats.p95, 0.0);
        // Two differing pixels of 20: the 19th smallest is one of them.
        b.at(0, 0)[2] = 0.7f;
        QVERIFY(compareImages(a, b, deltaE, stats, &error));
        QVERIFY(stats.p95 > 1.0);

        QVERIFY(!compareImages(a, flatImage(4, 4, {0, 0, 0}), deltaE, stats, &error));
        QVERIFY(error.find("5x4") != std::string::npos && error.find("4x4") != std::string::npos);

        // The heat map: 0 is black, the scale's top (and beyond) red; the legend below the map.
        Image map(3, 1, 1);
        map.pixels = {0.0f, 10.0f, 50.0f};
        const Image heat = heatMapWithLegend(map, 10.0);
        QCOMPARE(heat.height, 1 + heatMapLegendHeight());
        QVERIFY(heat.width >= 3);
        QCOMPARE(glm::vec3(heat.at(0, 0)[0], heat.at(0, 0)[1], heat.at(0, 0)[2]), glm::vec3(0.0f));
        QCOMPARE(heat.at(1, 0)[0], heatMapColor(10.0, 10.0).r);
        QCOMPARE(heat.at(2, 0)[1], heatMapColor(10.0, 10.0).g);
        QVERIFY(heatMapColor(10.0, 10.0).r > 0.9f && heatMapColor(10.0, 10.0).g < 0.2f);
        // The legend holds the ramp and white text: some pure white pixels below the map.
        int white = 0;
        for (int y = 1; y < heat.height; ++y)
            for (int x = 0; x < heat.width; ++x)
                white += heat.at(x, y)[0] == 1.0f && heat.at(x, y)[1] == 1.0f;
        QVERIFY(white > 20);
    }

    void displayTransformOfLinear() {
        // PBR Neutral leaves low values alone (below its 0.76 knee, minus the toe offset), so a
        // linear 0.18 grey comes out near sRGB(0.18 - toe); 0 stays 0; large values stay <= 1.
        Image linear = flatImage(2, 1, {0.0f, 0.0f, 0.0f});
        linear.at(1, 0)[0] = linear.at(1, 0)[1] = linear.at(1, 0)[2] = 1000.0f;
        const Image d = defaultDisplayTransform(linear);
        QCOMPARE(d.at(0, 0)[0], 0.0f);
        QVERIFY(d.at(1, 0)[0] <= 1.0f && d.at(1, 0)[0] > 0.99f);
    }

    // The statistics over the pixels a mesh covers fully (the Reference view, velvet compare
    // --table): partly covered and uncovered pixels do not count.
    void statisticsOverCoveredPixels() {
        velvet::Image deltaE(2, 2, 1), coverage(2, 2, 1);
        deltaE.pixels = {1.0f, 20.0f, 3.0f, 40.0f};
        coverage.pixels = {1.0f, 0.0f, 1.0f, 0.5f};
        const velvet::DeltaEStats s = velvet::deltaEStats(deltaE, coverage);
        QCOMPARE(s.pixels, size_t(2));
        QCOMPARE(s.mean, 2.0);
        QCOMPARE(s.p95, 3.0); // nearest rank: the ceil(0.95 x 2) = 2nd smallest
        QCOMPARE(s.max, 3.0);
        QCOMPARE(velvet::deltaEStats(deltaE, velvet::Image(2, 1, 1)).pixels, size_t(0));
        coverage.pixels = {0.0f, 0.0f, 0.99f, 0.0f};
        QCOMPARE(velvet::deltaEStats(deltaE, coverage).pixels, size_t(0));
    }
};

QTEST_APPLESS_MAIN(TestColorDifference)
#include "test_core_color_difference.moc"
