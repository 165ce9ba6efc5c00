// Measured properties of the fabric nodes' C++ twins (core/graph/fabric.h), which
// test_render_fabric_nodes shows the GPU matches: each pattern's period is one over its thread
// density (autocorrelation peaks), a twill's diagonal has the angle of its step, a satin's warp
// floats span N - 1 picks, plain weave is a checkerboard, warp and weft directions are
// orthogonal, the normal is the height's gradient (finite differences), a knit repeats once per
// stitch, fuzz streaks are `stretch` times longer along the yarn than across, and pile tilts by
// atan(lean) towards its lay direction. Filtered by a pixel's footprint, the Weave fades to its
// mean, which is the measured average of the unfiltered pattern.
#include "core/graph/fabric.h"

#include <QtTest>
#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <vector>

using namespace velvet::graph::fabric;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Normalised autocorrelation of the rows of @p rows (each a signal over one full period of the
/// whole pattern, so it is circular) at lag @p lag samples, averaged over rows.
double autocorrelation(const std::vector<std::vector<float>>& rows, int lag) {
    double num = 0.0, den = 0.0;
    for (const auto& r : rows) {
        double mean = 0.0;
        for (float v : r)
            mean += v;
        mean /= double(r.size());
        for (size_t k = 0; k < r.size(); ++k) {
            const double a = r[k] - mean, b = r[(k + size_t(lag)) % r.size()] - mean;
            num += a * b;
            den += a * a;
        }
    }
    return den > 0 ? num / den : 0.0;
}

/// The lag in [from, to] with the largest autocorrelation.
int peakLag(const std::vector<std::vector<float>>& rows, int from, int to) {
    int best = from;
    for (int l = from; l <= to; ++l)
        if (autocorrelation(rows, l) > autocorrelation(rows, best))
            best = l;
    return best;
}

/// The first local maximum of the autocorrelation after lag 0 that exceeds 0.1 (along V the
/// pick period shows only through the weft crowns between warp floats: r = 0.15 at one pick).
int firstPeakLag(const std::vector<std::vector<float>>& rows, int to) {
    for (int l = 2; l < to; ++l) {
        const double r = autocorrelation(rows, l);
        if (r > 0.1 && r >= autocorrelation(rows, l - 1) && r >= autocorrelation(rows, l + 1))
            return l;
    }
    return -1;
}

/// Samples @p f along U (rows at several V) or along V, @p perUnit samples per UV unit over
/// @p length UV units.
std::vector<std::vector<float>> sample(const std::function<float(glm::vec2)>& f, bool alongU,
                                       int perUnit, float length, int rowCount) {
    std::vector<std::vector<float>> rows(static_cast<size_t>(rowCount), std::vector<float>{});
    const int n = int(std::lround(perUnit * length));
    for (int r = 0; r < rowCount; ++r) {
        const float across = (r + 0.37f) * length / float(rowCount);
        for (int k = 0; k < n; ++k) {
            const float along = (k + 0.5f) / float(perUnit);
            rows[size_t(r)].push_back(
                f(alongU ? glm::vec2(along, across) : glm::vec2(across, along)));
        }
    }
    return rows;
}

WeaveParams twill(float over, float under, float step, glm::vec2 density) {
    WeaveParams p;
    p.pattern = float(WeavePattern::Twill);
    p.over = over;
    p.under = under;
    p.step = step;
    p.density = density;
    return p;
}

/// The warp mask at the centre of cell (i, j).
float warpAtCell(const WeaveParams& p, int i, int j) {
    return weave({(i + 0.5f) / p.density.x, (j + 0.5f) / p.density.y}, p).warp;
}

} // namespace

