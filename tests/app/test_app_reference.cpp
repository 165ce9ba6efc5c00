// `velvet reference` as a process (issue 15): Ctrl+C writes the samples taken so far, the time
// limit stops the render, and bad arguments are usage errors (exit 1) naming the option.

#include "core/image.h"
#include "run_velvet.h"

#include <QElapsedTimer>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <csignal>

using velvet::test::runVelvet;

namespace {

// Every pixel finite and the image not black: the file holds a real render.
void checkWrittenImage(const QString& file, int width, int height) {
    velvet::Image image;
    std::string error;
    QVERIFY2(velvet::readImage(file.toStdString(), image, &error), error.c_str());
    QCOMPARE(image.width, width);
    QCOMPARE(image.height, height);
    double sum = 0.0;
    for (const float v : image.pixels) {
        QVERIFY(std::isfinite(v));
        sum += v;
    }
    QVERIFY2(sum > 0.0, "the written image is black");
}

} // namespace

class TestAppReference : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;

private slots:
    void sigintWritesWhatItHas() {
        const QString out = m_dir.filePath("interrupted.exr");
        QProcess p;
        QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
        env.remove("DISPLAY");
        p.setProcessEnvironment(env);
        // Far more samples than the test waits for: only the interrupt can end it in time.
        p.start(VELVET_BINARY, {"reference", "-o", out, "--size", "32x24", "--spp", "1000000"});
        QVERIFY(p.waitForStarted());
        // Wait for the first completed pass ("N/1000000 samples per pixel" with N >= 1).
        QByteArray err;
        QElapsedTimer clock;
        clock.start();
        const QRegularExpression pass("\\b([1-9][0-9]*)/1000000 samples per pixel");
        while (!pass.match(QString::fromUtf8(err)).hasMatch() && clock.elapsed() < 120000) {
            p.waitForReadyRead(200);
            err += p.readAllStandardError();
        }
        QVERIFY2(pass.match(QString::fromUtf8(err)).hasMatch(), err.constData());
        QVERIFY(::kill(pid_t(p.processId()), SIGINT) == 0);
        QVERIFY2(p.waitForFinished(60000), "velvet reference did not stop on SIGINT");
        err += p.readAllStandardError();
        QCOMPARE(p.exitStatus(), QProcess::NormalExit);
        QCOMPARE(p.exitCode(), 0);
        QVERIFY2(err.contains("interrupted; writing"), err.constData());
        checkWrittenImage(out, 32, 24);
    }

    void timeLimitStops() {
        const QString out = m_dir.filePath("limited.exr");
        QElapsedTimer clock;
        clock.start();
        const auto r = runVelvet(
            {"reference", "-o", out, "--size", "24x16", "--spp", "1000000", "--time-limit", "0.5"},
            {.timeoutMs = 120000});
        QCOMPARE(r.exitCode, 0);
        QVERIFY2(clock.elapsed() < 60000, qPrintable(QString::number(clock.elapsed())));
        checkWrittenImage(out, 24, 16);
    }

    void badArgumentsNameTheOption_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<QString>("expected");
        const QString out = "x.exr";
        QTest::newRow("spp") << QStringList{"reference", "-o", out, "--spp", "0"} << "--spp";
        QTest::newRow("time") << QStringList{"reference", "-o", out, "--time-limit", "-1"}
                              << "--time-limit";
        QTest::newRow("png") << QStringList{"reference", "-o", "x.png"} << "must end in .exr";
        QTest::newRow("size") << QStringList{"reference", "-o", out, "--size", "0x9"} << "--size";
    }
    void badArgumentsNameTheOption() {
        QFETCH(QStringList, args);
        QFETCH(QString, expected);
        const auto r = runVelvet(args, {.workingDir = m_dir.path()});
        QCOMPARE(r.exitCode, 1); // a usage error (app/cli.h)
        QVERIFY2(r.err.contains(expected), qPrintable(r.err));
        QVERIFY(!QFile::exists(m_dir.filePath("x.exr")));
    }
};

QTEST_GUILESS_MAIN(TestAppReference)
#include "test_app_reference.moc"
