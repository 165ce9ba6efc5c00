// Each spatial post effect's defining property on a small synthetic input (post_test_harness.h
// runs the real chain on float textures; the colour effects against their twins are
// test_render_post_grading's), plus pooling, fusion, ordering and one golden per effect.
//
// Regenerating the goldens (only after a deliberate change, reviewed by eye):
//   VELVET_UPDATE_GOLDENS=1 ctest --test-dir build -R test_render_post_effects
// rewrites tests/render/golden/post_*.png; commit them.
#include "core/image.h"
#include "core/post_effects.h"
#include "post_effect_inputs.h"
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
using namespace velvet::test;

class TestRenderPostEffects : public QObject {
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
