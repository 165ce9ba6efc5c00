// Measured properties of the leather Grain node's C++ twin (core/graph/fabric.h, grain()), which
// test_render_fabric_nodes shows the GPU matches: a bake holds `scale`^2 cells per UV^2 (the cells'
// tops counted as connected regions, so the mean cell spacing is 1 / scale); the height stays in
// [0, 1] and the normal is unit length; the normal is the height's gradient (finite
// differences); and, filtered by a pixel's footprint, the Grain fades to its mean, which is the
// measured average of the unfiltered pattern.
#include "core/graph/fabric.h"

#include <QtTest>
#include <cmath>
#include <glm/geometric.hpp>
#include <vector>

using namespace velvet::graph::fabric;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A small deterministic generator of points in [0, 1).
struct Lcg {
    unsigned state = 12345u;
    float next() {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / 16777216.0f;
    }
};

/// Counts the cells of a bake of @p cells x @p cells cell spacings (@p perCell samples each) from
/// the pattern alone: the connected regions (4-neighbours) of the cells' tops, where the cavity
/// is under 1/2, whose centroid lies at least @p margin spacings inside the bake and which do
/// not touch its edge. @p windowCells receives the area of that inner window in cell spacings^2.
int countCells(const GrainParams& p, int cells, int perCell, int margin, double* windowCells) {
    const int n = cells * perCell;
    const glm::vec2 origin(3.1f, 5.7f); // away from the UV origin, so negative and odd cells too
    std::vector<char> top(size_t(n) * size_t(n));
    std::vector<char> seen(top.size(), 0);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const glm::vec2 uv =
                origin + glm::vec2(x + 0.5f, y + 0.5f) / (float(perCell) * p.scale);
            top[size_t(y) * size_t(n) + size_t(x)] = grain(uv, p).cavity < 0.5f ? 1 : 0;
        }
    int count = 0;
    std::vector<int> stack;
    for (int s = 0; s < n * n; ++s) {
        if (!top[size_t(s)] || seen[size_t(s)])
            continue;
        double cx = 0.0, cy = 0.0;
        int area = 0;
        bool edge = false;
        stack = {s};
        seen[size_t(s)] = 1;
        while (!stack.empty()) {
            const int q = stack.back();
            stack.pop_back();
            const int x = q % n, y = q / n;
            cx += x, cy += y, ++area;
            edge = edge || x == 0 || y == 0 || x == n - 1 || y == n - 1;
            const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
            for (int k = 0; k < 4; ++k) {
                if (nx[k] < 0 || ny[k] < 0 || nx[k] >= n || ny[k] >= n)
                    continue;
                const size_t r = size_t(ny[k]) * size_t(n) + size_t(nx[k]);
                if (top[r] && !seen[r]) {
                    seen[r] = 1;
                    stack.push_back(int(r));
                }
            }
        }
        cx = (cx / area + 0.5) / perCell, cy = (cy / area + 0.5) / perCell;
        if (!edge && cx >= margin && cx < cells - margin && cy >= margin && cy < cells - margin)
            ++count;
    }
    *windowCells = double(cells - 2 * margin) * double(cells - 2 * margin);
    return count;
}

} // namespace

class TestCoreGrain : public QObject {
    Q_OBJECT
private slots:
    // One cell per grid square, whatever the jitter: the bake holds scale^2 cells per UV^2, so
    // the mean spacing sqrt(area / count) is 1 / scale. A regular grid (irregularity 0) gives
    // exactly the 30 x 30 window's 900 cells; jittered ones within 1 % (cells whose centroid
    // falls across the window's edge come and go), measured 898 to 905.
    void cellSpacingIsOneOverScale_data() {
        QTest::addColumn<float>("scale");
        QTest::addColumn<float>("irregularity");
        QTest::addColumn<float>("creaseWidth");
        QTest::newRow("square grid, scale 7") << 7.0f << 0.0f << 0.2f;
        QTest::newRow("irregularity 0.5, scale 23") << 23.0f << 0.5f << 0.2f;
        QTest::newRow("default, scale 12") << 12.0f << 0.85f << 0.2f;
        QTest::newRow("irregularity 1, wide creases, scale 40") << 40.0f << 1.0f << 0.35f;
    }
    void cellSpacingIsOneOverScale() {
        QFETCH(float, scale);
        QFETCH(float, irregularity);
        QFETCH(float, creaseWidth);
        GrainParams p;
        p.scale = scale;
        p.irregularity = irregularity;
        p.creaseWidth = creaseWidth;
        double window = 0.0;
        const int count = countCells(p, 34, 12, 2, &window);
        const double spacing = std::sqrt(window / count) / scale; // UV units
        qInfo("%d cells in %.0f cell spacings^2: mean spacing %.5f, 1 / scale %.5f", count, window,
              spacing, 1.0 / scale);
        if (irregularity == 0.0f)
            QCOMPARE(count, 900);
        QVERIFY(std::abs(count - window) <= 0.01 * window);
        QVERIFY(std::abs(spacing * scale - 1.0) < 0.005);
    }

