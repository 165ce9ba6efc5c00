// Issue 18: `velvet pack` runs killed with SIGKILL mid-write never break the output and leave no
// stray temporaries beside it (the report: 40 killed runs left 9 ".orm.tmp….png" files). Writes
// go through an unnamed temporary (core/atomic_file.h), so a kill leaves nothing; a kill between
// naming and renaming may leave that one run's temporary, which the next run that reaches its
// write sweeps (a run killed while still reading its inputs sweeps nothing): a temporary is
// asserted to belong to a run killed since the last complete one, one at most each, and a final
// complete run leaves exactly the inputs and the output.
#include "core/image.h"
#include "run_velvet.h"

#include <QDir>
#include <QElapsedTimer>
#include <QProcess>
#include <QTemporaryDir>
#include <QThread>
#include <QtTest>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <random>

namespace {

constexpr int kRuns = 40; // the report's count

velvet::Image noise(int w, int h, unsigned seed) {
    velvet::Image img(w, h, 1);
    std::mt19937 random(seed);
    for (float& v : img.pixels)
        v = float(random() % 256) / 255.0f;
    return img;
}

/// Hidden files beside the output that no process of @p killed wrote, or a second one of the
/// same process. A kill between naming the written temporary and renaming it over the target
/// (two system calls apart) may leave that process's one temporary, which the next run that
/// reaches its write removes; @p ofLast counts those of the last of @p killed.
int strays(const QDir& dir, const QList<qint64>& killed, int* ofLast) {
    int n = 0;
    QList<qint64> seen;
    for (const QString& name : dir.entryList(QDir::Files | QDir::Hidden)) {
        if (!name.startsWith(QLatin1Char('.')))
            continue;
        const auto owner = std::find_if(killed.begin(), killed.end(), [&](qint64 pid) {
            return name.contains(QStringLiteral(".velvet-tmp-%1-").arg(pid));
        });
        if (owner == killed.end() || seen.contains(*owner)) {
            ++n;
            continue;
        }
        seen.append(*owner);
        if (*owner == killed.last())
            ++*ofLast;
    }
    return n;
}

} // namespace

class TestAppKilledWrites : public QObject {
    Q_OBJECT
private slots:
    void killedPackRunsLeaveNoLitter() {
        QTemporaryDir tmp;
        const QDir dir(tmp.path());
        std::string error;
        QStringList args{"pack", "--layout", "unreal-orm", "--out", dir.filePath("orm.png")};
        int seed = 1;
        // Noise does not compress: the PNG encode and write take long enough to be hit.
        for (const char* map : {"occlusion", "roughness", "metallic"}) {
            const QString file = dir.filePath(QString(map) + ".png");
            QVERIFY2(velvet::writeImage(file.toStdString(), noise(1024, 1024, unsigned(seed++)),
                                        velvet::PixelFormat::UInt8, &error),
                     error.c_str());
            args << QStringLiteral("--") + map << file;
        }
        // Complete runs: the shorter of two sets the range of kill moments (the first, with cold
        // caches or beside a loaded moment of a parallel suite, ran long enough in CI that most
        // later runs finished before their kill).
        int fullMs = 0;
        for (int i = 0; i < 2; ++i) {
            QElapsedTimer clock;
            clock.start();
            const velvet::test::Result full = velvet::test::runVelvet(args);
            QVERIFY2(full.exitCode == 0, qPrintable(full.err));
            fullMs = i == 0 ? int(clock.elapsed()) : std::min(fullMs, int(clock.elapsed()));
        }
        velvet::ImageInfo reference;
        QVERIFY(velvet::readImageInfo(dir.filePath("orm.png").toStdString(), reference, &error));

        std::mt19937 random(18);
        std::uniform_int_distribution<int> moment(fullMs / 4, fullMs);
        int killedBeforeEnd = 0, leftByLastKill = 0;
        QList<qint64> killedSinceComplete; // their temporaries may still stand
        for (int run = 0; run < kRuns; ++run) {
            QProcess p;
            QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
            env.remove("DISPLAY");
            p.setProcessEnvironment(env);
            p.start(VELVET_BINARY, args);
            QVERIFY(p.waitForStarted());
            const qint64 pid = p.processId();
            if (!p.waitForFinished(moment(random))) {
                ::kill(pid_t(pid), SIGKILL);
                p.waitForFinished();
                ++killedBeforeEnd;
                killedSinceComplete.append(pid);
            } else {
                killedSinceComplete.clear(); // a complete run swept them all
            }
            // The output is the previous complete one, never half of one, and nothing else.
            velvet::ImageInfo info;
            QVERIFY2(velvet::readImageInfo(dir.filePath("orm.png").toStdString(), info, &error),
                     error.c_str());
            QCOMPARE(info.width, reference.width);
            QCOMPARE(strays(dir, killedSinceComplete, &leftByLastKill), 0);
        }
        QVERIFY2(killedBeforeEnd >= kRuns / 2, qPrintable(QString::number(killedBeforeEnd)));
        const velvet::test::Result last = velvet::test::runVelvet(args);
        QVERIFY2(last.exitCode == 0, qPrintable(last.err));
        QCOMPARE(dir.entryList(QDir::Files | QDir::Hidden).size(), 4); // 3 maps + orm.png
        std::printf("velvet pack: %d of %d runs killed mid-run (one run %d ms), 0 strays left "
                    "(%d temporaries of the run just killed, swept by the next)\n",
                    killedBeforeEnd, kRuns, fullMs, leftByLastKill);
    }
};

QTEST_GUILESS_MAIN(TestAppKilledWrites)
#include "test_app_killed_writes.moc"
