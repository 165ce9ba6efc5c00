// velvet compare (issue 15): identical images give ΔE 0; a known colour change gives the
// CIEDE2000 of the two colours as mean, p95 and max (the heat map written, with its legend);
// an EXR is put through the default display transform first; different sizes and missing files
// are exit 2, a wrong number of inputs exit 1.
#include "core/color_difference.h"
#include "core/image.h"
#include "core/image_compare.h"
#include "run_velvet.h"

#include <QRegularExpression>
#include <QTemporaryDir>
#include <QtTest>

namespace {

using velvet::test::Result;

velvet::Image flat(int w, int h, glm::vec3 c) {
    velvet::Image img(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            std::copy(&c.x, &c.x + 3, img.at(x, y));
    return img;
}

void write(const QString& file, const velvet::Image& img, velvet::PixelFormat f) {
    std::string error;
    if (!velvet::writeImage(file.toStdString(), img, f, &error))
        qFatal("%s", error.c_str());
}

double statistic(const QString& out, const QString& name) {
    const auto m =
        QRegularExpression("^" + name + R"( ([0-9.]+)$)", QRegularExpression::MultilineOption)
            .match(out);
    return m.hasMatch() ? m.captured(1).toDouble() : -1.0;
}

} // namespace

class TestAppCompare : public QObject {
    Q_OBJECT
    QTemporaryDir m_tmp;

private slots:
    void knownDifferences() {
        // 8-bit values exactly: 51/255 and 102/255.
        const glm::vec3 c1(0.2f, 0.4f, 0.6f), c2(0.4f, 0.4f, 0.6f);
        write(m_tmp.filePath("a.png"), flat(10, 10, c1), velvet::PixelFormat::UInt8);
        velvet::Image b = flat(10, 10, c1);
        for (int x = 0; x < 10; ++x)
            std::copy(&c2.x, &c2.x + 3, b.at(x, 0)); // one row of 10 differs: 10 % of pixels
        write(m_tmp.filePath("b.png"), b, velvet::PixelFormat::UInt8);

        Result r =
            velvet::test::runVelvet({"compare", m_tmp.filePath("a.png"), m_tmp.filePath("a.png"),
                                     "-o", m_tmp.filePath("same.png")});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(statistic(r.out, "mean"), 0.0);
        QCOMPARE(statistic(r.out, "max"), 0.0);

        r = velvet::test::runVelvet({"compare", m_tmp.filePath("a.png"), m_tmp.filePath("b.png"),
                                     "-o", m_tmp.filePath("heat.png")});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const double de = velvet::ciede2000(velvet::srgbToLab(c1), velvet::srgbToLab(c2));
        QVERIFY(de > 5.0);
        QVERIFY2(std::abs(statistic(r.out, "max") - de) < 1e-3, qPrintable(r.out));
        QVERIFY(std::abs(statistic(r.out, "mean") - de / 10.0) < 1e-3);
        QCOMPARE(statistic(r.out, "p95"), de > 0 ? statistic(r.out, "p95") : 0.0);
        QVERIFY(std::abs(statistic(r.out, "p95") - de) < 1e-3); // 10 % differ: above the 95th
        velvet::Image heat;
        std::string error;
        QVERIFY(velvet::readImage(m_tmp.filePath("heat.png").toStdString(), heat, &error));
        QCOMPARE(heat.height, 10 + velvet::heatMapLegendHeight());
        QVERIFY(heat.at(5, 5)[0] == 0.0f && heat.at(5, 5)[1] == 0.0f); // ΔE 0: black
        QVERIFY(heat.at(5, 0)[0] + heat.at(5, 0)[1] + heat.at(5, 0)[2] > 0.3f);
    }

    void exrGoesThroughTheDisplayTransform() {
        // A linear EXR and the PNG of its default display transform compare equal (to 8 bits).
        velvet::Image linear = flat(4, 4, {0.05f, 0.18f, 0.9f});
        linear.at(1, 1)[0] = 3.0f;
        write(m_tmp.filePath("lin.exr"), linear, velvet::PixelFormat::Float);
        write(m_tmp.filePath("disp.png"), velvet::defaultDisplayTransform(linear),
              velvet::PixelFormat::UInt8);
        const Result r = velvet::test::runVelvet(
            {"compare", m_tmp.filePath("lin.exr"), m_tmp.filePath("disp.png")});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(statistic(r.out, "max") < 0.5, qPrintable(r.out));
        // Taken as sRGB without the transform, the same EXR differs a lot.
        write(m_tmp.filePath("raw.png"), linear, velvet::PixelFormat::UInt8);
        const Result raw = velvet::test::runVelvet(
            {"compare", m_tmp.filePath("lin.exr"), m_tmp.filePath("raw.png")});
        QVERIFY(statistic(raw.out, "mean") > 5.0);
    }