    // Everywhere, for any parameters in range: height, cavity and occlusion in [0, 1], the cell
    // id in [0, 1), the normal unit length and facing out.
    void heightInRangeAndNormalUnit() {
        Lcg rng;
        for (int t = 0; t < 40; ++t) {
            GrainParams p;
            p.scale = 2.0f + 60.0f * rng.next();
            p.irregularity = rng.next();
            p.creaseWidth = 0.01f + 0.49f * rng.next();
            p.dome = rng.next();
            p.depth = 2.0f * rng.next();
            if (t % 4 == 3)
                p.footprint = glm::vec2(rng.next() / p.scale);
            for (int k = 0; k < 500; ++k) {
                const glm::vec2 uv(20.0f * rng.next() - 10.0f, 20.0f * rng.next() - 10.0f);
                const GrainSample g = grain(uv, p);
                QVERIFY(g.height >= 0.0f && g.height <= 1.0f);
                QVERIFY(g.cavity >= 0.0f && g.cavity <= 1.0f);
                QVERIFY(g.occlusion >= 0.4f - 1e-6f && g.occlusion <= 1.0f);
                QVERIFY(g.cell >= 0.0f && g.cell < 1.0f);
                QVERIFY(g.roughness >= 0.0f && g.roughness <= 1.0f);
                QVERIFY(std::abs(glm::length(g.normal) - 1.0f) < 1e-5f);
                QVERIFY(g.normal.z > 0.0f);
            }
        }
    }

    // The analytic normal against central differences of depth x height (in cell spacings, so
    // depth / scale UV units): within 0.5 degrees wherever the four samples stay in one cell and
    // off the crease's floor (where the smooth minimum is clamped to 0).
    void normalIsHeightGradient_data() {
        QTest::addColumn<float>("dome");
        QTest::addColumn<float>("depth");
        QTest::newRow("default") << GrainParams{}.dome << GrainParams{}.depth;
        QTest::newRow("flat tops, deep") << 0.0f << 0.5f;
        QTest::newRow("full dome") << 1.0f << 0.3f;
    }
    void normalIsHeightGradient() {
        QFETCH(float, dome);
        QFETCH(float, depth);
        GrainParams p;
        p.scale = 9.0f;
        p.dome = dome;
        p.depth = depth;
        const float e = 2e-5f, k = p.depth / p.scale;
        Lcg rng;
        int kept = 0, good = 0;
        for (int n = 0; n < 3000; ++n) {
            const glm::vec2 uv(rng.next(), rng.next());
            const GrainSample c = grain(uv, p);
            const GrainSample s[4] = {
                grain(uv + glm::vec2(e, 0), p), grain(uv - glm::vec2(e, 0), p),
                grain(uv + glm::vec2(0, e), p), grain(uv - glm::vec2(0, e), p)};
            bool same = c.cavity < 1.0f;
            for (const GrainSample& t : s)
                same = same && t.cell == c.cell && t.cavity < 1.0f;
            if (!same)
                continue;
            ++kept;
            const glm::vec3 fd =
                glm::normalize(glm::vec3(-k * (s[0].height - s[1].height) / (2 * e),
                                         -k * (s[2].height - s[3].height) / (2 * e), 1.0f));
            const double angle = std::acos(std::min(1.0f, glm::dot(fd, c.normal))) * 180.0 / kPi;
            good += angle < 0.5 ? 1 : 0;
        }
        qInfo("%d of %d points agree within 0.5 degrees", good, kept);
        QVERIFY(kept > 2000);
        QVERIFY(good >= 0.98 * kept);
    }

