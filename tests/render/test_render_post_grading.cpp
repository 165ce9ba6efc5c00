// The post chain's colour effects against their C++ twins and known answers: the tone curves,
// colour grading, film grain, chromatic aberration, sharpening, FXAA and the vignette's
// parameters (post_test_harness.h runs the real chain on float textures; the spatial effects,
// fusion, ordering and goldens are test_render_post_effects').
#include "core/image.h"
#include "core/post_effects.h"
#include "core/tone_curves.h"
#include "post_effect_inputs.h"
#include "render/post_chain.h"
#include "render_test_util.h"

#include <QtTest>
#include <cmath>

using namespace velvet;
using namespace velvet::test;

namespace {

float srgbEncode(float c) {
    c = std::max(c, 0.0f);
    return c < 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}
float srgbDecode(float c) {
    return c < 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

/// @name C++ twins of the tone curves (resources/shaders/common_tonemap.glsl,
/// post_tonemap.glsl), in the operator order of the tonemap effect's choice.
/// @{
glm::vec3 acesFitted(glm::vec3 c) {
    const glm::mat3 in(0.59719f, 0.07600f, 0.02840f, 0.35458f, 0.90834f, 0.13383f, 0.04823f,
                       0.01566f, 0.83777f);
    const glm::mat3 out(1.60475f, -0.10208f, -0.00327f, -0.53108f, 1.10813f, -0.07276f, -0.07367f,
                        -0.00605f, 1.07602f);
    const glm::vec3 v = in * c;
    const glm::vec3 a = v * (v + 0.0245786f) - 0.000090537f;
    const glm::vec3 b = v * (0.983729f * v + 0.4329510f) + 0.238081f;
    return glm::clamp(out * (a / b), 0.0f, 1.0f);
}
glm::vec3 hable(glm::vec3 x) {
    const float A = 0.15f, B = 0.50f, C = 0.10f, D = 0.20f, E = 0.02f, F = 0.30f;
    return ((x * (A * x + C * B) + D * E) / (x * (A * x + B) + D * F)) - E / F;
}
glm::vec3 agx(glm::vec3 c) {
    const glm::mat3 inset(0.842479062253094f, 0.0423282422610123f, 0.0423756549057051f,
                          0.0784335999999992f, 0.878468636469772f, 0.0784336f, 0.0792237451477643f,
                          0.0791661274605434f, 0.879142973793104f);
    const glm::mat3 outset(1.19687900512017f, -0.0528968517574562f, -0.0529716355144438f,
                           -0.0980208811401368f, 1.15190312990417f, -0.0980434501171241f,
                           -0.0990297440797205f, -0.0989611768448433f, 1.15107367264116f);
    glm::vec3 v = inset * c;
    for (int k = 0; k < 3; ++k)
        v[k] = std::clamp((std::log2(std::max(v[k], 1e-10f)) + 12.47393f) / 16.5f, 0.0f, 1.0f);
    const glm::vec3 x2 = v * v, x4 = x2 * x2;
    v = 15.5f * x4 * x2 - 40.14f * x4 * v + 31.96f * x4 - 6.868f * x2 * v + 0.4298f * x2 +
        0.1191f * v - 0.00232f;
    v = glm::clamp(outset * v, 0.0f, 1.0f);
    for (int k = 0; k < 3; ++k)
        v[k] = std::clamp(srgbDecode(v[k]), 0.0f, 1.0f);
    return v;
}
/// Display-linear output of operator @p op (0 pbr-neutral … 5 linear) for scene-linear @p c.
glm::vec3 toneCurve(int op, glm::vec3 c) {
    c = glm::max(c, glm::vec3(0.0f));
    switch (op) {
    case 0:
        return glm::clamp(tone::khronosPbrNeutral(c), 0.0f, 1.0f);
    case 1:
        return acesFitted(c);
    case 2:
        return c / (1.0f + c);
    case 3:
        return glm::clamp(hable(2.0f * c) / hable(glm::vec3(11.2f)), 0.0f, 1.0f);
    case 4:
        return agx(c);
    default:
        return glm::clamp(c, 0.0f, 1.0f);
    }
}
/// @}

/// Row 0: grey 2^((x - 32) / 4) (1 at x = 32); row 1: the same times (1, 0.4, 0.1).
Image toneRamp() {
    Image img(kSize, 2, 4);
    for (int x = 0; x < kSize; ++x) {
        const float v = std::exp2(float(x - 32) / 4.0f);
        float* g = img.at(x, 0);
        g[0] = g[1] = g[2] = v;
        g[3] = 1;
        float* c = img.at(x, 1);
        c[0] = v, c[1] = 0.4f * v, c[2] = 0.1f * v, c[3] = 1;
    }
    return img;
}

/// Centroid along x of channel @p ch over columns [x0, x1) of row @p y.
double centroidX(const Image& img, int ch, int y, int x0, int x1) {
    double s = 0, w = 0;
    for (int x = x0; x < x1; ++x) {
        s += img.at(x, y)[ch] * (x + 0.5);
        w += img.at(x, y)[ch];
    }
    return w > 0 ? s / w : -1.0;
}

/// Twin of post_vignette.frag at pixel (x, y) of an n x n image (row 0 at the top).
glm::vec3 vignetteTwin(glm::vec3 colour, int x, int y, int n, const EffectInstance& e) {
    const glm::vec2 uv((x + 0.5f) / n, 1.0f - (y + 0.5f) / n);
    const glm::vec2 d =
        glm::abs(uv - glm::vec2(effectFloat(e, "centerX"), effectFloat(e, "centerY"))) * 2.0f;
    const float p = 8.0f + (2.0f - 8.0f) * effectFloat(e, "roundness");
    const float r =
        std::pow(std::pow(d.x, p) + std::pow(d.y, p), 1.0f / p) / std::pow(2.0f, 1.0f / p);
    const float e0 = 1.0f - effectFloat(e, "smoothness");
    const float t = std::clamp((r - e0) / (1.0f - e0), 0.0f, 1.0f);
    const float k = effectFloat(e, "intensity") * t * t * (3.0f - 2.0f * t);
    const auto col = e.params.at("color");
    const glm::vec3 tint(col[0], col[1], col[2]);
    return glm::mix(colour * (1.0f - k), glm::mix(colour, tint, k), effectFloat(e, "blend"));
}

} // namespace

class TestRenderPostGrading : public QObject {
    Q_OBJECT