class TestCoreFabric : public QObject {
    Q_OBJECT
private slots:
    // A 2/1 twill with 8 ends and 12 picks per UV unit, 48 samples per unit: along U the first
    // autocorrelation peak is one end (1/8 = 6 samples) and the highest within four ends is the
    // weave's repeat (3 ends = 18 samples); along V, one pick (4 samples) and 3 picks (12).
    void periodIsOneOverDensity() {
        const WeaveParams p = twill(2, 1, 1, {8, 12});
        const auto height = [&](glm::vec2 uv) { return weave(uv, p).height; };
        const auto alongU = sample(height, true, 48, 1.5f, 24); // 12 ends: 4 repeats
        QCOMPARE(firstPeakLag(alongU, 24), 6);
        QCOMPARE(peakLag(alongU, 3, 24), 18);
        QVERIFY(autocorrelation(alongU, 18) > 0.999);
        const auto alongV = sample(height, false, 48, 1.0f, 24);
        QCOMPARE(firstPeakLag(alongV, 16), 4);
        QCOMPARE(peakLag(alongV, 2, 16), 12);
    }

    // The twill line: end i + 1 repeats end i shifted by `step` picks, so the diagonal rises
    // step / weft density over 1 / warp density: atan(step * warpDensity / weftDensity) from U.
    // Measured on the warp mask at cell centres as the shift that best matches adjacent ends.
    void twillDiagonalAngle_data() {
        QTest::addColumn<float>("over");
        QTest::addColumn<float>("under");
        QTest::addColumn<float>("step");
        QTest::addColumn<glm::vec2>("density");
        QTest::newRow("2/1, equal densities: 45 degrees") << 2.f << 1.f << 1.f << glm::vec2(20, 20);
        QTest::newRow("3/1, 10 x 20") << 3.f << 1.f << 1.f << glm::vec2(10, 20);
        QTest::newRow("3/2 steep twill, step 2") << 3.f << 2.f << 2.f << glm::vec2(20, 20);
    }
    void twillDiagonalAngle() {
        QFETCH(float, over);
        QFETCH(float, under);
        QFETCH(float, step);
        QFETCH(glm::vec2, density);
        const WeaveParams p = twill(over, under, step, density);
        const int repeat = int(over + under);
        int bestShift = 0, bestScore = -1;
        for (int k = -repeat + 1; k < repeat; ++k) {
            int score = 0;
            for (int i = 0; i < 30; ++i)
                for (int j = 0; j < 30; ++j)
                    score += warpAtCell(p, i + 1, j) == warpAtCell(p, i, j + k) ? 1 : 0;
            // Ties (k and k - repeat match equally) go to the smaller |k|: the visible diagonal.
            if (score > bestScore || (score == bestScore && std::abs(k) < std::abs(bestShift))) {
                bestScore = score;
                bestShift = k;
            }
        }
        QCOMPARE(bestScore, 900);
        const double measured =
            std::atan2(std::abs(bestShift) / density.y, 1.0 / density.x) * 180.0 / kPi;
        const double expected = std::atan(step * density.x / density.y) * 180.0 / kPi;
        qInfo("twill line at %.2f degrees from U (expected %.2f)", measured, expected);
        QVERIFY(std::abs(measured - expected) < 1e-4);
    }

    // An N-harness satin: along the middle of each warp end the warp is seen in runs of N - 1
    // picks (measured in UV at 32 samples per pick, rounded to whole picks), one per repeat.
    void satinFloatsOverNMinusOne_data() {
        QTest::addColumn<float>("harness");
        QTest::addColumn<float>("step");
        QTest::newRow("5-harness, counter 2") << 5.f << 2.f;
        QTest::newRow("8-harness, counter 3") << 8.f << 3.f;
    }
    void satinFloatsOverNMinusOne() {
        QFETCH(float, harness);
        QFETCH(float, step);
        WeaveParams p;
        p.pattern = float(WeavePattern::Satin);
        p.harness = harness;
        p.step = step;
        p.density = {16, 16};
        p.width = 0.8f;
        const int perPick = 32, picks = int(harness) * 4;
        int runs = 0;
        for (int i = 0; i < 8; ++i) {
            const float u = (i + 0.5f) / p.density.x;
            std::vector<int> seen;
            for (int k = 0; k < picks * perPick; ++k)
                seen.push_back(int(weave({u, (k + 0.5f) / (perPick * p.density.y)}, p).warp));
            // Runs of 1 that start and end inside the sampled span.
            for (size_t k = 1; k < seen.size(); ++k)
                if (seen[k] == 1 && seen[k - 1] == 0) {
                    size_t e = k;
                    while (e < seen.size() && seen[e] == 1)
                        ++e;
                    if (e == seen.size())
                        break;
                    const double length = double(e - k) / perPick;
                    QCOMPARE(int(std::lround(length)), int(harness) - 1);
                    ++runs;
                }
        }
        QVERIFY(runs >= 8 * 3);
    }

