// Colour management (core/color_management.h, resources/ocio/config.ocio): the shipped config loads
// and offers what docs/color-management.md promises; known answers for the sRGB curve
// (IEC 61966-2-1), the Standard view and texture decoding; Raw is identity; $OCIO overrides the
// shipped config; a broken config is reported with its file name; the GPU display transform is
// complete data; exposure is a scene-linear multiplication by 2^EV.
#include "core/color_management.h"
#include "core/image.h"
#include "core/tone_curves.h"

#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

using namespace velvet;

namespace {

bool contains(const std::vector<std::string>& list, const std::string& item) {
    return std::find(list.begin(), list.end(), item) != list.end();
}

std::string shippedConfig() {
    return VELVET_SOURCE_DIR "/resources/ocio/config.ocio";
}

/// Sets or unsets $OCIO for the lifetime of the guard, restoring the previous value.
class OcioEnvGuard {
public:
    explicit OcioEnvGuard(const QByteArray* value)
        : m_had(qEnvironmentVariableIsSet("OCIO")), m_old(qgetenv("OCIO")) {
        if (value)
            qputenv("OCIO", *value);
        else
            qunsetenv("OCIO");
    }
    ~OcioEnvGuard() {
        if (m_had)
            qputenv("OCIO", m_old);
        else
            qunsetenv("OCIO");
    }

private:
    bool m_had;
    QByteArray m_old;
};

void writeFile(const QString& path, const std::string& text) {
    std::ofstream f(path.toStdString(), std::ios::binary);
    f << text;
}

} // namespace

class TestCoreColor : public QObject {
    Q_OBJECT

    ColorManagement m_cm;

    std::array<float, 3> display(std::array<float, 3> rgb, const DisplaySettings& s) {
        std::string error;
        if (!m_cm.applyDisplay(rgb.data(), s, &error))
            qWarning("%s", error.c_str());
        return rgb;
    }

private slots:
    // Khronos PBR Neutral (core/tone_curves.h), the twin the render and CLI tests compare the
    // GPU's default curve with: worked by hand from the specification's formula.
    void pbrNeutralKnownAnswers() {
        const auto near = [](glm::vec3 a, glm::vec3 b) {
            return glm::all(glm::lessThan(glm::abs(a - b), glm::vec3(1e-5f)));
        };
        // Below the compression start only the toe's offset applies: 0.04 above x = 0.08 ...
        QVERIFY(near(tone::khronosPbrNeutral(glm::vec3(0.5f)), glm::vec3(0.46f)));
        // ... and x - 6.25 x^2 below it (x = 0.02: 0.0175 off).
        QVERIFY(near(tone::khronosPbrNeutral(glm::vec3(0.02f)), glm::vec3(0.0025f)));
        // White: 0.96 compressed to 1 - 0.24^2 / 0.44, grey stays grey.
        QVERIFY(near(tone::khronosPbrNeutral(glm::vec3(1.0f)), glm::vec3(1.0f - 0.0576f / 0.44f)));
        // Bright colours approach 1 at their peak and never pass it; hue order is kept.
        const glm::vec3 hot = tone::khronosPbrNeutral({40.0f, 10.0f, 2.0f});
        QVERIFY(hot.r < 1.0f && hot.r > 0.99f);
        QVERIFY(hot.r > hot.g && hot.g > hot.b);
    }
    void initTestCase() {
        OcioEnvGuard noOcio(nullptr); // the shipped config, whatever the developer's shell says
        std::string error;
        QVERIFY2(m_cm.loadDefault(&error), error.c_str());
        QVERIFY(m_cm.isLoaded());
    }

    void srgbHelpersFollowIec61966() {
        // Known values: 0.5 encoded -> 0.214041 linear; linear 0.18 -> 0.461356 encoded.
        QVERIFY(std::fabs(srgbToLinear(0.5f) - 0.214041f) < 1e-5f);
        QVERIFY(std::fabs(linearToSrgb(0.18f) - 0.461356f) < 1e-5f);
        // The linear segment: 0.04045 / 12.92 and 0.0031308 * 12.92.
        QVERIFY(std::fabs(srgbToLinear(0.04045f) - 0.04045f / 12.92f) < 1e-7f);
        QVERIFY(std::fabs(linearToSrgb(0.002f) - 0.002f * 12.92f) < 1e-7f);
        QCOMPARE(srgbToLinear(0.0f), 0.0f);
        QVERIFY(std::fabs(srgbToLinear(1.0f) - 1.0f) < 1e-6f);
        QVERIFY(std::fabs(srgbToLinear(-0.5f) + srgbToLinear(0.5f)) < 1e-7f); // odd extension
        for (int i = 0; i <= 255; ++i) {
            const float v = i / 255.0f;
            QVERIFY(std::fabs(linearToSrgb(srgbToLinear(v)) - v) < 1e-5f);
        }
    }