    std::unique_ptr<render::PostChainRenderer> m_post;

    Image run(const PostChain& chain, const PostTestInput& in) {
        return runPostChain(*m_post, chain, in);
    }
    Image run(const PostChain& chain, const Image& color) {
        return runPostChain(*m_post, chain, color);
    }

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        m_post = std::make_unique<render::PostChainRenderer>();
    }
    void cleanupTestCase() { m_post.reset(); }

    // Every operator against its C++ twin on a ramp over 15 stops (grey and a saturated orange),
    // plus the known values the curves are defined by; output in [0, 1] and non-decreasing;
    // +1 EV of exposure equals doubling the input.
    void toneMappingOperatorsKnownAnswers() {
        const Image ramp = toneRamp();
        const char* names[] = {"pbr-neutral", "aces", "reinhard", "filmic", "agx", "linear"};
        for (int op = 0; op < 6; ++op) {
            const Image out = run(chainOf({fx("tonemap", {{"operator", {float(op)}}})}), ramp);
            float worst = 0;
            for (int y = 0; y < 2; ++y)
                for (int x = 0; x < kSize; ++x) {
                    const glm::vec3 want = toneCurve(op, rgbAt(ramp, x, y));
                    for (int k = 0; k < 3; ++k) {
                        const float got = out.at(x, y)[k];
                        QVERIFY2(got >= 0.0f && got <= 1.0f, names[op]);
                        worst = std::max(worst, std::abs(got - srgbEncode(want[k])));
                        // Monotonic on the grey ramp. (Not per channel on the orange row: AgX's
                        // outset matrix takes from red as green and blue rise towards white.)
                        if (x > 0 && y == 0)
                            QVERIFY2(got >= out.at(x - 1, y)[k] - 1e-4f,
                                     qPrintable(QString("%1 x=%2").arg(names[op]).arg(x)));
                    }
                }
            QVERIFY2(worst < 3e-3f, qPrintable(QString("%1: %2").arg(names[op]).arg(worst)));
            // Brighter in, brighter out over the ramp: the curve is not flat.
            QVERIFY2(out.at(kSize - 1, 0)[0] > out.at(0, 0)[0] + 0.5f, names[op]);

            // Exposure +1 EV equals a doubled input.
            Image doubled = ramp;
            for (size_t i = 0; i < doubled.pixels.size(); ++i)
                if (i % 4 != 3)
                    doubled.pixels[i] *= 2.0f;
            const Image exposed =
                run(chainOf({fx("tonemap", {{"operator", {float(op)}}, {"exposure", {1}}})}), ramp);
            const Image twice = run(chainOf({fx("tonemap", {{"operator", {float(op)}}})}), doubled);
            QVERIFY2(maxDiff(exposed, twice) < 2e-3f, names[op]);
        }
        auto decoded = [&](int op, int x) {
            return srgbDecode(
                run(chainOf({fx("tonemap", {{"operator", {float(op)}}})}), ramp).at(x, 0)[0]);
        };
        QVERIFY(std::abs(decoded(2, 32) - 0.5f) < 2e-3f); // Reinhard: 1 / (1 + 1)
        QVERIFY(std::abs(decoded(5, 28) - 0.5f) < 2e-3f); // linear: 2^-1 unchanged
        QVERIFY(decoded(5, 40) > 0.999f);                 // linear clamps 4 to 1
        // PBR Neutral below its knee (0.8 - 0.04): only the 0.04 offset, no compression.
        const Image neutral = run(chainOf({fx("tonemap", {{"operator", {0}}})}), ramp);
        int belowKnee = 0;
        for (int x = 0; x < kSize; ++x) {
            const float v = ramp.at(x, 0)[0];
            if (v >= 0.08f && v < 0.8f) {
                ++belowKnee;
                QVERIFY2(std::abs(srgbDecode(neutral.at(x, 0)[0]) - (v - 0.04f)) < 2e-3f,
                         qPrintable(QString::number(v)));
            }
        }
        QVERIFY(belowKnee >= 10);
        // Above the knee it compresses: 4 maps below 1 and below linear's clamp.
        QVERIFY(srgbDecode(neutral.at(40, 0)[0]) < 0.99f);
    }