    // Plain weave at cell centres: warp over exactly where i + j is even.
    void plainIsCheckerboard() {
        WeaveParams p;
        p.pattern = float(WeavePattern::Plain);
        p.density = {12, 7};
        for (int i = -6; i < 18; ++i)
            for (int j = -6; j < 18; ++j)
                QCOMPARE(warpAtCell(p, i, j), ((i + j) % 2 + 2) % 2 == 0 ? 1.0f : 0.0f);
    }

    // Wherever a warp end is seen its direction is (0, 1), a weft pick's (1, 0); the two are
    // orthogonal unit vectors, and both kinds appear (about half each in a balanced twill).
    void warpAndWeftDirectionsAreOrthogonal() {
        const WeaveParams p; // the node's default 2/1 twill
        int warp = 0, weft = 0;
        glm::vec2 dw(0), df(0);
        for (int y = 0; y < 128; ++y)
            for (int x = 0; x < 128; ++x) {
                const WeaveSample s = weave({(x + 0.5f) / 128, (y + 0.5f) / 128}, p);
                if (s.height <= 0.0f)
                    continue;
                QCOMPARE(glm::length(s.direction), 1.0f);
                (s.warp > 0.5f ? dw : df) = s.direction;
                ++(s.warp > 0.5f ? warp : weft);
            }
        QVERIFY(warp > 1000 && weft > 1000);
        QCOMPARE(glm::dot(dw, df), 0.0f);
    }

    // The normal is the gradient of crossingHeight x height in mean thread spacings: central
    // differences (step 2e-4 UV) of the height output agree with the analytic normal within
    // 0.5 degrees at 98 % of 2000 points, counting only points whose five samples see the same
    // thread (a difference across a yarn's edge is not a gradient).
    void normalIsHeightGradient_data() {
        QTest::addColumn<float>("pattern");
        QTest::newRow("twill") << float(WeavePattern::Twill);
        QTest::newRow("satin") << float(WeavePattern::Satin);
        QTest::newRow("herringbone") << float(WeavePattern::Herringbone);
    }
    void normalIsHeightGradient() {
        QFETCH(float, pattern);
        WeaveParams p;
        p.pattern = pattern;
        p.step = pattern == float(WeavePattern::Satin) ? 2.0f : 1.0f;
        p.density = {14, 18};
        p.roundness = 1.4f;
        const float e = 2e-4f, scale = p.crossingHeight * 2.0f / (p.density.x + p.density.y);
        unsigned state = 12345u;
        const auto next = [&] {
            state = state * 1664525u + 1013904223u;
            return float(state >> 8) / 16777216.0f;
        };
        int kept = 0, good = 0;
        for (int n = 0; n < 2000; ++n) {
            const glm::vec2 uv(next(), next());
            const WeaveSample c = weave(uv, p);
            const WeaveSample s[4] = {
                weave(uv + glm::vec2(e, 0), p), weave(uv - glm::vec2(e, 0), p),
                weave(uv + glm::vec2(0, e), p), weave(uv - glm::vec2(0, e), p)};
            bool same = c.height > 0.0f;
            for (const WeaveSample& t : s)
                same = same && t.warp == c.warp && t.thread == c.thread && t.height > 0.0f;
            if (!same)
                continue;
            ++kept;
            const glm::vec3 fd =
                glm::normalize(glm::vec3(-scale * (s[0].height - s[1].height) / (2 * e),
                                         -scale * (s[2].height - s[3].height) / (2 * e), 1.0f));
            const double angle = std::acos(std::min(1.0f, glm::dot(fd, c.normal))) * 180.0 / kPi;
            good += angle < 0.5 ? 1 : 0;
        }
        qInfo("%d of %d points agree within 0.5 degrees", good, kept);
        QVERIFY(kept > 1000);
        QVERIFY(good >= 0.98 * kept);
    }

