// Each post effect's defining property on a small synthetic input (post_test_harness.h
// runs the real chain on float textures), plus pooling, fusion, ordering and one golden per
// effect.
//
// Regenerating the goldens (only after a deliberate change, reviewed by eye):
//   VELVET_UPDATE_GOLDENS=1 ctest --test-dir build -R test_render_post_effects
// rewrites tests/render/golden/post_*.png; commit them.
#include "core/image.h"
#include "core/post_effects.h"
#include "core/tone_curves.h"
#include "post_test_harness.h"
#include "render/offscreen.h"
#include "render/post_chain.h"
#include "render/post_effect.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QtTest>
#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <set>

using namespace velvet;
using test::PostTestInput;

namespace {

constexpr int kSize = 64;

bool updateGoldens() {
    const char* v = std::getenv("VELVET_UPDATE_GOLDENS");
    return v && std::string(v) == "1";
}

PostChain chainOf(std::initializer_list<EffectInstance> effects) {
    PostChain c;
    c.effects = effects;
    return c;
}

EffectInstance fx(const char* type, std::map<std::string, std::vector<float>> params = {}) {
    EffectInstance e = makeEffect(type);
    for (auto& [k, v] : params)
        e.params[k] = v;
    return e;
}

/// A smooth gradient with a checker, values in [0.05, 0.95].
Image pattern(int n = kSize) {
    Image img(n, n, 4);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const float checker = ((x / 8 + y / 8) & 1) ? 0.3f : 0.0f;
            float* p = img.at(x, y);
            p[0] = 0.05f + 0.6f * float(x) / n + checker;
            p[1] = 0.05f + 0.6f * float(y) / n + checker * 0.5f;
            p[2] = 0.5f;
            p[3] = 1.0f;
        }
    return img;
}

Image flat(float v, int n = kSize) {
    Image img(n, n, 4);
    for (int i = 0; i < n * n; ++i) {
        img.pixels[size_t(i) * 4 + 0] = img.pixels[size_t(i) * 4 + 1] =
            img.pixels[size_t(i) * 4 + 2] = v;
        img.pixels[size_t(i) * 4 + 3] = 1.0f;
    }
    return img;
}

/// A lit sphere: camera at z = 3 looking at a unit sphere, a light from the upper left. Fills
/// colour, hardware depth, normals and matrices.
PostTestInput litSphere(int n = kSize) {
    PostTestInput in;
    in.color = Image(n, n, 4);
    in.depth = Image(n, n, 1);
    in.normals = Image(n, n, 3);
    const glm::mat4 proj = glm::perspective(glm::radians(45.0f), 1.0f, 0.1f, 20.0f);
    const glm::mat4 view = glm::lookAt(glm::vec3(0, 0, 3), glm::vec3(0), glm::vec3(0, 1, 0));
    in.proj = proj;
    in.viewProj = in.prevViewProj = proj * view;
    const glm::mat4 inv = glm::inverse(proj * view);
    const glm::vec3 light = glm::normalize(glm::vec3(-0.5f, 0.6f, 0.7f));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            // Row 0 is the top: NDC y = +1.
            const glm::vec2 ndc((x + 0.5f) / n * 2 - 1, 1 - (y + 0.5f) / n * 2);
            glm::vec4 a = inv * glm::vec4(ndc, -1, 1), b = inv * glm::vec4(ndc, 1, 1);
            const glm::vec3 o = glm::vec3(a) / a.w, d = glm::normalize(glm::vec3(b) / b.w - o);
            const float bq = glm::dot(o, d), c = glm::dot(o, o) - 1.0f, disc = bq * bq - c;
            float* col = in.color.at(x, y);
            col[3] = 1;
            if (disc < 0) {
                in.depth.at(x, y)[0] = 1.0f;
                col[0] = col[1] = col[2] = 0.05f;
                in.normals.at(x, y)[2] = 1;
                continue;
            }
            const glm::vec3 p = o + d * (-bq - std::sqrt(disc));
            const glm::vec3 nrm = glm::normalize(p);
            const glm::vec4 clip = proj * view * glm::vec4(p, 1);
            in.depth.at(x, y)[0] = clip.z / clip.w * 0.5f + 0.5f;
            const float lit = std::max(glm::dot(nrm, light), 0.0f) * 2.0f + 0.05f;
            col[0] = 0.8f * lit, col[1] = 0.5f * lit, col[2] = 0.3f * lit;
            for (int k = 0; k < 3; ++k)
                in.normals.at(x, y)[k] = nrm[k];
        }
    return in;
}

