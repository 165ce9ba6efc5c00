// `velvet bench --short --json` (DESIGN.md, "Measuring"): one JSON object with every key the
// renderer issue names, a G-buffer within budget, and finite positive ratios. Times and ratio
// targets are recorded in BENCHMARKS.md, never asserted (llvmpipe shares 2 cores here).
#include "core/post_effects.h"

#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QtTest>
#include <cmath>

class TestAppBench : public QObject {
    Q_OBJECT
private slots:
    void shortBenchPrintsEveryKey() {
        QProcess p;
        QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
        env.remove("DISPLAY");
        env.remove("WAYLAND_DISPLAY");
        p.setProcessEnvironment(env);
        p.start(VELVET_BINARY, {"bench", "--short", "--json"});
        QVERIFY2(p.waitForFinished(240000), "velvet bench --short did not finish in 240 s");
        const QByteArray out = p.readAllStandardOutput();
        QCOMPARE(p.exitStatus(), QProcess::NormalExit);
        QVERIFY2(p.exitCode() == 0, p.readAllStandardError().constData());
        QJsonParseError parseError;
        const QJsonDocument doc = QJsonDocument::fromJson(out, &parseError);
        QVERIFY2(doc.isObject(), qPrintable(parseError.errorString() + ": " + out));
        const QJsonObject o = doc.object();
        qInfo("%s", out.constData());

        const char* keys[] = {"gbuffer_bytes_per_pixel",
                              "lights1000_avg_lights_per_pixel",
                              "lights1000_speedup_vs_volumes",
                              "lights1000_speedup_vs_brute",
                              "lights_growth_1000_vs_100",
                              "light_pixel_pairs_ratio_1000_vs_100",
                              "gbuffer_ms",
                              "lighting_ms",
                              "ibl_ms",
                              "post_ms",
                              "total_ms",
                              "post_chain_share",
                              "bloom_vs_gauss9",
                              "effect_bloom_ms",
                              "orbit_frame_ms",
                              "orbit_frame_whole_scene_ms",
                              "orbit_speedup_vs_whole_scene",
                              "param_edit_mask_ms",
                              "param_edit_whole_scene_ms",
                              "stage_frame_off_ms",
                              "stage_frame_shadow_ms",
                              "stage_shadow_overhead",
                              "stage_shadow_overhead_cpu",
                              "stage_frame_shadow_cpu_ms",
                              "shadow_map_pass_ms",
                              "occlusion_pass_ms",
                              "shadow_mask_pass_ms",
                              "stage_shadow_ao_overhead_at_rest_resolution",
                              "shadow_mask_pass_at_rest_resolution_ms",
                              "occlusion_pass_at_rest_resolution_ms"};
        for (const char* k : keys)
            QVERIFY2(o.contains(k) && o.value(k).isDouble(), k);
        // The 24-byte layout with lobe channels beside the compact 16-byte one (issue 13).
        QCOMPARE(o.value("gbuffer_bytes_per_pixel").toDouble(), 24.0);
        QCOMPARE(o.value("gbuffer_bytes_per_pixel_compact").toDouble(), 16.0);
        for (const char* k :
             {"layout_default_lobes24_vs_compact16", "layout_mapped_lobes24_vs_compact16",
              "layout_mapped_frame_lobes24_vs_compact16"}) {
            const double v = o.value(k).toDouble();
            QVERIFY2(o.contains(k) && std::isfinite(v) && v > 0.0, k);
        }
        for (const char* k : {"lights1000_speedup_vs_volumes", "lights1000_speedup_vs_brute",
                              "lights_growth_1000_vs_100", "light_pixel_pairs_ratio_1000_vs_100",
                              "lights1000_avg_lights_per_pixel", "bloom_vs_gauss9",
                              "orbit_speedup_vs_whole_scene"}) {
            const double v = o.value(k).toDouble();
            QVERIFY2(std::isfinite(v) && v > 0.0, k);
        }
        // Each effect of the catalogue is timed alone (render/post_bench.h): one key per type.
        for (const velvet::EffectMeta& m : velvet::postEffectCatalogue()) {
            const QString key = QStringLiteral("effect_%1_ms")
                                    .arg(QString::fromUtf8(m.type.data(), int(m.type.size())));
            QVERIFY2(o.contains(key) && o.value(key).isDouble(), qPrintable(key));
            QVERIFY2(std::isfinite(o.value(key).toDouble()), qPrintable(key));
        }
        // A share of a frame is below 1; in short mode on a loaded machine the chain's cost can
        // drown in frame-to-frame noise (even read as negative), so only sanity is asserted here.
        const double share = o.value("post_chain_share").toDouble();
        QVERIFY(std::isfinite(share) && share < 1.0);
    }