    void shippedConfigHasRequiredContents() {
        const auto spaces = m_cm.colorSpaces();
        for (const char* cs : {"Linear Rec.709", "sRGB texture", "ACEScg", "ACES2065-1", "Raw"})
            QVERIFY2(contains(spaces, cs), cs);
        const auto displays = m_cm.displays();
        QVERIFY(contains(displays, "sRGB"));
        QVERIFY(contains(displays, "Display P3"));
        QCOMPARE(m_cm.defaultDisplay(), std::string("sRGB"));
        QCOMPARE(m_cm.defaultView("sRGB"), std::string("Standard"));
        for (const std::string& d : {std::string("sRGB"), std::string("Display P3")})
            for (const char* v : {"Standard", "ACES", "AgX", "Raw"})
                QVERIFY2(contains(m_cm.views(d), v), (d + " / " + v).c_str());
        QCOMPARE(m_cm.roleColorSpace("scene_linear"), std::string("Linear Rec.709"));
        QCOMPARE(m_cm.roleColorSpace("data"), std::string("Raw"));
        QCOMPARE(m_cm.roleColorSpace("color_picking"), std::string("sRGB texture"));
        QCOMPARE(m_cm.roleColorSpace("texture_paint"), std::string("sRGB texture"));
        QVERIFY(!m_cm.roleColorSpace("default").empty());
        QVERIFY(m_cm.isData("Raw"));
        QVERIFY(!m_cm.isData("sRGB texture"));
        QCOMPARE(m_cm.canonicalColorSpace("lin_rec709"), std::string("Linear Rec.709"));
        QVERIFY(contains(m_cm.looks(), "ACES 1.3 Gamut Compression"));
        QCOMPARE(m_cm.colorSpaceForFile("sky.EXR"), std::string("Linear Rec.709"));
        QCOMPARE(m_cm.colorSpaceForFile("albedo.png"), std::string("sRGB texture"));
    }

    void midGreyThroughStandardIsCode118() {
        // 0.18 -> sRGB 0.4614 -> 0.4614 * 255 = 117.6 -> code 118.
        for (const char* d : {"sRGB", "Display P3"}) { // a neutral is the same on both
            const auto out = display({0.18f, 0.18f, 0.18f}, {d, "Standard", "", 0.0f});
            for (float c : out) {
                const int code = int(std::lround(c * 255.0f));
                QVERIFY2(std::abs(code - 118) <= 1, qPrintable(QString("%1: %2").arg(d).arg(c)));
                QVERIFY(std::fabs(c - linearToSrgb(0.18f)) < 1e-4f);
            }
        }
        // Empty names are the defaults (sRGB, Standard); the Image path agrees with one pixel.
        Image img(2, 1, 4);
        for (int i = 0; i < 4; ++i)
            img.pixels[i] = img.pixels[4 + i] = i == 3 ? 0.5f : 0.18f;
        std::string error;
        QVERIFY2(m_cm.applyDisplay(img, {}, &error), error.c_str());
        QVERIFY(std::fabs(img.pixels[0] - linearToSrgb(0.18f)) < 1e-4f);
        QCOMPARE(img.pixels[3], 0.5f); // alpha untouched
    }

    void displayP3StandardIsColorimetric() {
        // Pure Rec.709 red in P3-D65 linear is (0.822462, 0.033194, 0.017083), then sRGB-encoded.
        const auto out = display({1.0f, 0.0f, 0.0f}, {"Display P3", "Standard", "", 0.0f});
        QVERIFY(std::fabs(out[0] - linearToSrgb(0.822462f)) < 1e-3f);
        QVERIFY(std::fabs(out[1] - linearToSrgb(0.033194f)) < 1e-3f);
        QVERIFY(std::fabs(out[2] - linearToSrgb(0.017083f)) < 1e-3f);
    }