    // Colour grading works in scene-linear (an HDR effect: the chain returns linear values).
    void colorGradingKnownAnswers() {
        const Image in = pattern();
        // Identity parameters change nothing.
        QVERIFY(maxDiff(run(chainOf({fx("color_grading")}), in), in) < 2e-3f);
        // Saturation 0: grey with the input's luminance.
        const Image grey = run(chainOf({fx("color_grading", {{"saturation", {0}}})}), in);
        for (int y = 0; y < kSize; y += 3)
            for (int x = 0; x < kSize; x += 3) {
                const float* p = grey.at(x, y);
                QVERIFY(std::abs(p[0] - p[1]) < 1e-3f && std::abs(p[1] - p[2]) < 1e-3f);
                QVERIFY(std::abs(p[0] - luma(in, x, y)) < 2e-3f);
            }
        auto one = [&](float v, std::map<std::string, std::vector<float>> params) {
            return rgbAt(run(chainOf({fx("color_grading", std::move(params))}), flat(v, 4)), 1, 1);
        };
        auto near = [](glm::vec3 a, glm::vec3 b) {
            return glm::all(glm::lessThan(glm::abs(a - b), glm::vec3(2e-3f) + 2e-3f * b));
        };
        // Contrast 2 around 18 % grey: 0.18 * (v / 0.18)^2.
        QVERIFY(near(one(0.5f, {{"contrast", {2}}}), glm::vec3(0.18f * std::pow(0.5f / 0.18f, 2))));
        QVERIFY(near(one(0.05f, {{"contrast", {2}}}), glm::vec3(0.05f * 0.05f / 0.18f)));
        QVERIFY(near(one(0.18f, {{"contrast", {2}}}), glm::vec3(0.18f)));
        // Lift adds to the shadows: v + lift (1 - v); gamma is a power 1/gamma; gain a scale.
        QVERIFY(near(one(0.2f, {{"lift", {0.1f, 0, 0}}}), glm::vec3(0.28f, 0.2f, 0.2f)));
        QVERIFY(near(one(0.25f, {{"gamma", {2, 1, 1}}}), glm::vec3(0.5f, 0.25f, 0.25f)));
        QVERIFY(near(one(0.2f, {{"gain", {1, 2, 1}}}), glm::vec3(0.2f, 0.4f, 0.2f)));
        QVERIFY(near(one(0.2f, {{"exposure", {1}}}), glm::vec3(0.4f)));
        // White balance keeps luminance: temperature +1 scales by (1.3, 1, 0.7), tint +1 by
        // (1, 0.7, 1), each divided by its luminance.
        const glm::vec3 warm(1.3f, 1.0f, 0.7f), magenta(1.0f, 0.7f, 1.0f);
        QVERIFY(near(one(0.2f, {{"temperature", {1}}}),
                     0.2f * warm / (0.2126f * warm.r + 0.7152f * warm.g + 0.0722f * warm.b)));
        QVERIFY(near(one(0.2f, {{"tint", {1}}}),
                     0.2f * magenta /
                         (0.2126f * magenta.r + 0.7152f * magenta.g + 0.0722f * magenta.b)));
        const glm::vec3 cool = one(0.2f, {{"temperature", {-1}}});
        QVERIFY(cool.b > cool.g && cool.g > cool.r); // blue (-)
    }

