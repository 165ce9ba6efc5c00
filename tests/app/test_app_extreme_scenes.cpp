// Issue 18, "Values in range that break the picture": a generated set of scenes with extreme
// values (an environment of 1e30, a light of 1.7e308 lux, a camera 1e-6 or 1e30 away, a yaw of
// 1e300, …) rendered with `velvet render -o x.exr`. A value beyond the schema's bounds
// (docs/file-formats.md, "Bounds") is refused with exit 2 and a message naming its key, before
// anything is rendered; a value at a bound is not refused, and renders finite (exit 0, every
// pixel of the image finite) or fails with exit 3 saying why ("not finite") and writes nothing.
// The outcomes are printed (BENCHMARKS.md, "Data safety").
#include "core/image.h"
#include "run_velvet.h"

#include <QFile>
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <cstdio>

namespace {

// The parts of a scene a row replaces; every other value is the default.
constexpr const char* kCamera = R"({})";
constexpr const char* kLight = R"({"type": "directional", "intensity": 3,
  "direction": [-0.4, -0.7, -0.6]})";
constexpr const char* kEnvironment = R"({"color": [1, 1, 1], "intensity": 1})";

QByteArray sceneText(const QString& camera, const QString& light, const QString& environment) {
    return QStringLiteral(R"({"format": "velvet.scene", "version": 2, "camera": %1,
      "lights": [%2], "environment": %3, "mesh": {"kind": "sphere"}})")
        .arg(camera, light, environment)
        .toUtf8();
}

} // namespace

class TestAppExtremeScenes : public QObject {
    Q_OBJECT
private slots:
    void extremeValuesAreRefusedOrRenderFinite_data() {
        QTest::addColumn<QString>("camera");
        QTest::addColumn<QString>("light");
        QTest::addColumn<QString>("environment");
        // The key the refusal must name; empty: within the bounds, so it must render (exit 0
        // with finite pixels, or exit 3 "not finite" and nothing written).
        QTest::addColumn<QString>("refusedKey");
        const QString cam = kCamera, light = kLight, env = kEnvironment;
        auto row = [](const char* name, QString c, QString l, QString e, QString key) {
            QTest::newRow(name) << c << l << e << key;
        };
        // Beyond the bounds.
        row("environment colour 1e30", cam, light, R"({"color": [1e30, 1e30, 1e30]})",
            "environment.color[0]");
        row("environment intensity 1e30", cam, light, R"({"intensity": 1e30})",
            "environment.intensity");
        row("environment colour x intensity 65504 x 2", cam, light,
            R"({"color": [65504, 1, 1], "intensity": 2})", "environment.intensity");
        row("background colour 1e30", cam, light,
            R"({"background": "solid-color", "backgroundColor": [1e30, 0, 0]})",
            "environment.backgroundColor[0]");
        row("environment rotation 1e300", cam, light, R"({"rotation": 1e300})",
            "environment.rotation");
        row("light 1.7e308 lux", cam,
            R"({"type": "directional", "intensity": 1.7e308, "direction": [0, -1, 0]})", env,
            "lights[0].intensity");
        row("light colour 3e38", cam,
            R"({"type": "directional", "color": [3e38, 3e38, 3e38], "direction": [0, -1, 0]})", env,
            "lights[0].color[0]");
        row("light direction 1e30", cam, R"({"type": "directional", "direction": [1e30, -1, 0]})",
            env, "lights[0].direction[0]");
        row("point light position 1e30", cam, R"({"type": "point", "position": [1e30, 0, 0]})", env,
            "lights[0].position[0]");
        row("point light range 1e-30", cam, R"({"type": "point", "range": 1e-30})", env,
            "lights[0].range");
        row("area light size 1e30", cam,
            R"({"type": "area", "shape": "rectangle", "size": [1e30, 1], "direction": [0, -1, 0]})",
            env, "lights[0].size[0]");
        row("camera distance 1e-6", R"({"distance": 1e-6})", light, env, "camera.distance");
        row("camera distance 1e30", R"({"distance": 1e30})", light, env, "camera.distance");
        row("camera yaw 1e300", R"({"yaw": 1e300})", light, env, "camera.yaw");
        row("camera target 1e30", R"({"target": [1e30, 0, 0]})", light, env, "camera.target[0]");
        row("camera far 1e30", R"({"far": 1e30})", light, env, "camera.far");
        row("camera near 1e-9", R"({"near": 1e-9})", light, env, "camera.near");
        row("orthographic height 1e30", R"({"orthographic": true, "orthoHeight": 1e30})", light,
            env, "camera.orthoHeight");
        // At the bounds: accepted, and never a non-finite pixel written.
        row("environment 65504", cam, light, R"({"color": [65504, 65504, 65504], "intensity": 1})",
            "");
        row("light 1e6 lux of colour 65504", cam,
            R"({"type": "directional", "intensity": 1e6, "color": [65504, 65504, 65504],
                "direction": [0, -1, 0]})",
            env, "");
        row("point light 1e6 cd beside the mesh", cam,
            R"({"type": "point", "intensity": 1e6, "position": [0, 0, 1.0001], "range": 1e6})", env,
            "");
        row("camera distance 1e-4", R"({"distance": 1e-4, "near": 1e-4})", light, env, "");
        row("camera distance 1e6", R"({"distance": 1e6, "far": 1e6})", light, env, "");
        row("camera yaw 1e5, target 1e6", R"({"yaw": 1e5, "target": [1e6, 0, 0]})", light, env, "");
        row("baseline", cam, light, env, "");
    }
    void extremeValuesAreRefusedOrRenderFinite() {
        QFETCH(QString, camera);
        QFETCH(QString, light);
        QFETCH(QString, environment);
        QFETCH(QString, refusedKey);
        QTemporaryDir dir;
        const QString file = dir.filePath("extreme.json"), out = dir.filePath("out.exr");
        QFile f(file);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(sceneText(camera, light, environment));
        f.close();
        const velvet::test::Result r =
            velvet::test::runVelvet({"render", file, "--size", "32x32", "-o", out});
        QCOMPARE(r.status, QProcess::NormalExit);
        if (!refusedKey.isEmpty()) {
            QVERIFY2(r.exitCode == 2, qPrintable(r.err));
            QVERIFY2(r.err.contains(file + ": " + refusedKey + ": "), qPrintable(r.err));
            QVERIFY(!QFile::exists(out));
        } else {
            QVERIFY2(r.exitCode == 0 || r.exitCode == 3, qPrintable(r.err));
            if (r.exitCode == 0) {
                velvet::Image image;
                std::string error;
                QVERIFY2(velvet::readImage(out.toStdString(), image, &error), error.c_str());
                for (float v : image.pixels)
                    QVERIFY2(std::isfinite(v), "exit 0 with a non-finite pixel");
            } else {
                QVERIFY2(r.err.contains("not finite"), qPrintable(r.err));
                QVERIFY(!QFile::exists(out));
            }
            if (QByteArray(QTest::currentDataTag()) == "baseline")
                QCOMPARE(r.exitCode, 0); // the checks refuse only what is broken
        }
        std::printf("%s: exit %d %s\n", QTest::currentDataTag(), r.exitCode,
                    qPrintable(r.err.trimmed().split('\n').last()));
    }
};

QTEST_GUILESS_MAIN(TestAppExtremeScenes)
#include "test_app_extreme_scenes.moc"