    // The CPU display transform is the renderer's: the same frame rendered to .exr (scene-linear)
    // and to .png (the GPU's default display path) compares within 8-bit rounding (measured:
    // mean 0.22, max 0.88 for gold at 128x128 on llvmpipe).
    void renderedExrMatchesRenderedPng() {
        const QString gold = QStringLiteral(VELVET_SOURCE_DIR "/resources/presets/gold.json");
        const QString exr = m_tmp.filePath("gold.exr"), png = m_tmp.filePath("gold.png");
        for (const QString& out : {exr, png}) {
            const Result r =
                velvet::test::runVelvet({"render", gold, "-o", out, "--size", "64x64"});
            QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        }
        const Result r = velvet::test::runVelvet({"compare", exr, png});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        qInfo("rendered EXR vs PNG: %s", qPrintable(QString(r.out).replace('\n', ' ')));
        QVERIFY2(statistic(r.out, "mean") < 0.5 && statistic(r.out, "max") < 1.5,
                 qPrintable(r.out));
    }

    void refusals() {
        write(m_tmp.filePath("small.png"), flat(3, 3, {0, 0, 0}), velvet::PixelFormat::UInt8);
        write(m_tmp.filePath("big.png"), flat(4, 3, {0, 0, 0}), velvet::PixelFormat::UInt8);
        Result r = velvet::test::runVelvet(
            {"compare", m_tmp.filePath("small.png"), m_tmp.filePath("big.png")});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("3x3") && r.err.contains("4x3"), qPrintable(r.err));
        r = velvet::test::runVelvet(
            {"compare", m_tmp.filePath("small.png"), m_tmp.filePath("no.png")});
        QCOMPARE(r.exitCode, 2);
        QVERIFY(r.err.contains("no.png"));
        QCOMPARE(velvet::test::runVelvet({"compare", m_tmp.filePath("small.png")}).exitCode, 1);
        QCOMPARE(velvet::test::runVelvet({"compare", m_tmp.filePath("small.png"),
                                          m_tmp.filePath("small.png"), "-o", "x.jpg"})
                     .exitCode,
                 1);
    }

    // --table: the viewport against the reference as a Markdown table, one row per case, and
    // the images of each case with --images; the same numbers as app/reference_table.h gives
    // (test_app_reference_table holds the goal).
    void table() {
        const Result r = velvet::test::runVelvet(
            {"compare", "--table", "--preset", "rubber", "--mesh", "sphere", "--light-rig",
             "environment,three-point", "--size", "16", "--spp", "16", "--images", m_tmp.path()});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const QStringList lines = QString(r.out).split('\n', Qt::SkipEmptyParts);
        QVERIFY2(lines.size() == 5, qPrintable(r.out)); // header, rule, two rows, the summary
        QVERIFY(lines[0].startsWith("| preset | mesh | lights | mean"));
        QVERIFY2(lines[2].startsWith("| rubber | sphere | environment | "), qPrintable(lines[2]));
        QVERIFY2(lines[3].startsWith("| rubber | sphere | three-point | "), qPrintable(lines[3]));
        QVERIFY2(lines[4].contains("of 2 cases meet the goal"), qPrintable(lines[4]));
        for (const char* kind : {"viewport", "reference", "delta"}) {
            const QString file =
                m_tmp.filePath(QStringLiteral("rubber_sphere_environment_%1.png").arg(kind));
            velvet::Image img;
            std::string error;
            QVERIFY2(velvet::readImage(file.toStdString(), img, &error), error.c_str());
            QCOMPARE(img.width, kind == std::string("delta") ? 220 : 16); // the legend widens
        }
        // Refusals: images with --table, an unknown preset, mesh or rig, a bad size.
        QCOMPARE(velvet::test::runVelvet({"compare", "--table", "a.png", "b.png"}).exitCode, 1);
        Result bad = velvet::test::runVelvet({"compare", "--table", "--preset", "velour"});
        QCOMPARE(bad.exitCode, 1);
        QVERIFY2(bad.err.contains("velour"), qPrintable(bad.err));
        QCOMPARE(velvet::test::runVelvet({"compare", "--table", "--mesh", "teapot"}).exitCode, 1);
        QCOMPARE(velvet::test::runVelvet({"compare", "--table", "--light-rig", "moon"}).exitCode,
                 1);
        QCOMPARE(velvet::test::runVelvet({"compare", "--table", "--size", "2"}).exitCode, 1);
    }
};

QTEST_GUILESS_MAIN(TestAppCompare)
#include "test_app_compare.moc"