    // Film grain: zero-mean noise whose variance follows intensity^2 (uniform noise: 1/12, times
    // the midtone response), the same for a fixed time and new 24 times a second.
    void filmGrainStatistics() {
        const Image in = flat(0.5f);
        const EffectInstance linear = fx("tonemap", {{"operator", {5}}});
        const float encoded = srgbEncode(0.5f);
        const float response = 4.0f * encoded * (1.0f - encoded) + 0.1f;
        PostTestInput at;
        at.color = in;
        at.time = 2.0f;
        double previous = 0;
        for (float intensity : {0.1f, 0.2f, 0.4f}) {
            const PostChain chain =
                chainOf({linear, fx("film_grain", {{"intensity", {intensity}}, {"size", {1}}})});
            const Image out = run(chain, at);
            QVERIFY(std::abs(meanOf(out, 1) - encoded) < 0.01);
            const double variance = varianceOf(out, 1);
            const double expected = std::pow(intensity * response, 2) / 12.0;
            qInfo("grain %.1f: variance %.5f, expected %.5f", intensity, variance, expected);
            QVERIFY(std::abs(variance / expected - 1.0) < 0.2);
            QVERIFY(variance > previous * 3.0); // doubling intensity quadruples the variance
            previous = variance;
            QCOMPARE(maxDiff(run(chain, at), out), 0.0f);
            PostTestInput later = at;
            later.time = 2.5f;
            QVERIFY(maxDiff(run(chain, later), out) > 0.01f);
        }
    }

