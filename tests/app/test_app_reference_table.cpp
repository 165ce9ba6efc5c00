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
// (image-based light's anisotropic sweep and the split sum at grazing angles; interreflections
// between a metal's own parts on the shader ball, which the path tracer has and the viewport's
// occlusion only darkens), sheen under the environment where a weave or crushed pile adds to
// it, the fabrics' weaves (pattern-aligned: lower relief contrast in the viewport; and where a
// thread is finer than a pixel the viewport shows the weave's mean with a flat normal, issue
// 13's filtering, which lacks the bumps' brighter rim), leather's grain under the HDRI
// (sub-pixel at 32x32), and the shader ball's cavities (occluded by the mesh's baked visibility
// as a cone, render/mesh_visibility.h, where the path tracer sees the mesh's own reflections).
// Re-recorded on 2026-12-03 after the anisotropic sweep, the sheen's irradiance about its mean
// direction and the baked visibility lowered every row they touch; and again after the
// reference honoured the material's occlusion as glTF defines it (the weaves' gaps), which
// lowered most fabric rows and raised wool's and tweed's under the rig (BENCHMARKS.md); and
// again after the lighting kept light from below a bent normal's geometric horizon out, which
// took wool and crushed velvet under the rig off the list; and on 2026-12-04 after the
// occlusion took back the light a crease bounces and the diffuse irradiance the share of a bent
// normal's lobe above the face (BENCHMARKS.md, "Interreflection in the occlusion"); and again
// after the reference stratified its first vertex (path_sampling.h): less of its own noise
// counts as ΔE, which took ceramic, linen and silk under the HDRI off the list; and on 2026-12-05
// after image-based light narrowed the reflected lobe at grazing angles (reflectedRadiance in
// common_environment.glsl): the metals' rows fell by a fifth to a half, and ceramic under the HDRI,
// 1.94 before, now sits on the goal's line (2.00 here, 1.89 at 48x48 and 512 samples); and on
// 2026-12-06 after the anisotropic sweep weighted each sample by the lobe's own Fresnel and
// masking (anisotropicReflection): brushed aluminium's rows fell by more than half; and on
// 2026-12-06 (evening) after the sheen's image-based light lost the share of its lobe below a
// bent normal's face (lighting.frag): wool, terry and crushed velvet under the HDRI fell (wool's
// p95 7.36 to 6.46); and again when the three-point rig's fill and rim began to cast shadows, as
// the path tracer's do: the fabrics and leather on the ball under the rig fell (satin, crushed
// velvet and leather now meet the goal there and joined the table), gold's rose (10.74 / 56.88
// to 11.47 / 57.93: its interreflections, which the viewport lacks, now sit in more shadow);
// and when the reference drew a directional light as the disc of its angular diameter, as the
// viewport's penumbra does (leather on the ball under the rig, on the line at this size, moved
// from 1.24 / 4.55 to 1.24 / 5.22 and is listed); and on 2026-12-07 when the table began to
// compare the viewport as it stands at rest, its glossy reflections sampled
// (FrameSettings::reflectionSamples): copper and gold on the sphere and crushed velvet on the
// sphere under the HDRI now meet the goal (copper 2.63 / 8.12 to 1.39 / 4.77 under the HDRI) and
// left the list, so the test fails if the sampling goes; and again when a stretched lobe was
// sampled too: brushed aluminium on the sphere under the rig met the goal (2.29 / 7.32 to
// 1.18 / 3.73) and left the list, under the HDRI it fell to 2.38 / 6.77, and silk under the HDRI,
// 1.9x before, moved onto the line at this size (2.03 / 4.94) and is listed; and again when
// image-based light read the environment's integrated irradiance in place of its SH9
// (render/irradiance_map.h): ceramic, silk and terry on the sphere under the HDRI met the goal
// (ceramic 2.00 / 4.30 to 1.07 / 2.67, terry 2.71 / 5.80 to 1.78 / 4.09) and left the list, so the
// test fails if the SH9 comes back; cotton under the HDRI is on the line at this size (2.56 / 5.85
// to 1.97 / 4.41) and stays listed, and the other misses' bounds were tightened to their values;
// and again when the table began to draw the refinement's 16 frames, each reading the light of
// the one before, as the editor does at rest (more bounces of the mesh's own light than the one
// a single frame traces): plastic on the ball under the HDRI met the goal (1.89 / 4.53) and left
// the list, under the rig it reads 1.80 / 5.26; gold on the ball under the HDRI rose from
// 7.60 / 35.94 to 8.75 / 34.51 (its rings' rims, already brighter than the path tracer's, gain
// the bounces), under the rig it reads 10.20 / 46.59; and on 2026-12-08 when each of those 16
// frames took the refinement's sub-pixel jitter and its own set of reflection samples, as the
// editor's do (before, all 16 drew the same samples at the pixels' centres): brushed aluminium
// on the sphere under the HDRI met the goal (2.38 / 6.77 to 1.38 / 3.72) and left the list, so
// the test fails if the frames draw the same samples again; plastic on the ball under the rig
// (1.69 / 4.97) and crushed velvet on the ball under the HDRI (2.00 / 4.91) sit on the line at
// this size and stay listed; the other bounds were re-recorded; and again when the frames at
// rest sampled the sheen's lobe (common_environment.glsl's sampledSheenLight) in place of the
// irradiance about its mean direction: crushed velvet on the ball under the HDRI met the goal
// (1.43 / 3.17) and left the list, so the test fails if the sheen's samples go; cotton on the
// sphere under the HDRI meets it on the line (1.94 / 4.08) and stays listed; the knits and
// weaves on the sphere rose a little (wool under the HDRI 2.17 / 5.69 to 2.45 / 5.62).
const Miss kMisses[] = {
    {"cotton", kSphere, "environment", 1.94, 4.08}, // on the line at this size (met at 48x48)
    {"denim", kSphere, "three-point", 2.25, 5.51},  // met at 48x48
    {"tweed", kSphere, "environment", 2.37, 4.97},  // met at 48x48
    {"tweed", kSphere, "three-point", 2.58, 5.97},  // met at 48x48
    {"wool", kSphere, "environment", 2.45, 5.62},
    {"plastic", kBall, "three-point", 1.69, 4.97}, // on the line at this size
    {"gold", kBall, "environment", 8.28, 34.07},
    {"gold", kBall, "three-point", 9.91, 48.06},
    {"leather", kBall, "three-point", 1.10, 5.32},
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
        // On the ball: a plain dielectric, a glossy one, a metal, and fabrics and leather whose
        // rows under the rig depend on every light's shadow (the rig's fill and rim cast theirs).
        for (const char* preset :
             {"rubber", "plastic", "gold", "satin", "crushed_velvet", "leather"})
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
