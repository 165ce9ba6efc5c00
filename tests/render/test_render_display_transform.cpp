// The OpenColorIO display transform on the GPU (render/display_transform.h, issue 6): OCIO's own
// shader must give what OCIO's CPU processor gives, exposure must be a uniform, and a view is
// compiled once. What each case proves is stated on the case.
#include "core/color_management.h"
#include "core/post_chain.h"
#include "core/post_effects.h"
#include "core/tone_curves.h"
#include "post_test_harness.h"
#include "render/display_encoding.h"
#include "render/display_transform.h"
#include "render/offscreen.h"
#include "render/post_chain.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QtTest>
#include <algorithm>
#include <cmath>
#include <memory>

using namespace velvet;

namespace {

/// The tolerance: GPU and CPU agree within one 8-bit code.
constexpr float kTolerance = 1.0f / 255.0f;

std::shared_ptr<ColorManagement> shippedConfig() {
    static std::shared_ptr<ColorManagement> cm = [] {
        auto c = std::make_shared<ColorManagement>();
        std::string error;
        if (!c->loadFile(VELVET_SOURCE_DIR "/resources/ocio/config.ocio", &error))
            qFatal("%s", error.c_str());
        return c;
    }();
    return cm;
}

/// Rows of scene-linear ramps over 2^-10 .. 2^8 (shadows to far above white), 256 steps each:
/// grey, a warm tint, the three primaries, a saturated cyan; the first column is exact black.
Image hdrRamp() {
    const glm::vec3 tints[] = {{1, 1, 1}, {1, 0.6f, 0.2f}, {1, 0, 0},
                               {0, 1, 0}, {0, 0, 1},       {0.05f, 0.8f, 1.0f}};
    const int n = 256, rows = int(std::size(tints));
    Image img(n, rows, 4);
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < n; ++x) {
            const float v = x == 0 ? 0.0f : std::exp2(-10.0f + 18.0f * float(x) / float(n - 1));
            float* p = img.at(x, y);
            p[0] = v * tints[y].r, p[1] = v * tints[y].g, p[2] = v * tints[y].b, p[3] = 1.0f;
        }
    return img;
}

Image scaled(Image img, float factor) {
    for (size_t i = 0; i < img.pixels.size(); ++i)
        if (i % 4 != 3)
            img.pixels[i] *= factor;
    return img;
}

/// Largest channel difference over RGB after clamping both to [0, 1] (what a display stores).
float maxDifference(const Image& a, const Image& b, QString* where = nullptr) {
    float worst = 0.0f;
    if (where)
        *where = "every pixel (identical)";
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float d = std::abs(std::clamp(a.rgba(x, y)[c], 0.0f, 1.0f) -
                                         std::clamp(b.rgba(x, y)[c], 0.0f, 1.0f));
                if (d > worst) {
                    worst = d;
                    if (where)
                        *where = QString("pixel (%1, %2) channel %3: %4 vs %5")
                                     .arg(x)
                                     .arg(y)
                                     .arg(c)
                                     .arg(a.rgba(x, y)[c])
                                     .arg(b.rgba(x, y)[c]);
                }
            }
    return worst;
}

Image cpuDisplay(Image img, const DisplaySettings& s) {
    std::string error;
    if (!shippedConfig()->applyDisplay(img, s, &error))
        qFatal("CPU display transform: %s", error.c_str());
    return img;
}

/// Selects @p s (extracted with exposure 0, as the renderer does) and runs it over @p linear.
Image gpuDisplay(render::DisplayTransform& dt, const Image& linear, const DisplaySettings& s,
                 float exposureEv) {
    std::string error;
    DisplaySettings shaderSettings = s;
    shaderSettings.exposure = 0.0f;
    const auto transform = shippedConfig()->gpuDisplayTransform(shaderSettings, &error);
    if (!transform)
        qFatal("gpuDisplayTransform: %s", error.c_str());
    if (!dt.select(*transform, &error))
        qFatal("DisplayTransform::select: %s", error.c_str());
    Image out;
    if (!dt.apply(linear, exposureEv, out, &error))
        qFatal("DisplayTransform::apply: %s", error.c_str());
    return out;
}

/// Khronos PBR Neutral (Khronos Group 2024, "PBR Neutral" specification), the reference formula,
/// as the renderer's default built-in curve computes it, then clamped to [0, 1].
glm::vec3 pbrNeutral(glm::vec3 c) {
    return glm::clamp(tone::khronosPbrNeutral(glm::max(c, glm::vec3(0.0f))), 0.0f, 1.0f);
}

