// core/mtlx_values (docs/interchange.md, "UV transforms"): a Velvet UV transform written as a
// MaterialX placement (image uvtiling / uvoffset, and a place2d for a rotation) samples the same
// texel as Velvet for every UV, and a placement read back gives the same transform. The
// reference below is NG_place2d_vector2 and mx_rotate_vector2 of MaterialX's standard library,
// written out literally, and the image node's uv * uvtiling + uvoffset; MaterialX's v runs up
// from the bottom row, Velvet's down from the top (v_mx = 1 - v).
#include "core/mtlx_values.h"

#include <QtTest>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <random>

using namespace velvet;

namespace {

glm::vec2 mxRotate(glm::vec2 in, float degrees) { // mx_rotate_vector2
    const float r = glm::radians(degrees), s = std::sin(r), c = std::cos(r);
    return {c * in.x + s * in.y, -s * in.x + c * in.y};
}

/// What MaterialX samples (in its UV space) for texcoord @p t.
glm::vec2 mxSample(const mtlx::MtlxPlacement& p, glm::vec2 t) {
    if (p.place) {
        const mtlx::Place2d& q = *p.place;
        const glm::vec2 sub = t - q.pivot;
        t = q.operationOrder == 0 ? mxRotate(sub / q.scale, q.rotate) - q.offset + q.pivot
                                  : mxRotate(sub - q.offset, q.rotate) / q.scale + q.pivot;
    }
    return t * p.tiling + p.offset;
}

/// What Velvet samples (texture_ref.h: R(rotation) (scale uv) + offset, R counter-clockwise).
glm::vec2 velvetSample(const UvTransform& uv, glm::vec2 t) {
    const float r = glm::radians(uv.rotation), s = std::sin(r), c = std::cos(r);
    const glm::vec2 st = uv.scale * t;
    return glm::vec2(c * st.x - s * st.y, s * st.x + c * st.y) + uv.offset;
}

glm::vec2 flipV(glm::vec2 t) {
    return {t.x, 1.0f - t.y};
}

/// The largest distance between the two samplings over a grid of UVs (beyond [0, 1] too).
float largestDifference(const UvTransform& velvet, const mtlx::MtlxPlacement& mx) {
    float worst = 0.0f;
    for (float u = -1.0f; u <= 2.0f; u += 0.25f)
        for (float v = -1.0f; v <= 2.0f; v += 0.25f) {
            const glm::vec2 t(u, v);
            worst = std::max(worst,
                             glm::length(velvetSample(velvet, t) - flipV(mxSample(mx, flipV(t)))));
        }
    return worst;
}

} // namespace

class TestMtlxValues : public QObject {
    Q_OBJECT
private slots:
    /// Export: every transform, rotated or not, samples the same texels in MaterialX.
    void exportedPlacementSamplesTheSameTexels() {
        std::mt19937 rng(12);
        std::uniform_real_distribution<float> scale(0.2f, 5.0f), offset(-2.0f, 2.0f),
            angle(-180.0f, 180.0f);
        for (int i = 0; i < 200; ++i) {
            UvTransform uv;
            uv.scale = {scale(rng), scale(rng)};
            uv.offset = {offset(rng), offset(rng)};
            uv.rotation = i % 4 == 0 ? 0.0f : angle(rng);
            const mtlx::MtlxPlacement mx = mtlx::mtlxPlacement(uv.scale, uv.offset, uv.rotation);
            // Unrotated transforms keep the image node's own inputs (no place2d).
            QCOMPARE(mx.place.has_value(), uv.rotation != 0.0f);
            const float d = largestDifference(uv, mx);
            QVERIFY2(d < 1e-3f, qPrintable(QString::number(d)));
            // ... and read back as they were.
            UvTransform back;
            QVERIFY(mtlx::velvetPlacement(mx, back));
            QVERIFY2(glm::length(back.scale - uv.scale) < 1e-4f * glm::length(uv.scale) &&
                         glm::length(back.offset - uv.offset) < 1e-4f &&
                         std::abs(std::remainder(back.rotation - uv.rotation, 360.0f)) < 1e-3f,
                     qPrintable(QStringLiteral("%1 %2 %3 -> %4 %5 %6")
                                    .arg(uv.scale.x)
                                    .arg(uv.offset.x)
                                    .arg(uv.rotation)
                                    .arg(back.scale.x)
                                    .arg(back.offset.x)
                                    .arg(back.rotation)));
        }
    }

