// The viewport against the reference (issue 15's goal, app/reference_table.h): every library
// preset on the sphere, and three on the shader ball (a rough dielectric, a glossy one, a metal),
// under the default HDRI alone and the three-point rig, 32x32 pixels, 256 reference samples per
// pixel (deterministic: the reference's random streams are fixed by the seed). A case meets the
// goal — mean ΔE2000 < 2 and 95th percentile < 5 over the mesh's pixels — unless it is one of the
// named misses below, whose measured values may not grow by more than 10 % (+0.2). A named miss
// that meets the goal is reported, so the list is kept honest. BENCHMARKS.md has the full table.
#include "app/reference_table.h"

#include <QtTest>
#include <string>

using namespace velvet;
using namespace velvet::cli;

namespace {

struct Miss {
    const char* preset;
    PreviewMeshKind mesh;
    const char* rig;
    double mean,
        p95; ///< as measured at 32x32, 256 spp (velvet compare --table --size 32 --spp 256)
};

constexpr PreviewMeshKind kSphere = PreviewMeshKind::Sphere;
constexpr PreviewMeshKind kBall = PreviewMeshKind::ShaderBall;

// Why they miss (BENCHMARKS.md, "The viewport against the reference"): metals and anisotropy
// (the bent-normal approximation of anisotropic reflections; the metals' rows were re-recorded
// after direct light and the reference gained the multiple-scattering energy the image-based
// light has, which lowered them by 0.01-0.4), sheen
// under the environment (albedo x prefiltered radiance against the integrated sheen lobe), the
// fabrics' weaves (pattern-aligned: lower relief contrast in the viewport; and where a thread
// is finer than a pixel the viewport shows the weave's mean with a flat normal, issue 13's
// filtering, which lacks the bumps' brighter rim: cotton, denim and tweed under the HDRI and
// satin under the rig were re-measured with it; leather's grain, sub-pixel at 32x32, likewise
// under the HDRI since the preset has a Leather grain normal; cotton, linen and tweed again
// when their threads were made finer and their yarns flatter for the thumbnails, so more of
// them is filtered; the Burley presets' rows were re-measured after image-based light took
// Burley's albedo, which lowered most and raised terry's and wool's under the HDRI; terry's
// again when its pile became a finer, less crushed loop pile that reads as towelling), the shader
// ball's cavities (the viewport reflects the environment where the mesh sees itself).
const Miss kMisses[] = {
    {"brushed_aluminium", kSphere, "environment", 13.45, 29.48},
    {"brushed_aluminium", kSphere, "three-point", 8.09, 23.51},
    {"ceramic", kSphere, "environment", 2.41, 5.36},
    {"copper", kSphere, "environment", 4.38, 11.51},
    {"copper", kSphere, "three-point", 3.15, 8.80},
    {"cotton", kSphere, "environment", 6.37, 13.44},
    {"cotton", kSphere, "three-point", 1.97, 6.46},
    {"crimson_velvet", kSphere, "environment", 3.39, 8.23},
    {"crimson_velvet", kSphere, "three-point", 2.34, 6.52},
    {"crushed_velvet", kSphere, "environment", 7.32, 39.44},
    {"crushed_velvet", kSphere, "three-point", 3.63, 15.12},
    {"denim", kSphere, "environment", 3.70, 7.62},
    {"denim", kSphere, "three-point", 3.51, 7.32},
    {"gold", kSphere, "environment", 3.97, 10.56},
    {"gold", kSphere, "three-point", 2.99, 8.23},
    {"leather", kSphere, "environment", 2.27, 4.02},
    {"linen", kSphere, "environment", 6.41, 12.06},
    {"linen", kSphere, "three-point", 2.36, 6.86},
    {"satin", kSphere, "environment", 3.38, 11.73},
    {"satin", kSphere, "three-point", 3.28, 10.90},
    {"silk", kSphere, "environment", 4.70, 11.34},
    {"terry", kSphere, "environment", 4.34, 11.84},
    {"tweed", kSphere, "environment", 5.87, 12.07},
    {"tweed", kSphere, "three-point", 3.42, 7.81},
    {"wool", kSphere, "environment", 5.84, 13.15},
    {"wool", kSphere, "three-point", 3.33, 8.34},
    {"plastic", kBall, "environment", 7.63, 48.04},
    {"plastic", kBall, "three-point", 5.87, 31.76},
    {"gold", kBall, "environment", 14.44, 67.03},
    {"gold", kBall, "three-point", 13.82, 65.02},
};

const Miss* knownMiss(const ReferenceTableCase& c) {
    for (const Miss& m : kMisses)
        if (c.preset == m.preset && c.mesh == m.mesh && c.rig == m.rig)
            return &m;
    return nullptr;
}

/// The recorded value plus the regression allowance.
double bound(double measured) {
    return measured * 1.1 + 0.2;
}

} // namespace