    // Jersey: the height repeats once per stitch, 1 / wale density along U (the two legs of a
    // stitch mirror each other, so the highest peak is the whole stitch, not half of it) and
    // 1 / course density along V; the legs lean in mirror directions.
    void knitRepeatsPerStitch() {
        KnitParams k;
        k.density = {8, 12};
        const auto height = [&](glm::vec2 uv) { return knit(uv, k).height; };
        QCOMPARE(peakLag(sample(height, true, 48, 1.0f, 24), 3, 9), 6);
        QCOMPARE(peakLag(sample(height, false, 48, 1.0f, 24), 2, 6), 4);
        const glm::vec2 left = knit({0.25f / 8, 0.5f / 12}, k).direction;
        const glm::vec2 right = knit({0.75f / 8, 0.5f / 12}, k).direction;
        QCOMPARE(left.x, -right.x);
        QCOMPARE(left.y, right.y);
        QVERIFY(left.x < 0.0f);
    }

    // Fuzz streaks run with the yarn: the lag at which the fuzz mask's correlation falls to 1/2
    // is `stretch` times longer along the direction than across it (within 25 %).
    void fuzzIsStretchedAlongTheYarn() {
        FuzzParams f;
        f.direction = glm::normalize(glm::vec2(1, 2));
        f.amount = 1.0f;
        f.density = 100.0f;
        f.stretch = 6.0f;
        const glm::vec2 across(f.direction.y, -f.direction.x);
        std::vector<glm::vec2> points;
        unsigned state = 99u;
        for (int n = 0; n < 3000; ++n) {
            state = state * 1664525u + 1013904223u;
            const float a = float(state >> 8) / 16777216.0f;
            state = state * 1664525u + 1013904223u;
            points.emplace_back(a, float(state >> 8) / 16777216.0f);
        }
        const auto halfLength = [&](glm::vec2 dir) {
            for (int l = 1; l < 400; ++l) {
                const float lag = l * 0.02f / f.density;
                double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
                for (const glm::vec2& p : points) {
                    const double a = fuzz(p, f).mask, b = fuzz(p + lag * dir, f).mask;
                    sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b;
                }
                const double n = double(points.size());
                const double r =
                    (sab / n - sa * sb / (n * n)) /
                    std::sqrt((saa / n - sa * sa / (n * n)) * (sbb / n - sb * sb / (n * n)));
                if (r < 0.5)
                    return double(lag);
            }
            return 0.0;
        };
        const double along = halfLength(f.direction), acrossLength = halfLength(across);
        qInfo("correlation half-length along %.5f, across %.5f, ratio %.2f", along, acrossLength,
              along / acrossLength);
        QVERIFY(acrossLength > 0.0);
        QVERIFY(std::abs(along / acrossLength / f.stretch - 1.0) < 0.25);
    }