    void srgbTextureDecodesToLinear() {
        Image img(2, 1, 4);
        const float in[8] = {0.5f, 0.5f, 0.5f, 0.25f, 0.0f, 1.0f, 0.04f, 1.0f};
        std::copy(in, in + 8, img.pixels.begin());
        std::string error;
        QVERIFY2(m_cm.toSceneLinear(img, "sRGB texture", &error), error.c_str());
        for (int c = 0; c < 3; ++c)
            QVERIFY2(std::fabs(img.pixels[c] - 0.2140f) < 1e-4f,
                     qPrintable(QString::number(img.pixels[c])));
        QCOMPARE(img.pixels[3], 0.25f);
        QVERIFY(std::fabs(img.pixels[4]) < 1e-6f);
        QVERIFY(std::fabs(img.pixels[5] - 1.0f) < 1e-5f);
        QVERIFY(std::fabs(img.pixels[6] - 0.04f / 12.92f) < 1e-5f);
        // Grey images (one channel) convert as RRR.
        Image grey(1, 1, 1);
        grey.pixels[0] = 0.5f;
        QVERIFY2(m_cm.toSceneLinear(grey, "sRGB texture", &error), error.c_str());
        QVERIFY(std::fabs(grey.pixels[0] - 0.2140f) < 1e-4f);
    }

    void acesWhiteIsWhite() {
        // ACES2065-1 and ACEScg (D60 white) reach Rec.709 through a Bradford adaptation, which
        // maps equal-energy RGB white to D65 white: (1, 1, 1) stays (1, 1, 1).
        for (const char* cs : {"ACES2065-1", "ACEScg"}) {
            Image img(1, 1, 3);
            std::fill(img.pixels.begin(), img.pixels.end(), 1.0f);
            std::string error;
            QVERIFY2(m_cm.toSceneLinear(img, cs, &error), error.c_str());
            for (float v : img.pixels)
                QVERIFY2(std::fabs(v - 1.0f) < 2e-3f, qPrintable(QString("%1: %2").arg(cs).arg(v)));
        }
    }

    void rawIsIdentity() {
        const std::array<float, 3> in = {-0.25f, 0.18f, 7.5f};
        for (const char* d : {"sRGB", "Display P3"})
            QCOMPARE(display(in, {d, "Raw", "", 0.0f}), in);
        Image img(1, 1, 3);
        std::copy(in.begin(), in.end(), img.pixels.begin());
        std::string error;
        QVERIFY2(m_cm.toSceneLinear(img, "Raw", &error), error.c_str());
        QCOMPARE(img.pixels[0], in[0]);
        QCOMPARE(img.pixels[1], in[1]);
        QCOMPARE(img.pixels[2], in[2]);
    }

    void tonemappedViewsAreSane() {
        // ACES and AgX compress highlights: 16x mid grey stays below display white, and a ramp
        // stays monotonic.
        for (const char* v : {"ACES", "AgX"}) {
            float previous = -1.0f;
            for (float x = 0.001f; x < 100.0f; x *= 1.5f) {
                const float y = display({x, x, x}, {"sRGB", v, "", 0.0f})[1];
                QVERIFY2(y >= previous - 1e-6f, qPrintable(QString("%1 at %2").arg(v).arg(x)));
                previous = y;
            }
            const float bright = display({2.88f, 2.88f, 2.88f}, {"sRGB", v, "", 0.0f})[1];
            QVERIFY2(bright < 1.0f && bright > 0.7f,
                     qPrintable(QString("%1: %2").arg(v).arg(bright)));
        }
    }

    void exposureDoublesTheLinearInput() {
        for (const char* v : {"Standard", "ACES", "AgX"}) {
            for (float x : {0.01f, 0.09f, 0.18f, 0.4f}) {
                const auto plusOne = display({x, x * 0.5f, x * 0.25f}, {"sRGB", v, "", 1.0f});
                const auto doubled = display({2 * x, x, x * 0.5f}, {"sRGB", v, "", 0.0f});
                for (int c = 0; c < 3; ++c)
                    QVERIFY2(std::fabs(plusOne[c] - doubled[c]) < 1e-5f,
                             qPrintable(QString("%1 %2: %3 vs %4")
                                            .arg(v)
                                            .arg(x)
                                            .arg(plusOne[c])
                                            .arg(doubled[c])));
            }
        }
    }