    // Chromatic aberration: red sampled outwards and blue inwards, `amount` px at the corners, so
    // thin vertical stripes split at the left and right and stay whole at the centre.
    void chromaticAberrationSplitsAtTheEdges() {
        Image in = flat(0.0f);
        for (int y = 0; y < kSize; ++y)
            for (int x : {8, 9, 31, 32, 54, 55})
                for (int k = 0; k < 3; ++k)
                    in.at(x, y)[k] = 1.0f;
        const Image out = run(chainOf({fx("chromatic_aberration", {{"amount", {4}}})}), in);
        const int row = kSize / 2;
        struct Window {
            int x0, x1;
            double split; ///< expected red centroid - blue centroid (px)
        };
        // offset(x) = (uv - 0.5) * 2 * 0.7071 * amount px; red shows at stripe - offset, blue at
        // stripe + offset.
        const double stripeOffset = (9.0 / kSize - 0.5) * 2 * 0.70710678 * 4;
        for (const Window w : {Window{0, 20, -2 * stripeOffset}, Window{20, 44, 0.0},
                               Window{44, 64, 2 * stripeOffset}}) {
            const double r = centroidX(out, 0, row, w.x0, w.x1),
                         g = centroidX(out, 1, row, w.x0, w.x1),
                         b = centroidX(out, 2, row, w.x0, w.x1);
            const double g0 = centroidX(in, 1, row, w.x0, w.x1);
            qInfo("aberration [%d, %d): red %.2f green %.2f blue %.2f", w.x0, w.x1, r, g, b);
            QVERIFY(std::abs(g - g0) < 0.05); // green never moves
            QVERIFY2(std::abs((r - b) - w.split) < 0.6,
                     qPrintable(QString("split %1, expected %2").arg(r - b).arg(w.split)));
        }
        QVERIFY(2 * stripeOffset < -3.0); // the left and right splits are really measurable
    }

    // Sharpen: c + amount (c - mean of the 4 neighbours), on display values after the implicit
    // tone map: flat input unchanged, an edge gains contrast by exactly that much.
    void sharpenKnownAnswer() {
        const EffectInstance linear = fx("tonemap", {{"operator", {5}}});
        const Image flatIn = flat(0.4f);
        QVERIFY(maxDiff(run(chainOf({linear, fx("sharpen", {{"amount", {1}}})}), flatIn),
                        run(chainOf({linear}), flatIn)) < 2e-3f);
        Image edge = flat(0.1f);
        for (int y = 0; y < kSize; ++y)
            for (int x = kSize / 2; x < kSize; ++x)
                for (int k = 0; k < 3; ++k)
                    edge.at(x, y)[k] = 0.6f;
        const Image t = run(chainOf({linear}), edge);
        const Image s = run(chainOf({linear, fx("sharpen", {{"amount", {1}}})}), edge);
        auto at = [&](int x, int y) {
            return t.at(std::clamp(x, 0, kSize - 1), std::clamp(y, 0, kSize - 1))[0];
        };
        for (int y = 0; y < kSize; y += 7)
            for (int x = 0; x < kSize; ++x) {
                const float mean =
                    0.25f * (at(x + 1, y) + at(x - 1, y) + at(x, y + 1) + at(x, y - 1));
                const float want = std::max(at(x, y) + (at(x, y) - mean), 0.0f);
                QVERIFY2(std::abs(s.at(x, y)[0] - want) < 2e-3f, qPrintable(QString::number(x)));
            }
        const int c = kSize / 2;
        QVERIFY(s.at(c, 5)[0] - s.at(c - 1, 5)[0] > 1.4f * (t.at(c, 5)[0] - t.at(c - 1, 5)[0]));
    }