    // Filtering (fabric_source.inl): where a pixel spans three quarters of a thread or more, the
    // Weave shows the same values everywhere — its mean — and that mean is the measured average
    // of the unfiltered pattern over a whole repeat within 0.02 (colour per channel, height,
    // sheen) and 0.01 (warp share); the normal is flat, and the roughness takes the relief's
    // slopes (GGX alpha^2 grows by their variance, Toksvig 2005), modelled within 35 % of the
    // measured mean squared slope.
    void filteredWeaveIsItsMeasuredMean_data() {
        QTest::addColumn<int>("pattern");
        QTest::addColumn<float>("width");
        QTest::addColumn<float>("roundness");
        QTest::newRow("plain, w 1, r 1") << 0 << 1.0f << 1.0f;
        QTest::newRow("plain, w 0.6, r 0.5") << 0 << 0.6f << 0.5f;
        QTest::newRow("twill 3/1, w 0.85, r 1") << 1 << 0.85f << 1.0f;
        QTest::newRow("twill 3/1, w 0.9, r 1.2 (denim)") << 1 << 0.9f << 1.2f;
        QTest::newRow("satin 5, w 1, r 0.5") << 2 << 1.0f << 0.5f;
        QTest::newRow("satin 5, w 0.85, r 2") << 2 << 0.85f << 2.0f;
        QTest::newRow("basket 2, w 0.85, r 1") << 3 << 0.85f << 1.0f;
        QTest::newRow("herringbone 2/2, w 0.92, r 1") << 4 << 0.92f << 1.0f;
    }
    void filteredWeaveIsItsMeasuredMean() {
        QFETCH(int, pattern);
        QFETCH(float, width);
        QFETCH(float, roundness);
        WeaveParams p;
        p.pattern = float(pattern);
        p.over = pattern == 4 ? 2.0f : 3.0f;
        p.under = pattern == 4 ? 2.0f : 1.0f;
        p.harness = 5.0f;
        p.step = pattern == 2 ? 2.0f : 1.0f;
        p.group = pattern == 4 ? 4.0f : 2.0f;
        p.density = {1.0f, 1.0f};
        p.width = width;
        p.roundness = roundness;
        p.warpColor = {0.9f, 0.1f, 0.4f};
        p.weftColor = {0.05f, 0.7f, 0.3f};
        p.roughness = 0.5f;
        p.crossingHeight = 0.2f; // alpha^4 stays under 1 (no clamp) with the slopes added
        // One whole repeat along u and v (herringbone: two stripes of 4 ends), 64 x 64 samples a
        // cell (yarn edges are sharp: coarser sampling misplaces them by a whole sample).
        const int kCells = pattern == 4 ? 8 : pattern == 2 ? 5 : 4, kPer = 64;
        glm::dvec3 color(0.0);
        double height = 0.0, sheen = 0.0, warp = 0.0, slope2 = 0.0;
        for (int a = 0; a < kCells * kPer; ++a)
            for (int b = 0; b < kCells * kPer; ++b) {
                const WeaveSample w = weave({(a + 0.5f) / kPer, (b + 0.5f) / kPer}, p);
                color += glm::dvec3(w.color);
                height += w.height, sheen += w.sheen, warp += w.warp;
                slope2 +=
                    (w.normal.x * w.normal.x + w.normal.y * w.normal.y) / (w.normal.z * w.normal.z);
            }
        const double n = double(kCells * kPer) * double(kCells * kPer);
        color /= n, height /= n, sheen /= n, warp /= n, slope2 /= n;

        WeaveParams filtered = p;
        filtered.footprint = {0.75f, 0.5f}; // three quarters of a thread along u
        const WeaveSample a = weave({0.13f, 0.71f}, filtered);
        const WeaveSample b = weave({3.6f, 1.27f}, filtered);
        QCOMPARE(a.color, b.color);
        QCOMPARE(a.height, b.height);
        QCOMPARE(a.normal, glm::vec3(0.0f, 0.0f, 1.0f));
        QCOMPARE(b.normal, glm::vec3(0.0f, 0.0f, 1.0f));
        const WeaveMean mean = weaveMean(p);
        QCOMPARE(a.color, mean.color);
        QCOMPARE(a.sheen, mean.sheen);
        QCOMPARE(a.warp, mean.warp);
        QCOMPARE(a.occlusion, 0.45f + 0.55f * mean.height);
        qInfo("measured colour (%.4f %.4f %.4f) height %.4f sheen %.4f warp %.4f; model (%.4f "
              "%.4f %.4f) %.4f %.4f %.4f",
              color.x, color.y, color.z, height, sheen, warp, mean.color.x, mean.color.y,
              mean.color.z, mean.height, mean.sheen, mean.warp);
        for (int c = 0; c < 3; ++c)
            QVERIFY(std::abs(mean.color[c] - color[c]) < 0.02);
        QVERIFY(std::abs(mean.height - height) < 0.02);
        QVERIFY(std::abs(mean.sheen - sheen) < 0.02);
        QVERIFY(std::abs(mean.warp - warp) < 0.01);
        // Toksvig: alpha^4 (alpha = roughness^2) of the filtered weave less that of the mean
        // roughness is the modelled slope variance; against the measured one.
        const float base = std::clamp(p.roughness + 0.15f * (1.0f - mean.height), 0.0f, 1.0f);
        const double modelled = std::pow(double(a.roughness), 4.0) - std::pow(double(base), 4.0);
        qInfo("mean squared slope: measured %.4f, modelled %.4f", slope2, modelled);
        QVERIFY(modelled > 0.65 * slope2 && modelled < 1.35 * slope2);
    }