    void lookIsApplied() {
        // The ACES 1.3 gamut compression only moves colours near or outside the AP1 boundary.
        const std::array<float, 3> grey = {0.18f, 0.18f, 0.18f};
        const DisplaySettings plain{"sRGB", "ACES", "", 0.0f};
        const DisplaySettings look{"sRGB", "ACES", "ACES 1.3 Gamut Compression", 0.0f};
        const auto a = display(grey, plain), b = display(grey, look);
        for (int c = 0; c < 3; ++c)
            QVERIFY(std::fabs(a[c] - b[c]) < 1e-4f);
        const std::array<float, 3> saturated = {0.0f, 0.0f, 1.0f};
        QVERIFY(display(saturated, plain) != display(saturated, look));
    }

    void unknownNamesAreReported() {
        std::array<float, 3> rgb = {0.18f, 0.18f, 0.18f};
        std::string error;
        QVERIFY(!m_cm.applyDisplay(rgb.data(), {"Cinema 9000", "", "", 0.0f}, &error));
        QVERIFY2(error.find("Cinema 9000") != std::string::npos, error.c_str());
        QVERIFY(!m_cm.applyDisplay(rgb.data(), {"sRGB", "Vivid", "", 0.0f}, &error));
        QVERIFY2(error.find("Vivid") != std::string::npos, error.c_str());
        QVERIFY(!m_cm.applyDisplay(rgb.data(), {"sRGB", "Standard", "Nope", 0.0f}, &error));
        QVERIFY2(error.find("Nope") != std::string::npos, error.c_str());
        Image img(1, 1, 3);
        QVERIFY(!m_cm.toSceneLinear(img, "Kodachrome", &error));
        QVERIFY2(error.find("Kodachrome") != std::string::npos, error.c_str());
        QVERIFY2(error.find("config.ocio") != std::string::npos, error.c_str());
    }

    void ocioEnvironmentVariableOverrides() {
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        const QString path = dir.filePath("tiny.ocio");
        writeFile(path, R"(ocio_profile_version: 2
roles:
  default: Tiny Linear
  scene_linear: Tiny Linear
  data: Tiny Linear
displays:
  Tiny Display:
    - !<View> {name: Tiny View, colorspace: Tiny Linear}
colorspaces:
  - !<ColorSpace>
    name: Tiny Linear
    isdata: false
)");
        const QByteArray value = path.toLocal8Bit();
        OcioEnvGuard env(&value);
        QCOMPARE(ColorManagement::defaultConfigPath().string(), path.toStdString());
        ColorManagement cm;
        std::string error;
        QVERIFY2(cm.loadDefault(&error), error.c_str());
        QCOMPARE(cm.configPath().string(), path.toStdString());
        QVERIFY(contains(cm.colorSpaces(), "Tiny Linear"));
        QVERIFY(!contains(cm.colorSpaces(), "ACEScg"));
        QCOMPARE(cm.displays(), std::vector<std::string>{"Tiny Display"});
        // An empty $OCIO means "not set".
        const QByteArray empty;
        OcioEnvGuard unset(&empty);
        QVERIFY(ColorManagement::defaultConfigPath().string().ends_with("ocio/config.ocio"));
    }

    void everyViewWithTheDefaultViewTransformEncodes() {
        // Two views share the default view transform; encodingView() names the first, but the
        // second encodes too (the renderer's built-in curve runs before it). "Film" has another
        // view transform and "Raw" none: both are OCIO's alone.
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        const QString path = dir.filePath("two-encoding-views.ocio");
        writeFile(path, R"(ocio_profile_version: 2
roles:
  default: Linear
  scene_linear: Linear
  data: Linear
displays:
  Screen:
    - !<View> {name: Standard, view_transform: Plain, display_colorspace: Screen Space}
    - !<View> {name: Standard Copy, view_transform: Plain, display_colorspace: Screen Space}
    - !<View> {name: Film, view_transform: Filmic, display_colorspace: Screen Space}
    - !<View> {name: Raw, colorspace: Linear}
default_view_transform: Plain
view_transforms:
  - !<ViewTransform>
    name: Plain
    from_scene_reference: !<MatrixTransform> {}
  - !<ViewTransform>
    name: Filmic
    from_scene_reference: !<ExponentTransform> {value: [0.5, 0.5, 0.5, 1]}
display_colorspaces:
  - !<ColorSpace>
    name: Screen Space
colorspaces:
  - !<ColorSpace>
    name: Linear
)");
        ColorManagement cm;
        std::string error;
        QVERIFY2(cm.loadFile(path.toStdString(), &error), error.c_str());
        QCOMPARE(cm.encodingView("Screen"), std::string("Standard"));
        QCOMPARE(cm.isEncodingView("Screen", "Standard", &error), std::optional<bool>(true));
        QCOMPARE(cm.isEncodingView("Screen", "Standard Copy", &error), std::optional<bool>(true));
        QCOMPARE(cm.isEncodingView("Screen", "Film", &error), std::optional<bool>(false));
        QCOMPARE(cm.isEncodingView("Screen", "Raw", &error), std::optional<bool>(false));
        QCOMPARE(cm.isEncodingView("", "", &error), std::optional<bool>(true)); // the defaults
        QCOMPARE(cm.isEncodingView("Screen", "Nope", &error), std::optional<bool>());
        QVERIFY2(error.find("Nope") != std::string::npos, error.c_str());
    }