    // FXAA: a hard aliased edge gets intermediate values along it; flat regions and a flat image
    // stay as they are.
    void fxaaSmoothsAliasedEdge() {
        const EffectInstance linear = fx("tonemap", {{"operator", {5}}});
        const PostChain chain = chainOf({linear, fx("fxaa")});
        const Image flatIn = flat(0.3f);
        QVERIFY(maxDiff(run(chain, flatIn), run(chainOf({linear}), flatIn)) < 1e-3f);
        Image edge = flat(0.0f); // a staircase of slope 1/2: white below the line y = x / 2
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                if (y > x / 2)
                    for (int k = 0; k < 3; ++k)
                        edge.at(x, y)[k] = 1.0f;
        const Image out = run(chain, edge);
        int intermediate = 0, farChanged = 0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const float v = out.at(x, y)[1];
                const int distance = std::abs(y - x / 2);
                if (distance <= 1 && v > 0.05f && v < 0.95f)
                    ++intermediate;
                if (distance >= 4 && std::abs(v - edge.at(x, y)[1]) > 1e-3f)
                    ++farChanged;
            }
        qInfo("fxaa: %d intermediate pixels along the edge", intermediate);
        QVERIFY(intermediate >= kSize / 2);
        QCOMPARE(farChanged, 0);
    }

    // Vignette against its twin for a moved centre, square and round shapes, narrow and wide
    // falloffs and a coloured border.
    void vignetteParametersMatchTwin() {
        const Image in = flat(0.6f);
        const EffectInstance linear = fx("tonemap", {{"operator", {5}}});
        const Image ref = run(chainOf({linear}), in);
        const glm::vec3 base = rgbAt(ref, 0, 0);
        const std::vector<std::map<std::string, std::vector<float>>> cases{
            {{"centerX", {0.25f}}, {"centerY", {0.7f}}},
            {{"roundness", {0}}, {"intensity", {0.8f}}},
            {{"smoothness", {0.1f}}, {"intensity", {0.8f}}},
            {{"smoothness", {1.0f}}, {"intensity", {0.8f}}},
            {{"blend", {1}}, {"color", {1, 0, 0}}, {"intensity", {1}}},
        };
        std::vector<Image> outs;
        for (const auto& params : cases) {
            const EffectInstance v = fx("vignette", params);
            const Image out = run(chainOf({linear, v}), in);
            float worst = 0;
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x)
                    worst = std::max(
                        worst, glm::length(rgbAt(out, x, y) - vignetteTwin(base, x, y, kSize, v)));
            QVERIFY2(worst < 3e-3f, qPrintable(QString::number(worst)));
            outs.push_back(out);
        }
        const int n = kSize - 1, c = kSize / 2;
        // Moved centre (left, upper): undarkened there, the far right darker than the far left.
        QVERIFY(std::abs(outs[0].at(16, 19)[0] - base.r) < 2e-3f);
        QVERIFY(outs[0].at(n, 19)[0] < outs[0].at(0, 19)[0] - 0.05f);
        QVERIFY(outs[0].at(16, n)[0] < outs[0].at(16, 0)[0] - 0.02f); // bottom darker than top
        // Square (roundness 0) darkens the middle of the edges more than round does.
        const Image round = run(chainOf({linear, fx("vignette", {{"intensity", {0.8f}}})}), in);
        QVERIFY(outs[1].at(n, c)[0] < round.at(n, c)[0] - 0.05f);
        // A wide falloff darkens the middle of the edges; a narrow one leaves them.
        QVERIFY(std::abs(outs[2].at(n, c)[0] - base.r) < 2e-3f);
        QVERIFY(outs[3].at(n, c)[0] < base.r - 0.1f);
        // Blend 1: the corners take the colour (their pixel centres sit just inside r = 1, where
        // the mask is 0.998), the centre keeps the image.
        for (auto [x, y] : {std::pair{0, 0}, {n, 0}, {0, n}, {n, n}})
            QVERIFY(glm::length(rgbAt(outs[4], x, y) - glm::vec3(1, 0, 0)) < 5e-3f);
        QVERIFY(glm::length(rgbAt(outs[4], c, c) - base) < 2e-3f);
    }
};

QTEST_GUILESS_MAIN(TestRenderPostGrading)
#include "test_render_post_grading.moc"