    // Full mode only (VELVET_BENCH_FULL=1; 1280x720, 7 frames per variant, minutes): the tiled
    // path's cost grows no faster than its work, i.e. lights_growth_1000_vs_100 (a ratio of
    // times) <= light_pixel_pairs_ratio_1000_vs_100 (a ratio of light-pixel pairs) -
    // BENCHMARKS.md's target. Short mode is too noisy for a ratio of times.
    /// `velvet bench --frame` (issue 16): the peer's frame with the specialised programs beside
    /// the generic ones, alternate frames of one process. The ratio is asserted loosely (the
    /// specialisation measures about 2.5x here; BENCHMARKS.md), never a time.
    void frameBenchSpecialisedBeatsGeneric() {
        QProcess p;
        p.start(VELVET_BINARY, {"bench", "--frame", "--short", "--json"});
        QVERIFY2(p.waitForFinished(240000), "velvet bench --frame did not finish in 240 s");
        QVERIFY2(p.exitCode() == 0, p.readAllStandardError().constData());
        const QJsonObject o = QJsonDocument::fromJson(p.readAllStandardOutput()).object();
        for (const char* k : {"frame_wall_ms", "generic_frame_wall_ms", "gbuffer_ms", "lighting_ms",
                              "post_ms", "specialised_lighting_speedup"})
            QVERIFY2(o.value(k).isDouble() && o.value(k).toDouble() > 0.0, k);
        QCOMPARE(o.value("specialised_frames").toDouble(), 1.0);
        // The value-edit frames keep the background's pixels, the orbit's draw them (counts).
        QCOMPARE(o.value("background_kept_frames").toDouble(), o.value("frames").toDouble());
        QCOMPARE(o.value("orbit_background_kept_frames").toDouble(), 0.0);
        const double speedup = o.value("specialised_frame_speedup").toDouble();
        QVERIFY2(speedup > 1.2, qPrintable(QString::number(speedup)));
    }

    void fullBenchTiledGrowsWithLightPixelPairs() {
        if (qgetenv("VELVET_BENCH_FULL") != "1")
            QSKIP("full-mode bench: set VELVET_BENCH_FULL=1");
        QProcess p;
        QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
        env.remove("DISPLAY");
        env.remove("WAYLAND_DISPLAY");
        p.setProcessEnvironment(env);
        p.start(VELVET_BINARY, {"bench", "--json"});
        QVERIFY2(p.waitForFinished(1800000), "velvet bench did not finish in 30 min");
        QVERIFY2(p.exitCode() == 0, p.readAllStandardError().constData());
        const QJsonObject o = QJsonDocument::fromJson(p.readAllStandardOutput()).object();
        const double growth = o.value("lights_growth_1000_vs_100").toDouble(NAN);
        const double pairs = o.value("light_pixel_pairs_ratio_1000_vs_100").toDouble(NAN);
        qInfo("full bench: tiled growth 1000 vs 100 lights %.2f (%.1f / %.1f ms over a %.1f ms "
              "frame without point lights), light-pixel pairs ratio %.2f",
              growth, o.value("lights1000_tiled_ms").toDouble(),
              o.value("lights100_tiled_ms").toDouble(),
              o.value("frame_nolights_wall_ms").toDouble(), pairs);
        QVERIFY(std::isfinite(growth) && std::isfinite(pairs));
        QVERIFY2(growth <= pairs,
                 qPrintable(QString("growth %1 > pairs %2").arg(growth).arg(pairs)));
    }
};

QTEST_GUILESS_MAIN(TestAppBench)
#include "test_app_bench.moc"