    // A pixel spanning a quarter of a thread or less sees the pattern unfiltered; between a
    // quarter and three quarters it fades monotonically from the pattern to the mean.
    void weaveFadesWithTheFootprint() {
        WeaveParams p = twill(3, 1, 1, {40.0f, 30.0f});
        p.warpColor = {0.02f, 0.05f, 0.2f};
        p.weftColor = {0.8f, 0.8f, 0.75f};
        const WeaveMean mean = weaveMean(p);
        for (int k = 0; k < 50; ++k) {
            const glm::vec2 uv(0.013f * k + 0.002f, 0.029f * k + 0.011f);
            const WeaveSample sharp = weave(uv, p);
            WeaveParams q = p;
            q.footprint = glm::vec2(0.25f / 40.0f); // a quarter of an end, a third of a pick
            const WeaveSample same = weave(uv, q);
            QCOMPARE(same.color, sharp.color);
            QCOMPARE(same.normal, sharp.normal);
            QCOMPARE(same.height, sharp.height);
            float last = std::abs(sharp.color.x - mean.color.x);
            for (float cells : {0.35f, 0.5f, 0.65f}) {
                q.footprint = glm::vec2(cells / 40.0f);
                const float off = std::abs(weave(uv, q).color.x - mean.color.x);
                QVERIFY(off <= last + 1e-6f);
                last = off;
            }
        }
    }

    // Uncrushed pile tilts every normal by atan(lean) towards the lay direction; crushed velvet
    // flattens patches (tilt atan 1.2) turned other ways, over a fair share of the surface.
    void pileTiltsTowardsItsLay() {
        PileParams p;
        p.angle = 30.0f;
        p.lean = 0.35f;
        int crushed = 0;
        for (int n = 0; n < 400; ++n) {
            const glm::vec2 uv((n % 20 + 0.5f) / 20, (n / 20 + 0.5f) / 20);
            const glm::vec3 nrm = pile(uv, p).normal;
            QVERIFY(std::abs(std::atan2(glm::length(glm::vec2(nrm.x, nrm.y)), nrm.z) -
                             std::atan(0.35)) < 1e-5);
            QVERIFY(std::abs(std::atan2(nrm.y, nrm.x) * 180.0 / kPi - 30.0) < 1e-3);
            PileParams c = p;
            c.crush = 1.0f;
            const PileSample s = pile(uv, c);
            if (s.crush >= 1.0f) {
                ++crushed;
                QVERIFY(std::abs(
                            std::atan2(glm::length(glm::vec2(s.normal.x, s.normal.y)), s.normal.z) -
                            std::atan(1.2)) < 1e-5);
            }
        }
        qInfo("%d of 400 points fully crushed", crushed);
        QVERIFY(crushed > 20 && crushed < 380);
    }
};

QTEST_GUILESS_MAIN(TestCoreFabric)
#include "test_core_fabric.moc"