double meanOf(const Image& img, int channel) {
    double s = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            s += img.at(x, y)[channel];
    return s / (img.width * img.height);
}

double varianceOf(const Image& img, int channel) {
    const double m = meanOf(img, channel);
    double s = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            s += (img.at(x, y)[channel] - m) * (img.at(x, y)[channel] - m);
    return s / (img.width * img.height);
}

float maxDiff(const Image& a, const Image& b) {
    float d = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        if (i % 4 != 3)
            d = std::max(d, std::abs(a.pixels[i] - b.pixels[i]));
    return d;
}

float luma(const Image& img, int x, int y) {
    const float* p = img.at(x, y);
    return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
}

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

glm::vec3 rgbAt(const Image& img, int x, int y) {
    const float* p = img.at(x, y);
    return {p[0], p[1], p[2]};
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

class TestRenderPostEffects : public QObject {
    Q_OBJECT

    std::unique_ptr<render::PostChainRenderer> m_post;

    Image run(const PostChain& chain, const PostTestInput& in) {
        Image out;
        std::string error;
        if (!test::applyPostChain(*m_post, chain, in, out, &error))
            qFatal("post chain failed: %s", error.c_str());
        return out;
    }
    Image run(const PostChain& chain, const Image& color) {
        PostTestInput in;
        in.color = color;
        return run(chain, in);
    }

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        m_post = std::make_unique<render::PostChainRenderer>();
    }
    void cleanupTestCase() { m_post.reset(); }

    void gaussianWeightsMatchG() {
        for (float sigma : {0.8f, 2.0f, 5.0f}) {
            const int radius = int(std::ceil(3 * sigma));
            const auto w = render::gaussianWeights(sigma, radius);
            double sum = w[0];
            for (size_t i = 1; i < w.size(); ++i)
                sum += 2 * w[i];
            QVERIFY(std::abs(sum - 1.0) < 1e-6);
            // Proportional to G(x) = e^(-x^2/2s^2)/sqrt(2 pi s^2).
            const double g0 = 1.0 / std::sqrt(2 * M_PI * sigma * sigma);
            for (size_t i = 0; i < w.size(); ++i) {
                const double g = g0 * std::exp(-double(i * i) / (2.0 * sigma * sigma));
                QVERIFY(std::abs(w[i] / w[0] - g / g0) < 1e-5);
                QVERIFY(std::abs(w[i] - g) < 0.01 * g0 + 1e-6); // truncation loses < 1 %
            }
        }
    }

    void blurKeepsMeanLowersVariance() {
        const Image in = pattern();
        for (float sigma : {1.5f, 4.0f}) { // full and half resolution
            const Image out =
                run(chainOf({fx("gaussian_blur", {{"sigma", {sigma}}, {"radius", {12}}})}), in);
            for (int c = 0; c < 3; ++c) {
                const double m0 = meanOf(in, c), m1 = meanOf(out, c);
                QVERIFY2(std::abs(m1 - m0) <= 0.01 * m0, qPrintable(QString::number(m1 / m0)));
                if (c < 2)
                    QVERIFY(varianceOf(out, c) < varianceOf(in, c));
            }
        }
    }

    void vignetteDarkensCornersByIntensity() {
        const Image in = flat(0.8f);
        const Image out = run(chainOf({fx("vignette", {{"intensity", {0.4f}}})}), in);
        // An LDR effect: the chain tone maps implicitly first, so compare with the centre.
        const Image toneMapped = run(chainOf({fx("tonemap")}), in);
        const float centre = toneMapped.at(kSize / 2, kSize / 2)[0];
        const int n = kSize - 1;
        for (auto [x, y] : {std::pair{0, 0}, {n, 0}, {0, n}, {n, n}})
            QVERIFY2(std::abs(out.at(x, y)[0] / centre - 0.6f) < 0.01f,
                     qPrintable(QString::number(out.at(x, y)[0] / centre)));
        QVERIFY(std::abs(out.at(kSize / 2, kSize / 2)[0] - centre) < 1e-3f);
    }

    void pixelationMakesCellsConstant() {
        const Image in = pattern();
        const Image out = run(chainOf({fx("pixelate", {{"cellSize", {8}}})}), in);
        // Cells are aligned to the bottom-left (GL origin); 64 is a multiple of 8, so image rows
        // (row 0 at the top) split into the same cells. Each cell takes the input at its centre
        // texel (GL (x0 + 4, y0 + 4)), which is image pixel (x0 + 4, y0 + 3) from the top.
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const int rx = x / 8 * 8 + 4, ry = y / 8 * 8 + 3;
                for (int k = 0; k < 4; ++k) {
                    QCOMPARE(out.at(x, y)[k], out.at(rx, ry)[k]);
                    QVERIFY2(std::abs(out.at(x, y)[k] - in.at(rx, ry)[k]) < 1e-3f,
                             qPrintable(QString("%1,%2 channel %3").arg(x).arg(y).arg(k)));
                }
            }
        // Not the identity: the pattern's gradient varies inside a cell.
        QVERIFY(maxDiff(out, in) > 0.02f);
    }

    void toonLeavesAtMostNBands() {
        PostTestInput in = litSphere();
        const Image out = run(chainOf({fx("toon", {{"bands", {3}}, {"outline", {0}}})}), in);
        std::set<int> levels;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                if (in.depth.at(x, y)[0] < 1.0f)
                    levels.insert(int(std::lround(luma(out, x, y) * 200)));
        qInfo("toon: %zu luminance levels on the sphere", levels.size());
        QVERIFY(levels.size() <= 3 && levels.size() >= 2);
    }

    void bloomAddsLightOnlyAroundBrightPixels() {
        Image in = flat(0.2f);
        for (int k = 0; k < 3; ++k)
            in.at(12, 12)[k] = 50.0f;
        const EffectInstance bloom = fx(
            "bloom", {{"threshold", {1}}, {"knee", {0.1f}}, {"radius", {3}}, {"intensity", {1}}});
        const Image out = run(chainOf({bloom}), in);
        QVERIFY(out.at(14, 12)[0] > 0.2f + 1e-3f); // glow next to the bright pixel
        QVERIFY(out.at(20, 14)[0] > 0.2f + 1e-4f);
        QVERIFY(std::abs(out.at(56, 56)[0] - 0.2f) < 1e-3f); // nothing far away
        // Nothing above the threshold: nothing added anywhere.
        QVERIFY(maxDiff(run(chainOf({bloom}), flat(0.2f)), flat(0.2f)) < 1e-3f);
    }

    void motionBlurStillAndMoving() {
        PostTestInput in = litSphere();
        const PostChain chain = chainOf({fx("motion_blur", {{"samples", {8}}, {"strength", {1}}})});
        // Still camera: the input itself (within the half-float precision of the targets).
        QVERIFY(maxDiff(run(chain, in), in.color) < 2e-3f);
        // Camera moved sideways since the previous frame: a horizontal smear.
        const glm::mat4 view =
            glm::lookAt(glm::vec3(0.3f, 0, 3), glm::vec3(0.3f, 0, 0), glm::vec3(0, 1, 0));
        in.prevViewProj = in.proj * view;
        const Image out = run(chain, in);
        QVERIFY(maxDiff(out, in.color) > 0.05f);
        // Along a row through the sphere's edge the image changes; rows above the sphere (a
        // uniform background) stay the same.
        double rowChange = 0, colChange = 0;
        for (int x = 0; x < kSize; ++x)
            rowChange += std::abs(out.at(x, kSize / 2)[0] - in.color.at(x, kSize / 2)[0]);
        for (int x = 0; x < kSize; ++x)
            colChange += std::abs(out.at(x, 1)[0] - in.color.at(x, 1)[0]);
        QVERIFY(rowChange > 0.1 && colChange < 1e-3);
    }

    void dofKeepsFocalPlaneSharp() {
        PostTestInput in = litSphere();
        // Add texture so blur is visible.
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                if ((x + y) % 2)
                    in.color.at(x, y)[1] *= 0.5f;
        // The sphere's front is 2 m away; focus there, range 0.3 m.
        const Image focused = run(
            chainOf({fx("depth_of_field",
                        {{"focalDistance", {2.0f}}, {"focalRange", {0.3f}}, {"maxBlur", {8}}})}),
            in);
        const int c = kSize / 2;
        // Green variance of the checker over a block: a blur flattens it.
        auto blockVariance = [](const Image& img, int x0, int y0, int size) {
            double s = 0, s2 = 0;
            for (int y = y0; y < y0 + size; ++y)
                for (int x = x0; x < x0 + size; ++x)
                    s += img.at(x, y)[1], s2 += double(img.at(x, y)[1]) * img.at(x, y)[1];
            const double n = size * size, m = s / n;
            return s2 / n - m * m;
        };
        // In focus: the front of the sphere (2 m to 2.15 m) is exactly the input.
        for (int y = c - 4; y <= c + 4; y += 2)
            for (int x = c - 4; x <= c + 4; x += 2)
                QVERIFY2(std::abs(focused.at(x, y)[1] - in.color.at(x, y)[1]) < 1e-3f,
                         qPrintable(QString("%1,%2").arg(x).arg(y)));
        QVERIFY(blockVariance(focused, c - 4, c - 4, 8) >
                0.9 * blockVariance(in.color, c - 4, c - 4, 8));
        // The background (infinitely far) is out of focus: its checker is blurred away.
        const double bg = blockVariance(in.color, 0, 0, 6);
        QVERIFY(bg > 0);
        QVERIFY2(blockVariance(focused, 0, 0, 6) < 0.2 * bg,
                 qPrintable(QString::number(blockVariance(focused, 0, 0, 6) / bg)));
        const Image far = run(
            chainOf({fx("depth_of_field",
                        {{"focalDistance", {10.0f}}, {"focalRange", {0.3f}}, {"maxBlur", {8}}})}),
            in);
        QVERIFY(std::abs(far.at(c, c)[1] - in.color.at(c, c)[1]) > 0.01f);
        // Focused far behind it, the sphere is blurred: its checker variance drops.
        const double sphere = blockVariance(in.color, c - 4, c - 4, 8);
        QVERIFY2(blockVariance(far, c - 4, c - 4, 8) < 0.2 * sphere,
                 qPrintable(QString::number(blockVariance(far, c - 4, c - 4, 8) / sphere)));
    }

    // The blur grows with the circle of confusion: a plane 5 m away with a vertical step edge,
    // focused so that its CoC is 0.5 and then 1. At 0.5 the edge is blurred by half the radius
    // (no sharp half-step left, as a mix of sharp and full blur would leave), at 1 by the whole.
    void dofBlurGrowsWithCircleOfConfusion() {
        PostTestInput in;
        in.color = flat(0.1f);
        for (int y = 0; y < kSize; ++y)
            for (int x = kSize / 2; x < kSize; ++x)
                for (int k = 0; k < 3; ++k)
                    in.color.at(x, y)[k] = 0.9f;
        in.proj = glm::perspective(glm::radians(45.0f), 1.0f, 0.1f, 20.0f);
        const glm::vec4 clip = in.proj * glm::vec4(0, 0, -5.0f, 1);
        in.depth = Image(kSize, kSize, 1);
        for (float& d : in.depth.pixels)
            d = clip.z / clip.w * 0.5f + 0.5f;
        // halfRange 0.5 m: CoC = clamp((|5 - focus| - 0.5) / 0.5, 0, 1).
        auto edge = [&](float focus, float& maxJump) {
            const Image out = run(chainOf({fx("depth_of_field", {{"focalDistance", {focus}},
                                                                 {"focalRange", {1.0f}},
                                                                 {"maxBlur", {16}}})}),
                                  in);
            int width = 0; // pixels of the row between 10 % and 90 % of the step
            maxJump = 0;
            const int y = kSize / 2;
            for (int x = 0; x < kSize; ++x) {
                const float t = (out.at(x, y)[0] - 0.1f) / 0.8f;
                width += t > 0.1f && t < 0.9f;
                if (x > 0)
                    maxJump = std::max(maxJump, std::abs(out.at(x, y)[0] - out.at(x - 1, y)[0]));
            }
            return width;
        };
        float jumpSharp = 0, jumpHalf = 0, jumpFull = 0;
        const int sharp = edge(5.0f, jumpSharp), half = edge(4.25f, jumpHalf),
                  full = edge(3.0f, jumpFull);
        qInfo("dof edge width: %d px in focus, %d at CoC 0.5, %d at CoC 1 (max steps %.2f %.2f "
              "%.2f)",
              sharp, half, full, jumpSharp, jumpHalf, jumpFull);
        QCOMPARE(sharp, 0);
        QVERIFY(std::abs(jumpSharp - 0.8f) < 2e-3f);
        QVERIFY(jumpHalf < 0.3f * 0.8f); // blurred, not half sharp
        QVERIFY(half >= 3);
        QVERIFY(full > half * 3 / 2);
        QVERIFY(jumpFull < jumpHalf);
    }

    void nightVisionIsGreen() {
        const Image out = run(chainOf({fx("tonemap"), fx("night_vision")}), pattern());
        double r = 0, g = 0, b = 0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                r += out.at(x, y)[0], g += out.at(x, y)[1], b += out.at(x, y)[2];
                QVERIFY(out.at(x, y)[1] >= out.at(x, y)[0] && out.at(x, y)[1] >= out.at(x, y)[2]);
            }
        QVERIFY(g > 2 * r && g > 2 * b);
    }

    void vaporwaveChannelOffsetIsMeasurable() {
        Image in = flat(0.0f);
        for (int y = 0; y < kSize; ++y)
            for (int x = kSize / 2; x < kSize; ++x)
                for (int k = 0; k < 3; ++k)
                    in.at(x, y)[k] = 1.0f;
        const Image out = run(chainOf({fx("vaporwave", {{"aberration", {8}},
                                                        {"staticAmount", {0}},
                                                        {"scanlines", {0}},
                                                        {"desaturation", {0}},
                                                        {"tintAmount", {0}},
                                                        {"checkerSize", {0}}})}),
                              in);
        auto edge = [&](int ch) {
            for (int x = 0; x < kSize; ++x)
                if (out.at(x, 5)[ch] > 0.5f)
                    return x;
            return -1;
        };
        qInfo("vaporwave: red edge at %d, green edge at %d", edge(0), edge(1));
        QCOMPARE(edge(0), kSize / 2);
        QVERIFY(edge(0) - edge(1) >= 2); // green sampled 2 px to the right near the centre
    }

    void stylisedEffectsAreDeterministic() {
        const PostTestInput sphere = litSphere();
        for (const char* type : {"pointillism", "paintbrush"}) {
            PostTestInput in = sphere;
            in.time = 1.5f;
            const PostChain chain = chainOf({fx(type)});
            const Image a = run(chain, in), b = run(chain, in);
            QCOMPARE(maxDiff(a, b), 0.0f);
            QVERIFY(maxDiff(a, in.color) > 0.05f);
        }
        // Paintbrush strokes change over time (after a period), not between identical times.
        PostTestInput in = sphere;
        in.time = 0.5f;
        const Image t0 = run(chainOf({fx("paintbrush")}), in);
        in.time = 9.5f;
        QVERIFY(maxDiff(run(chainOf({fx("paintbrush")}), in), t0) > 0.01f);
    }

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

    // Motion blur follows the camera: a vertical move smears the sphere's top and bottom edges,
    // a horizontal one its left and right edges.
    void motionBlurDirection() {
        const PostChain chain = chainOf({fx("motion_blur", {{"samples", {8}}, {"strength", {1}}})});
        const float c = kSize / 2.0f, radius = 27.3f; // the sphere's outline (litSphere)
        auto sectorChange = [&](const Image& out, const Image& in, bool vertical) {
            double s = 0;
            int count = 0;
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x) {
                    const float dx = x + 0.5f - c, dy = y + 0.5f - c;
                    const float r = std::sqrt(dx * dx + dy * dy);
                    const bool inSector = vertical ? std::abs(dy) > 2 * std::abs(dx)
                                                   : std::abs(dx) > 2 * std::abs(dy);
                    if (std::abs(r - radius) < 4 && inSector) {
                        s += std::abs(out.at(x, y)[0] - in.at(x, y)[0]);
                        ++count;
                    }
                }
            return s / count;
        };
        for (bool verticalMove : {true, false}) {
            PostTestInput in = litSphere();
            const glm::vec3 shift = verticalMove ? glm::vec3(0, 0.3f, 0) : glm::vec3(0.3f, 0, 0);
            in.prevViewProj =
                in.proj * glm::lookAt(glm::vec3(0, 0, 3) + shift, shift, glm::vec3(0, 1, 0));
            const Image out = run(chain, in);
            const double along = sectorChange(out, in.color, verticalMove);
            const double across = sectorChange(out, in.color, !verticalMove);
            qInfo("motion blur %s: %.4f along the move, %.4f across",
                  verticalMove ? "vertical" : "horizontal", along, across);
            QVERIFY(along > 0.02);
            QVERIFY(along > 3 * across);
        }
    }

    // Toon outline: the sphere's silhouette takes the outline colour, its interior does not, the
    // background is left alone.
    void toonOutlineOnEdgesOnly() {
        const PostTestInput in = litSphere();
        const glm::vec3 magenta(1, 0, 1);
        const Image out =
            run(chainOf({fx("toon", {{"outline", {1}}, {"outlineColor", {1, 0, 1}}})}), in);
        int edges = 0;
        for (int y = 1; y < kSize - 1; ++y)
            for (int x = 1; x < kSize - 1; ++x) {
                const bool onSphere = in.depth.at(x, y)[0] < 1.0f;
                const float dx = x + 0.5f - kSize / 2.0f, dy = y + 0.5f - kSize / 2.0f;
                bool silhouette = false;
                for (auto [ox, oy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
                    silhouette |= in.depth.at(x + ox, y + oy)[0] >= 1.0f;
                const bool isMagenta = glm::length(rgbAt(out, x, y) - magenta) < 1e-3f;
                if (!onSphere) {
                    QVERIFY(glm::length(rgbAt(out, x, y) - rgbAt(in.color, x, y)) < 1e-3f);
                } else if (silhouette) {
                    ++edges;
                    QVERIFY2(isMagenta, qPrintable(QString("%1,%2").arg(x).arg(y)));
                } else if (std::sqrt(dx * dx + dy * dy) < 18.0f) {
                    QVERIFY2(!isMagenta, qPrintable(QString("%1,%2").arg(x).arg(y)));
                }
            }
        QVERIFY(edges > 50);
    }

    void orderMattersAndDisablingIsANoOp() {
        const Image in = pattern();
        const EffectInstance blur = fx("gaussian_blur", {{"sigma", {2}}, {"radius", {6}}});
        const EffectInstance pix = fx("pixelate", {{"cellSize", {8}}});
        const Image a = run(chainOf({blur, pix}), in), b = run(chainOf({pix, blur}), in);
        QVERIFY(maxDiff(a, b) > 0.01f);
        EffectInstance off = fx("vignette", {{"intensity", {1}}});
        off.enabled = false;
        const Image c = run(chainOf({blur, off, pix}), in);
        QCOMPARE(maxDiff(a, c), 0.0f);
    }

    // Frame blending: with frameBlend > 0 motion blur mixes in last frame's input, which the
    // chain keeps in a pooled target; at 0 (the default) nothing of the previous frame remains.
    void motionBlurBlendsThePreviousFrame() {
        const PostChain blend = chainOf({fx("motion_blur", {{"frameBlend", {0.5f}}})});
        PostTestInput a = litSphere(), b = litSphere();
        a.color = flat(0.2f);
        b.color = flat(0.6f);
        // First frame: no history yet; a still camera leaves the image as it is.
        QVERIFY(maxDiff(run(blend, a), a.color) < 2e-3f);
        const Image out = run(blend, b);
        for (const auto& [x, y] : {std::pair{0, 0}, {kSize / 2, kSize / 2}, {kSize - 1, 7}})
            QVERIFY(std::abs(out.at(x, y)[0] - 0.4f) < 2e-3f); // mix(0.6, 0.2, 0.5)
        // The history target is reused, not reallocated, frame after frame.
        const int allocated = m_post->textureAllocations();
        for (int i = 0; i < 20; ++i)
            run(blend, i % 2 ? a : b);
        QCOMPARE(m_post->textureAllocations(), allocated);
        // Without frame blending the previous frame plays no part.
        const PostChain plain = chainOf({fx("motion_blur")});
        run(plain, a);
        QVERIFY(maxDiff(run(plain, b), b.color) < 2e-3f);
    }

    // One renderer per catalogue effect (built from the entry, or the effect's own class); the
    // pointwise ones are fusable, and every shader their passes name ships.
    void everyEffectHasARenderer() {
        for (const EffectMeta& m : postEffectCatalogue()) {
            const std::string type(m.type);
            const std::unique_ptr<render::PostEffect> e = render::makePostEffect(m.type);
            QVERIFY2(e, type.c_str());
            QCOMPARE(e->meta().type, m.type);
            QCOMPARE(e->fusable() != nullptr, m.pointwise);
            std::vector<std::string> shaders;
            for (const render::PostPassInfo& p : e->passes())
                shaders.emplace_back(p.shader);
            if (e->fusable())
                shaders.push_back(e->fusable()->glslFile());
            QVERIFY2(!shaders.empty(), type.c_str());
            for (const std::string& f : shaders)
                QVERIFY2(std::filesystem::exists(std::string(VELVET_SOURCE_DIR) +
                                                 "/resources/shaders/" + f),
                         (type + ": " + f).c_str());
            QCOMPARE(e->readsPreviousFrame(fx(type.c_str(), {{"frameBlend", {0.5f}}})),
                     bool(m.reads & kReadsPreviousFrame));
        }
        QVERIFY(!render::makePostEffect("no_such_effect"));
    }

    void cheapLdrEffectsAreFused() {
        const PostChain chain =
            chainOf({fx("bloom"), fx("tonemap"), fx("vignette"), fx("film_grain"), fx("fxaa")});
        run(chain, pattern());
        QCOMPARE(m_post->lastStepCount(), 3); // bloom, tonemap+vignette+grain, fxaa
    }

    void textureCountIsFlat() {
        const PostChain chain = defaultPostChain();
        PostTestInput in = litSphere(32);
        run(chain, in);
        run(chain, in);
        const int allocated = m_post->textureAllocations();
        for (int i = 0; i < 100; ++i)
            run(chain, in);
        QCOMPARE(m_post->textureAllocations(), allocated);
        qInfo("pool: %d textures allocated, %d held", allocated, m_post->pooledTextures());
    }

    void everyEffectHasAGolden_data() {
        QTest::addColumn<QString>("type");
        for (const EffectMeta& m : postEffectCatalogue())
            QTest::newRow(std::string(m.type).c_str())
                << QString::fromUtf8(m.type.data(), int(m.type.size()));
    }
    void everyEffectHasAGolden() {
        QFETCH(QString, type);
        PostTestInput in = litSphere(48);
        in.time = 0.25f;
        PostChain chain;
        const EffectMeta* meta = findPostEffect(type.toStdString());
        if (meta->stage == PostStage::Ldr)
            chain.effects.push_back(fx("tonemap"));
        chain.effects.push_back(fx(type.toStdString().c_str()));
        // Effects whose defaults change nothing on this input get parameters (or a camera move)
        // that show them; otherwise their golden would equal post_tonemap.png.
        if (type == "color_grading")
            chain.effects.back() = fx("color_grading", {{"contrast", {1.4f}},
                                                        {"saturation", {1.6f}},
                                                        {"temperature", {0.5f}},
                                                        {"lift", {0.0f, 0.02f, 0.06f}},
                                                        {"gain", {1.2f, 1.0f, 0.9f}}});
        if (type == "motion_blur") // the camera was 0.4 m to the right and 0.2 m lower
            in.prevViewProj = in.proj * glm::lookAt(glm::vec3(0.4f, -0.2f, 3),
                                                    glm::vec3(0.4f, -0.2f, 0), glm::vec3(0, 1, 0));
        if (meta->stage != PostStage::Ldr && type != "tonemap")
            chain.effects.push_back(fx("tonemap"));
        const Image out = run(chain, in);
        const std::string file = std::string(VELVET_SOURCE_DIR) + "/tests/render/golden/post_" +
                                 meta->type.data() + ".png";
        std::string error;
        if (updateGoldens()) {
            QVERIFY2(writeImage(file, out, PixelFormat::UInt8, &error), error.c_str());
            return;
        }
        Image golden;
        QVERIFY2(readImage(file, golden, &error), error.c_str());
        QCOMPARE(golden.width, out.width);
        int differing = 0;
        for (int y = 0; y < out.height; ++y)
            for (int x = 0; x < out.width; ++x) {
                float d = 0;
                for (int k = 0; k < 3; ++k)
                    d = std::max(
                        d, std::abs(std::round(golden.at(x, y)[k] * 255.0f) -
                                    std::round(std::clamp(out.at(x, y)[k], 0.0f, 1.0f) * 255.0f)));
                differing += d > 5.0f;
            }
        QVERIFY2(differing <= out.width * out.height / 1000,
                 qPrintable(QString("%1 pixels differ from %2").arg(differing).arg(file.c_str())));
    }

    // The renderer runs scene.post: an empty chain leaves the image exactly as before, a tone
    // mapping chain replaces the final pass.
    void rendererRunsSceneChain() {
        Scene scene = test::shippedDefaultScene();
        scene.post = {};
        render::FrameSettings fs;
        fs.width = fs.height = 48;
        Image plain, chained;
        std::string error;
        QVERIFY2(render::renderSceneOffscreen(scene, fs, nullptr, &plain, &error), error.c_str());
        scene.post = defaultPostChain();
        QVERIFY2(render::renderSceneOffscreen(scene, fs, nullptr, &chained, &error), error.c_str());
        QVERIFY(maxDiff(plain, chained) > 0.02f);
        // Disabled effects only: identical to no chain.
        for (auto& e : scene.post.effects)
            e.enabled = false;
        Image disabled;
        QVERIFY2(render::renderSceneOffscreen(scene, fs, nullptr, &disabled, &error),
                 error.c_str());
        QCOMPARE(maxDiff(plain, disabled), 0.0f);
    }
};

QTEST_GUILESS_MAIN(TestRenderPostEffects)
#include "test_render_post_effects.moc"