    void brokenConfigNamesTheFile() {
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        const QString path = dir.filePath("broken.ocio");
        writeFile(path, "ocio_profile_version: 2\ncolorspaces: [this is not {a colour space\n");
        ColorManagement cm;
        std::string error;
        QVERIFY(!cm.loadFile(path.toStdString(), &error));
        QVERIFY(!cm.isLoaded());
        QVERIFY2(error.find(path.toStdString()) != std::string::npos, error.c_str());
        // A config that parses but references an unknown colour space fails validation.
        writeFile(path, "ocio_profile_version: 2\nroles:\n  scene_linear: Missing\n"
                        "colorspaces:\n  - !<ColorSpace>\n    name: A\n");
        QVERIFY(!cm.loadFile(path.toStdString(), &error));
        QVERIFY2(error.find(path.toStdString()) != std::string::npos, error.c_str());
        // A missing file too; a failed load keeps the config that was loaded before.
        QVERIFY(!m_cm.loadFile(dir.filePath("nowhere.ocio").toStdString(), &error));
        QVERIFY2(error.find("nowhere.ocio") != std::string::npos, error.c_str());
        QVERIFY(m_cm.isLoaded());
        QCOMPARE(m_cm.configPath().string().ends_with("config.ocio"), true);
    }

    void gpuDisplayTransformIsComplete_data() {
        QTest::addColumn<QString>("view");
        QTest::addColumn<bool>("needsLut");
        QTest::newRow("Standard") << "Standard" << false;
        QTest::newRow("ACES") << "ACES" << false;
        QTest::newRow("AgX") << "AgX" << true; // the shipped sigmoid LUT
    }

    void gpuDisplayTransformIsComplete() {
        QFETCH(QString, view);
        QFETCH(bool, needsLut);
        for (const char* d : {"sRGB", "Display P3"}) {
            std::string error;
            GpuTransformOptions options;
            options.functionName = "velvet_test_display";
            const auto gpu =
                m_cm.gpuDisplayTransform({d, view.toStdString(), "", 0.5f}, &error, options);
            QVERIFY2(gpu, error.c_str());
            QVERIFY(!gpu->glsl.empty());
            QVERIFY(gpu->glsl.find("vec4 velvet_test_display(") != std::string::npos);
            QCOMPARE(gpu->functionName, std::string("velvet_test_display"));
            QVERIFY(!gpu->cacheId.empty());
            if (needsLut)
                QVERIFY(!gpu->textures.empty());
            for (const GpuLutTexture& t : gpu->textures) {
                QVERIFY(t.width > 0 && t.height > 0 && t.depth > 0);
                QVERIFY(t.channels == 1 || t.channels == 3);
                QCOMPARE(t.values.size(), size_t(t.width) * t.height * t.depth * t.channels);
                QVERIFY(gpu->glsl.find(t.samplerName) != std::string::npos);
                QVERIFY(std::all_of(t.values.begin(), t.values.end(),
                                    [](float v) { return std::isfinite(v); }));
                if (t.dimensions == 3)
                    QVERIFY(t.width == t.height && t.height == t.depth);
                if (t.dimensions == 1)
                    QCOMPARE(t.height, 1);
            }
            const auto exposure = std::find_if(gpu->uniforms.begin(), gpu->uniforms.end(),
                                               [](const GpuUniform& u) { return u.isExposure; });
            QVERIFY(exposure != gpu->uniforms.end());
            QCOMPARE(exposure->floats.size(), size_t(1));
            QCOMPARE(exposure->floats[0], 0.5f);
            QVERIFY(gpu->glsl.find(exposure->name) != std::string::npos);
        }
    }
};

QTEST_GUILESS_MAIN(TestCoreColor)
#include "test_core_color.moc"