    /// Import: place2d nodes as other tools write them (a pivot, either operation order, the
    /// image's own tiling on top) become the Velvet transform that samples the same texels.
    void importedPlace2dSamplesTheSameTexels() {
        struct Case {
            const char* what;
            mtlx::MtlxPlacement p;
        };
        mtlx::Place2d centre;
        centre.pivot = {0.5f, 0.5f};
        centre.rotate = 90.0f;
        mtlx::Place2d trs = centre;
        trs.operationOrder = 1;
        trs.scale = {2.0f, 2.0f};
        trs.offset = {0.1f, -0.3f};
        mtlx::Place2d srt;
        srt.scale = {0.5f, 4.0f}; // non-uniform before the rotation: no shear
        srt.rotate = -35.0f;
        srt.offset = {0.25f, 0.0f};
        srt.pivot = {0.2f, 0.7f};
        const Case cases[] = {
            {"quarter turn about the centre", {glm::vec2(1.0f), glm::vec2(0.0f), centre}},
            {"TRS, uniform scale", {glm::vec2(1.0f), glm::vec2(0.0f), trs}},
            {"SRT, non-uniform scale, tiled", {glm::vec2(3.0f), glm::vec2(0.5f, 0.1f), srt}},
            {"image tiling alone", {glm::vec2(4.0f, 2.0f), glm::vec2(0.3f, 0.2f), std::nullopt}},
        };
        for (const Case& c : cases) {
            UvTransform uv;
            QVERIFY2(mtlx::velvetPlacement(c.p, uv), c.what);
            const float d = largestDifference(uv, c.p);
            QVERIFY2(d < 1e-4f, qPrintable(QString("%1: %2").arg(c.what).arg(d)));
        }
        // Known answer: the quarter turn about the centre takes MaterialX texcoord (1, 0.5) to
        // rotate2d((0.5, 0)) + pivot = (0.5, 0): Velvet's (1, 0.5) samples (0.5, 1).
        UvTransform quarter;
        QVERIFY(mtlx::velvetPlacement(cases[0].p, quarter));
        QVERIFY(glm::length(velvetSample(quarter, {1.0f, 0.5f}) - glm::vec2(0.5f, 1.0f)) < 1e-5f);
        QVERIFY(std::abs(quarter.rotation - 90.0f) < 1e-4f);
    }

    /// A shear (a non-uniform scale after the rotation) has no Velvet counterpart: refused, so
    /// the importer says so.
    void shearIsRefused() {
        mtlx::Place2d trs;
        trs.operationOrder = 1; // rotate, then scale
        trs.rotate = 30.0f;
        trs.scale = {1.0f, 3.0f};
        UvTransform uv;
        QVERIFY(!mtlx::velvetPlacement({glm::vec2(1.0f), glm::vec2(0.0f), trs}, uv));
        mtlx::Place2d turn;
        turn.rotate = 45.0f;
        QVERIFY(!mtlx::velvetPlacement({glm::vec2(1.0f, 2.0f), glm::vec2(0.0f), turn}, uv));
        QVERIFY(mtlx::velvetPlacement({glm::vec2(2.0f), glm::vec2(0.0f), turn}, uv));
    }

    void constantValues() {
        std::vector<float> v;
        QCOMPARE(QString::fromStdString(mtlx::constantValue("0.5", 3, v)), QString());
        QVERIFY(v == std::vector<float>({0.5f, 0.5f, 0.5f})); // a scalar splat for a colour
        QCOMPARE(QString::fromStdString(mtlx::constantValue("1, x", 2, v)),
                 QStringLiteral("is not a number list"));
        QCOMPARE(QString::fromStdString(mtlx::constantValue("1, 2", 3, v)),
                 QStringLiteral("has 2 components, expected 3"));
        QCOMPARE(QString::fromStdString(mtlx::constantValue("inf", 1, v)),
                 QStringLiteral("is not finite"));
    }
};

QTEST_GUILESS_MAIN(TestMtlxValues)
#include "test_core_mtlx_values.moc"
