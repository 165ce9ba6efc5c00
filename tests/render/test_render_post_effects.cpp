// Each post effect's defining property on a small synthetic input (render/post_chain.h's apply
// runs the real chain on float textures), plus pooling, fusion, ordering and one golden per
// effect.
//
// Regenerating the goldens (only after a deliberate change, reviewed by eye):
//   VELVET_UPDATE_GOLDENS=1 ctest --test-dir build -R test_render_post_effects
// rewrites tests/render/golden/post_*.png; commit them.
#include "core/image.h"
#include "core/post_effects.h"
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
using render::PostTestInput;

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

} // namespace

class TestRenderPostEffects : public QObject {
    Q_OBJECT

    std::unique_ptr<render::PostChainRenderer> m_post;

    Image run(const PostChain& chain, const PostTestInput& in) {
        Image out;
        std::string error;
        if (!m_post->apply(chain, in, out, &error))
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
        const Image out = run(chainOf({fx("pixelate", {{"cellSize", {8}}})}), pattern());
        // Cells are aligned to the bottom-left (GL origin); 64 is a multiple of 8.
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                QVERIFY(maxDiff(out, out) == 0 &&
                        out.at(x, y)[0] == out.at(x / 8 * 8, y / 8 * 8)[0]);
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
        QVERIFY(std::abs(focused.at(c, c)[1] - in.color.at(c, c)[1]) < 1e-3f);
        QVERIFY(std::abs(focused.at(1, 1)[1] - in.color.at(1, 1)[1]) < 1e-3f ||
                in.depth.at(1, 1)[0] == 1.0f); // background is far: blurred, but uniform there
        const Image far = run(
            chainOf({fx("depth_of_field",
                        {{"focalDistance", {10.0f}}, {"focalRange", {0.3f}}, {"maxBlur", {8}}})}),
            in);
        QVERIFY(std::abs(far.at(c, c)[1] - in.color.at(c, c)[1]) > 0.01f);
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

    // One renderer class per catalogue effect; the pointwise ones are fusable, and every shader
    // their passes name ships.
    void everyEffectHasItsClass() {
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