    // Filtered (a pixel spanning three quarters of a cell), the Grain is the same everywhere:
    // the modelled mean (grainMean), which is the average of the unfiltered pattern within 0.01
    // in height and crease profile, the colour and roughness following the mean height, a flat
    // normal, and the slopes' variance in the roughness (Toksvig) within 12 % of the measured.
    void filteredGrainIsItsMeasuredMean_data() {
        QTest::addColumn<float>("irregularity");
        QTest::addColumn<float>("creaseWidth");
        QTest::addColumn<float>("dome");
        QTest::newRow("default") << GrainParams{}.irregularity << GrainParams{}.creaseWidth
                                 << GrainParams{}.dome;
        QTest::newRow("square grid, narrow creases, flat") << 0.0f << 0.08f << 0.0f;
        QTest::newRow("irregularity 0.5, w 0.3, dome 0.6") << 0.5f << 0.3f << 0.6f;
        QTest::newRow("irregularity 1, w 0.16, dome 1") << 1.0f << 0.16f << 1.0f;
    }
    void filteredGrainIsItsMeasuredMean() {
        QFETCH(float, irregularity);
        QFETCH(float, creaseWidth);
        QFETCH(float, dome);
        GrainParams p;
        p.scale = 1.0f;
        p.irregularity = irregularity;
        p.creaseWidth = creaseWidth;
        p.dome = dome;
        p.depth = 0.1f; // alpha^4 stays under 1 (no clamp) with the slopes added
        p.roughness = 0.4f;
        p.creaseRoughness = 0.7f;
        p.color = {0.8f, 0.3f, 0.1f};
        p.creaseColor = {0.1f, 0.05f, 0.4f};
        // 40 x 40 cells, 20 x 20 samples each (offset from the cells' symmetric points).
        const int kCells = 40, kPer = 20;
        double height = 0.0, crease = 0.0, slope2 = 0.0;
        for (int a = 0; a < kCells * kPer; ++a)
            for (int b = 0; b < kCells * kPer; ++b) {
                const GrainSample g = grain({(a + 0.37f) / kPer, (b + 0.61f) / kPer}, p);
                height += g.height, crease += 1.0 - g.cavity;
                slope2 +=
                    (g.normal.x * g.normal.x + g.normal.y * g.normal.y) / (g.normal.z * g.normal.z);
            }
        const double n = double(kCells * kPer) * double(kCells * kPer);
        height /= n, crease /= n, slope2 /= n;

        GrainParams filtered = p;
        filtered.footprint = {0.75f, 0.25f}; // three quarters of a cell along u
        const GrainSample a = grain({0.13f, 0.71f}, filtered);
        const GrainSample b = grain({3.6f, 1.27f}, filtered);
        QCOMPARE(a.color, b.color);
        QCOMPARE(a.height, b.height);
        QCOMPARE(a.roughness, b.roughness);
        QCOMPARE(a.normal, glm::vec3(0.0f, 0.0f, 1.0f));
        QCOMPARE(b.normal, glm::vec3(0.0f, 0.0f, 1.0f));
        const GrainMean mean = grainMean(p);
        QCOMPARE(a.height, mean.height);
        QCOMPARE(a.cavity, 1.0f - mean.crease);
        QCOMPARE(a.color, glm::mix(p.creaseColor, p.color, mean.height));
        qInfo(
            "measured height %.4f crease %.4f slope^2 %.4f (per unit depth); model %.4f %.4f %.4f",
            height, crease, slope2 / (p.depth * p.depth), mean.height, mean.crease, mean.slope2);
        QVERIFY(std::abs(mean.height - height) < 0.01);
        QVERIFY(std::abs(mean.crease - crease) < 0.01);
        const double base = glm::mix(p.creaseRoughness, p.roughness, mean.height);
        const double modelled = std::pow(double(a.roughness), 4.0) - std::pow(base, 4.0);
        qInfo("mean squared slope: measured %.5f, in the roughness %.5f", slope2, modelled);
        QVERIFY(modelled > 0.88 * slope2 && modelled < 1.12 * slope2);
    }

    // A pixel spanning a quarter of a cell or less sees the pattern unfiltered; between a
    // quarter and three quarters it fades monotonically from the pattern to the mean.
    void grainFadesWithTheFootprint() {
        GrainParams p;
        p.scale = 30.0f;
        const GrainMean mean = grainMean(p);
        for (int k = 0; k < 50; ++k) {
            const glm::vec2 uv(0.013f * k + 0.002f, 0.029f * k + 0.011f);
            const GrainSample sharp = grain(uv, p);
            GrainParams q = p;
            q.footprint = glm::vec2(0.25f / p.scale);
            const GrainSample same = grain(uv, q);
            QCOMPARE(same.color, sharp.color);
            QCOMPARE(same.normal, sharp.normal);
            QCOMPARE(same.height, sharp.height);
            QCOMPARE(same.roughness, sharp.roughness);
            float last = std::abs(sharp.height - mean.height);
            float lastTilt = 1.0f - sharp.normal.z;
            for (float cells : {0.35f, 0.5f, 0.65f}) {
                q.footprint = glm::vec2(cells / p.scale);
                const GrainSample g = grain(uv, q);
                const float off = std::abs(g.height - mean.height);
                QVERIFY(off <= last + 1e-6f);
                QVERIFY(1.0f - g.normal.z <= lastTilt + 1e-6f);
                last = off;
                lastTilt = 1.0f - g.normal.z;
            }
        }
    }
};

QTEST_GUILESS_MAIN(TestCoreGrain)
#include "test_core_grain.moc"