/// What the built-in path should show: @p curve on linear x 2^ev, then OCIO's CPU processor for
/// @p display's un-tone-mapped view ("Standard").
template <class Curve>
Image cpuBuiltIn(Image linear, float ev, const std::string& display, Curve curve) {
    for (int y = 0; y < linear.height; ++y)
        for (int x = 0; x < linear.width; ++x) {
            float* p = linear.at(x, y);
            const glm::vec3 t = curve(glm::vec3(p[0], p[1], p[2]) * std::exp2(ev));
            p[0] = t.r, p[1] = t.g, p[2] = t.b;
        }
    return cpuDisplay(linear, {display, "Standard", "", 0.0f});
}

/// Selects @p display's encoding in @p encoding (OCIO's shader for its un-tone-mapped view).
void selectEncoding(render::DisplayEncoding& encoding, const std::string& display) {
    std::string error;
    const auto t =
        shippedConfig()->gpuDisplayEncoding(display, &error, render::DisplayEncoding::options());
    if (!t)
        qFatal("gpuDisplayEncoding: %s", error.c_str());
    if (!encoding.select(*t, &error))
        qFatal("DisplayEncoding::select: %s", error.c_str());
}

} // namespace

class TestRenderDisplayTransform : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        QVERIFY(shippedConfig()->isLoaded());
    }

    // The acceptance test: OCIO's GLSL, uploaded by DisplayTransform, matches OCIO's CPU
    // processor on HDR ramps within 1/255, for every view of both displays and with a look.
    void gpuMatchesCpuOnRamp_data() {
        QTest::addColumn<QString>("display");
        QTest::addColumn<QString>("view");
        QTest::addColumn<QString>("look");
        for (const auto& display : shippedConfig()->displays())
            for (const auto& view : shippedConfig()->views(display))
                QTest::newRow(qPrintable(QString::fromStdString(display + " / " + view)))
                    << QString::fromStdString(display) << QString::fromStdString(view) << QString();
        QTest::newRow("sRGB / ACES + gamut compression") << "sRGB"
                                                         << "ACES"
                                                         << "ACES 1.3 Gamut Compression";
    }
    void gpuMatchesCpuOnRamp() {
        QFETCH(QString, display);
        QFETCH(QString, view);
        QFETCH(QString, look);
        const DisplaySettings s{display.toStdString(), view.toStdString(), look.toStdString(),
                                0.0f};
        render::DisplayTransform dt;
        const Image ramp = hdrRamp();
        const Image gpu = gpuDisplay(dt, ramp, s, 0.0f);
        const Image cpu = cpuDisplay(ramp, s);
        QString where;
        const float worst = maxDifference(gpu, cpu, &where);
        qInfo("%s / %s%s: max |GPU - CPU| = %.2e (%.4f/255) at %s", qPrintable(display),
              qPrintable(view), look.isEmpty() ? "" : qPrintable(" + " + look), double(worst),
              double(worst * 255.0f), qPrintable(where));
        QVERIFY2(worst <= kTolerance, qPrintable(where));
        QCOMPARE(dt.compileCount(), 1);
    }

    // Issue 6: linear 0.18 through the shipped sRGB Standard view is 8-bit code 118 (+-1), on the
    // GPU too (0.18 -> IEC 61966-2-1 sRGB = 0.4614).
    void middleGreyStandardIsCode118() {
        Image grey(1, 1, 4);
        grey.pixels = {0.18f, 0.18f, 0.18f, 1.0f};
        render::DisplayTransform dt;
        const Image out = gpuDisplay(dt, grey, {"sRGB", "Standard", "", 0.0f}, 0.0f);
        for (int c = 0; c < 3; ++c)
            QVERIFY2(std::abs(std::round(out.pixels[c] * 255.0f) - 118.0f) <= 1.0f,
                     qPrintable(QString::number(out.pixels[c] * 255.0f)));
    }

    // Exposure is OCIO's dynamic uniform: +1 EV through the uniform gives what the CPU processor
    // gives for twice the input, and changing it compiles nothing.
    void exposureIsAUniform_data() {
        QTest::addColumn<QString>("view");
        for (const char* v : {"Standard", "ACES", "AgX"})
            QTest::newRow(v) << v;
    }
    void exposureIsAUniform() {
        QFETCH(QString, view);
        const DisplaySettings s{"sRGB", view.toStdString(), "", 0.0f};
        render::DisplayTransform dt;
        const Image ramp = hdrRamp();
        const Image at0 = gpuDisplay(dt, ramp, s, 0.0f);
        const int compiles = dt.compileCount();
        QCOMPARE(compiles, 1);
        Image plusOne;
        std::string error;
        QVERIFY2(dt.apply(ramp, 1.0f, plusOne, &error), error.c_str());
        QCOMPARE(dt.compileCount(), compiles);
        const float worst = maxDifference(plusOne, cpuDisplay(scaled(ramp, 2.0f), s));
        qInfo("sRGB / %s, +1 EV uniform vs CPU of 2x input: max %.2e (%.4f/255)", qPrintable(view),
              double(worst), double(worst * 255.0f));
        QVERIFY(worst <= kTolerance);
        // And the uniform really moved the image (a stale uniform would pass the CPU check only if
        // the CPU were wrong too).
        QVERIFY(maxDifference(plusOne, at0) > 0.05f);
        // The CPU processor's own exposure agrees as well.
        QVERIFY(maxDifference(plusOne, cpuDisplay(ramp, {"sRGB", s.view, "", 1.0f})) <= kTolerance);
    }

    // Programs are cached by OCIO's cache id: a new view compiles exactly once, returning to a
    // view compiles nothing, and the cached program still computes the right thing.
    void viewSwitchCompilesOnce() {
        render::DisplayTransform dt;
        const Image ramp = hdrRamp();
        const DisplaySettings aces{"sRGB", "ACES", "", 0.0f}, agx{"sRGB", "AgX", "", 0.0f};
        gpuDisplay(dt, ramp, aces, 0.0f);
        QCOMPARE(dt.compileCount(), 1);
        const Image agxGpu = gpuDisplay(dt, ramp, agx, 0.0f);
        QCOMPARE(dt.compileCount(), 2);
        const Image acesAgain = gpuDisplay(dt, ramp, aces, 0.0f);
        QCOMPARE(dt.compileCount(), 2);
        QCOMPARE(dt.cachedProgramCount(), 2);
        QVERIFY(maxDifference(acesAgain, cpuDisplay(ramp, aces)) <= kTolerance);
        QVERIFY(maxDifference(agxGpu, cpuDisplay(ramp, agx)) <= kTolerance);
    }

    // The whole renderer: FrameSettings' display/view/look put OCIO's transform at the tone-mapping
    // stage. The displayed frame equals the CPU processor applied to the frame's own linear HDR
    // buffer (within 1/255 plus the RGBA8 target's rounding); exposure is a uniform; a view
    // compiles once; empty names keep the built-in tone mapper untouched.
    void rendererUsesOcioAtToneMappingStage() {
        constexpr int kSize = 64;
        render::Renderer r;
        std::string error;
        QVERIFY2(r.initialize(&error), error.c_str());
        r.setColorManagement(shippedConfig());
        r.setScene(test::shippedDefaultScene());
        r.finishEnvironment(); // a finished IBL bake, so frames differ only by the display
                               // transform
        render::OffscreenTarget target;
        QVERIFY2(target.resize(kSize, kSize, &error), error.c_str());
        render::FrameSettings fs;
        fs.width = fs.height = kSize;

        QVERIFY2(r.render(fs, target.framebuffer(), &error), error.c_str());
        const Image builtIn = r.readDisplay();
        const int baseCompiles = r.shaderCompileCount();

        auto check = [&](const char* what, float exposure) {
            const Image linear = r.readLinear();
            const Image display = r.readDisplay();
            const float worst = maxDifference(
                display, cpuDisplay(linear, {"sRGB", fs.displayView, fs.look, exposure}));
            qInfo("renderer, sRGB / %s at %+.0f EV (%s): max |frame - CPU(linear)| = %.4f/255",
                  fs.displayView.c_str(), double(exposure), what, double(worst * 255.0f));
            // 1/255 for the transform + half a code for the RGBA8 target's rounding.
            QVERIFY(worst <= 1.5f / 255.0f);
        };

        fs.displayView = "ACES"; // empty display: the config's default, sRGB
        QVERIFY2(r.render(fs, target.framebuffer(), &error), error.c_str());
        QCOMPARE(r.shaderCompileCount(), baseCompiles + 1);
        check("first frame", 0.0f);
        QVERIFY(maxDifference(r.readDisplay(), builtIn) > 0.02f); // not the built-in tone mapper

        fs.exposureEv = 1.0f;
        QVERIFY2(r.render(fs, target.framebuffer(), &error), error.c_str());
        QCOMPARE(r.shaderCompileCount(), baseCompiles + 1);
        check("exposure uniform", 1.0f);

        fs.displayView = "AgX";
        QVERIFY2(r.render(fs, target.framebuffer(), &error), error.c_str());
        QCOMPARE(r.shaderCompileCount(), baseCompiles + 2);
        check("new view", 1.0f);
        QVERIFY2(r.render(fs, target.framebuffer(), &error), error.c_str());
        fs.displayView = "ACES";
        QVERIFY2(r.render(fs, target.framebuffer(), &error), error.c_str());
        QCOMPARE(r.shaderCompileCount(), baseCompiles + 2);
        check("cached view", 1.0f);

        fs.look = "ACES Blue Light Fix";
        QVERIFY2(r.render(fs, target.framebuffer(), &error), error.c_str());
        QCOMPARE(r.shaderCompileCount(), baseCompiles + 3);
        check("look", 1.0f);

        // Back to no OCIO names: the built-in path, bit for bit, and nothing compiled.
        fs = {};
        fs.width = fs.height = kSize;
        QVERIFY2(r.render(fs, target.framebuffer(), &error), error.c_str());
        QCOMPARE(r.shaderCompileCount(), baseCompiles + 3);
        QCOMPARE(maxDifference(r.readDisplay(), builtIn), 0.0f);
    }

    // The built-in curves' display encoding is OCIO's shader: the chain's tone map with the
    // linear curve over ramps gives OCIO's CPU processor of the clamped values for the display's
    // Standard view within 1/255; Display P3 differs from sRGB as OCIO predicts; and for sRGB
    // OCIO agrees with the IEC 61966-2-1 OETF the renderer used before (goldens unchanged).
    void builtInCurveEncodedByOcioOnRamp_data() {
        QTest::addColumn<QString>("display");
        QTest::newRow("sRGB") << "sRGB";
        QTest::newRow("Display P3") << "Display P3";
    }
    void builtInCurveEncodedByOcioOnRamp() {
        QFETCH(QString, display);
        const Image ramp = scaled(hdrRamp(), 1.0f / 8.0f);
        render::DisplayEncoding encoding;
        selectEncoding(encoding, display.toStdString());
        QVERIFY(!encoding.isFallback());
        render::PostChainRenderer chain;
        PostChain c;
        c.effects.push_back(makeEffect("tonemap"));
        c.effects[0].params["operator"] = {5.0f}; // linear: clamp to [0, 1]
        test::PostTestInput in;
        in.color = ramp;
        in.encoding = &encoding;
        Image gpu;
        std::string error;
        QVERIFY2(test::applyPostChain(chain, c, in, gpu, &error), error.c_str());
        const auto clamp01 = [](glm::vec3 v) { return glm::clamp(v, 0.0f, 1.0f); };
        QString where;
        const float worst =
            maxDifference(gpu, cpuBuiltIn(ramp, 0.0f, display.toStdString(), clamp01), &where);
        qInfo("%s: max |GPU - OCIO CPU| = %.4f/255 at %s", qPrintable(display),
              double(worst * 255.0f), qPrintable(where));
        QVERIFY2(worst <= kTolerance, qPrintable(where));

        Image handWritten = ramp;
        for (float& v : handWritten.pixels)
            v = linearToSrgb(std::clamp(v, 0.0f, 1.0f));
        const float fromOetf = maxDifference(gpu, handWritten);
        if (display == "sRGB")
            QVERIFY2(fromOetf <= kTolerance, qPrintable(QString::number(fromOetf * 255.0f)));
        else
            QVERIFY2(fromOetf > 0.05f, "Display P3 must re-encode saturated colours");
    }

    // The renderer's own final pass: default settings (PBR Neutral, no OCIO names) show the
    // curve followed by OCIO's sRGB encoding; choosing Display P3 (its default view, Standard,
    // only encodes) keeps the curve and switches the encoding; exposure compiles nothing.
    void rendererBuiltInCurveEncodedByOcio() {
        constexpr int kSize = 64;
        render::Renderer r;
        std::string error;
        QVERIFY2(r.initialize(&error), error.c_str());
        r.setColorManagement(shippedConfig());
        r.setScene(test::shippedDefaultScene());
        r.finishEnvironment();
        render::OffscreenTarget target;
        QVERIFY2(target.resize(kSize, kSize, &error), error.c_str());
        render::FrameSettings fs;
        fs.width = fs.height = kSize;
        auto check = [&](const std::string& display, const char* what) {
            QVERIFY2(r.render(fs, target.framebuffer(), &error), error.c_str());
            const float worst = maxDifference(
                r.readDisplay(), cpuBuiltIn(r.readLinear(), fs.exposureEv, display, pbrNeutral));
            qInfo("renderer, PBR Neutral + %s encoding (%s): max |frame - CPU| = %.4f/255",
                  display.c_str(), what, double(worst * 255.0f));
            QVERIFY(worst <= 1.5f / 255.0f); // + half a code for the RGBA8 target
        };
        check("sRGB", "default settings");
        const Image srgbFrame = r.readDisplay();
        const int compiles = r.shaderCompileCount();
        fs.exposureEv = 1.5f;
        check("sRGB", "exposure");
        QCOMPARE(r.shaderCompileCount(), compiles);
        fs.exposureEv = 0.0f;
        fs.display = "Display P3";
        check("Display P3", "display chosen, default view");
        QVERIFY(maxDifference(r.readDisplay(), srgbFrame) > 0.5f / 255.0f);
        QCOMPARE(r.shaderCompileCount(), compiles + 1); // one tone-map program per encoding
        fs.exposureEv = -1.0f;
        check("Display P3", "exposure");
        QCOMPARE(r.shaderCompileCount(), compiles + 1);
    }

    // No OCIO config can be loaded at all: the renderer still draws, encoding with the
    // hand-written IEC 61966-2-1 OETF (and warns once on stderr); choosing a display then fails.
    void noConfigFallsBackToBuiltInOetf() {
        const QByteArray previous = qgetenv("OCIO");
        qputenv("OCIO", "/nonexistent/velvet-test.ocio");
        render::Renderer r;
        std::string error;
        const bool initialized = r.initialize(&error);
        render::OffscreenTarget target;
        render::FrameSettings fs;
        fs.width = fs.height = 32;
        bool rendered = initialized && target.resize(32, 32, &error) &&
                        r.render(fs, target.framebuffer(), &error);
        Image expected;
        if (rendered) {
            expected = r.readLinear();
            for (int y = 0; y < expected.height; ++y)
                for (int x = 0; x < expected.width; ++x) {
                    float* p = expected.at(x, y);
                    const glm::vec3 t = pbrNeutral({p[0], p[1], p[2]});
                    p[0] = linearToSrgb(t.r), p[1] = linearToSrgb(t.g), p[2] = linearToSrgb(t.b);
                }
        }
        const Image shown = rendered ? r.readDisplay() : Image();
        fs.display = "sRGB";
        const bool withDisplay = rendered && r.render(fs, target.framebuffer(), nullptr);
        if (previous.isNull())
            qunsetenv("OCIO");
        else
            qputenv("OCIO", previous);
        QVERIFY2(rendered, error.c_str());
        QVERIFY(maxDifference(shown, expected) <= 1.5f / 255.0f);
        QVERIFY(!withDisplay);
    }

    // An unknown name fails the frame before anything is drawn, with a message naming it.
    void unknownViewFailsTheFrame() {
        render::Renderer r;
        std::string error;
        QVERIFY2(r.initialize(&error), error.c_str());
        r.setColorManagement(shippedConfig());
        render::OffscreenTarget target;
        QVERIFY2(target.resize(8, 8, &error), error.c_str());
        render::FrameSettings fs;
        fs.width = fs.height = 8;
        fs.displayView = "Nope";
        QVERIFY(!r.render(fs, target.framebuffer(), &error));
        QVERIFY2(QString::fromStdString(error).contains("Nope"), error.c_str());
        fs.displayView = "Standard";
        fs.look = "No such look";
        QVERIFY(!r.render(fs, target.framebuffer(), &error));
        QVERIFY2(QString::fromStdString(error).contains("No such look"), error.c_str());
    }
};

QTEST_GUILESS_MAIN(TestRenderDisplayTransform)
#include "test_render_display_transform.moc"
