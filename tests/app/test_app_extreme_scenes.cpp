// Issue 18, "Values in range that break the picture": generated scenes with extreme values the
// schema allows (an environment of 1e30, a light of 3e38 lux, a camera 1e-6 or 1e30 away, a yaw
// of 1e30) rendered with `velvet render -o x.exr`. Whatever a scene gets — exit 0, 2 (refused)
// or 3 (rendering failure) — an image written with exit 0 holds only finite pixels, and exit 3
// says why ("not finite"). The outcomes are printed (BENCHMARKS.md).
#include "core/document_io.h"
#include "core/image.h"
#include "run_velvet.h"

#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <cstdio>
#include <functional>

using velvet::Scene;

class TestAppExtremeScenes : public QObject {
    Q_OBJECT
private slots:
    void extremeScenesNeverWriteNonFinitePixels_data() {
        QTest::addColumn<int>("which");
        const char* names[] = {"environment colour 1e30",
                               "environment intensity 1e30",
                               "light 3e38 lux",
                               "light colour 3e38",
                               "camera distance 1e-6",
                               "camera distance 1e30",
                               "yaw 1e30",
                               "baseline (default scene)"};
        for (int i = 0; i < 8; ++i)
            QTest::newRow(names[i]) << i;
    }
    void extremeScenesNeverWriteNonFinitePixels() {
        QFETCH(int, which);
        const std::function<void(Scene&)> edits[] = {
            [](Scene& s) { s.environment.hdri.clear(), s.environment.color = glm::vec3(1e30f); },
            [](Scene& s) { s.environment.intensity = 1e30f; },
            [](Scene& s) { s.lights.at(0).intensity = 3e38f; },
            [](Scene& s) { s.lights.at(0).color = glm::vec3(3e38f); },
            [](Scene& s) { s.camera.distance = 1e-6f; },
            [](Scene& s) { s.camera.distance = 1e30f; },
            [](Scene& s) { s.camera.yawDeg = 1e30f; },
            [](Scene&) {},
        };
        QTemporaryDir dir;
        Scene scene = velvet::defaultScene();
        edits[which](scene);
        const QString file = dir.filePath("extreme.json"), out = dir.filePath("out.exr");
        std::string error;
        QVERIFY2(velvet::saveSceneFile(scene, file.toStdString(), &error), error.c_str());
        const velvet::test::Result r =
            velvet::test::runVelvet({"render", file, "--size", "32x32", "-o", out});
        QCOMPARE(r.status, QProcess::NormalExit);
        QVERIFY2(r.exitCode == 0 || r.exitCode == 2 || r.exitCode == 3, qPrintable(r.err));
        if (r.exitCode == 0) {
            velvet::Image image;
            QVERIFY2(velvet::readImage(out.toStdString(), image, &error), error.c_str());
            for (float v : image.pixels)
                QVERIFY2(std::isfinite(v), "exit 0 with a non-finite pixel");
        } else if (r.exitCode == 3) {
            QVERIFY2(r.err.contains("not finite"), qPrintable(r.err));
            QVERIFY(!QFile::exists(out));
        }
        if (which == 7)
            QCOMPARE(r.exitCode, 0); // the baseline renders: the check refuses only what is broken
        std::printf("%s: exit %d %s\n", QTest::currentDataTag(), r.exitCode,
                    qPrintable(r.err.trimmed().split('\n').last()));
    }
};

QTEST_GUILESS_MAIN(TestAppExtremeScenes)
#include "test_app_extreme_scenes.moc"