class TestAppReferenceTable : public QObject {
    Q_OBJECT
    ReferenceTable m_table;
    ReferenceTableOptions m_options;

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(m_table.start(&error), error.c_str());
        m_options.size = 32;
        m_options.samples = 256;
        QVERIFY(libraryPresets().size() >= 18);
    }

    void viewportAgainstReference_data() {
        QTest::addColumn<QString>("preset");
        QTest::addColumn<int>("mesh");
        QTest::addColumn<QString>("rig");
        const auto add = [](const std::string& preset, PreviewMeshKind mesh) {
            for (const char* rig : {"environment", "three-point"}) {
                const std::string name =
                    preset + " " + std::string(previewMeshKindNames()[size_t(mesh)]) + " " + rig;
                QTest::newRow(name.c_str())
                    << QString::fromStdString(preset) << int(mesh) << QString::fromLatin1(rig);
            }
        };
        for (const std::string& preset : libraryPresets())
            add(preset, kSphere);
        for (const char* preset : {"rubber", "plastic", "gold"})
            add(preset, kBall);
    }

    void viewportAgainstReference() {
        QFETCH(QString, preset);
        QFETCH(int, mesh);
        QFETCH(QString, rig);
        const ReferenceTableCase c{preset.toStdString(), PreviewMeshKind(mesh), rig.toStdString()};
        ReferenceTableRow row;
        std::string error;
        QVERIFY2(m_table.measure(c, m_options, row, &error), error.c_str());
        // The mesh's pixels: the sphere fills about half the frame (kStageFill 0.8 of the
        // height), the shader ball less.
        QVERIFY2(row.stats.pixels > 200, qPrintable(QString::number(row.stats.pixels)));
        qInfo("%s", referenceTableLine(row).c_str());
        if (const Miss* miss = knownMiss(c)) {
            if (meetsReferenceGoal(row.stats))
                qWarning("%s now meets the goal (mean %.2f, p95 %.2f): take it off the misses",
                         qPrintable(QString(QTest::currentDataTag())), row.stats.mean,
                         row.stats.p95);
            QVERIFY2(row.stats.mean <= bound(miss->mean) && row.stats.p95 <= bound(miss->p95),
                     qPrintable(QStringLiteral("regressed: mean %1 (recorded %2), p95 %3 "
                                               "(recorded %4)")
                                    .arg(row.stats.mean)
                                    .arg(miss->mean)
                                    .arg(row.stats.p95)
                                    .arg(miss->p95)));
        } else {
            QVERIFY2(meetsReferenceGoal(row.stats),
                     qPrintable(QStringLiteral("mean %1 (goal < 2), p95 %2 (goal < 5)")
                                    .arg(row.stats.mean)
                                    .arg(row.stats.p95)));
        }
    }
};

QTEST_GUILESS_MAIN(TestAppReferenceTable)
#include "test_app_reference_table.moc"
