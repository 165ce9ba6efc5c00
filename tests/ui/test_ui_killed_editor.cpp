// Issue 18, "Seconds, not a minute": the editor autosaves about 2 s after the last edit of a
// burst (ui/autosave.h), so an edit, 3 s of waiting and a SIGKILL lose nothing: started again on
// the same file, the editor offers recovery and the edit is back, dirty. Two editors on two files
// are killed together and each gets its own edit back. The editors are real `velvet` processes
// under xvfb, driven by the test hooks in ui/editor.cpp (VELVET_TEST_EDIT,
// VELVET_TEST_ACCEPT_RECOVERY).
#include "core/document_io.h"

#include <QDirIterator>
#include <QElapsedTimer>
#include <QProcess>
#include <QTemporaryDir>
#include <QThread>
#include <QtTest>
#include <csignal>
#include <memory>

namespace {

QProcessEnvironment editorEnv(const QTemporaryDir& home) {
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.insert("QT_QPA_PLATFORM", "xcb");
    env.insert("HOME", home.path());
    env.insert("XDG_CONFIG_HOME", home.filePath("config"));
    env.insert("XDG_CACHE_HOME", home.filePath("cache"));
    env.insert("XDG_DATA_HOME", home.filePath("data"));
    return env;
}

bool waitForText(QProcess& p, QByteArray& seen, const QByteArray& text, int ms) {
    QElapsedTimer clock;
    clock.start();
    while (!seen.contains(text) && clock.elapsed() < ms) {
        p.waitForReadyRead(200);
        seen += p.readAllStandardError();
        if (p.state() == QProcess::NotRunning)
            break;
    }
    seen += p.readAllStandardError();
    return seen.contains(text);
}

} // namespace

class TestUiKilledEditor : public QObject {
    Q_OBJECT
private slots:
    void editSurvivesAKillThreeSecondsLater() {
        if (qEnvironmentVariableIsEmpty("DISPLAY"))
            QSKIP("needs a display (run through ctest: xvfb-run)");
        QTemporaryDir home;
        QVERIFY(home.isValid());
        const QStringList files{home.filePath("a.json"), home.filePath("b.json")};
        const QList<float> edits{0.123f, 0.456f};
        std::string error;
        for (const QString& f : files)
            QVERIFY2(velvet::saveSceneFile(velvet::defaultScene(), f.toStdString(), &error),
                     error.c_str());
        QThread::msleep(20); // the autosave's time must be later than the file's

        // Two editors, one edit each, then 3 s of nothing, then SIGKILL.
        std::vector<std::unique_ptr<QProcess>> editors;
        std::vector<QByteArray> seen(2);
        for (int i = 0; i < 2; ++i) {
            auto p = std::make_unique<QProcess>();
            QProcessEnvironment env = editorEnv(home);
            env.insert("VELVET_TEST_EDIT", QString::number(edits[i]));
            p->setProcessEnvironment(env);
            p->start(VELVET_BINARY, {files[i]});
            QVERIFY(p->waitForStarted());
            editors.push_back(std::move(p));
        }
        for (int i = 0; i < 2; ++i)
            QVERIFY2(waitForText(*editors[i], seen[i], "velvet-test: edited", 120000),
                     seen[i].constData());
        QThread::msleep(3000);
        for (auto& p : editors) {
            ::kill(pid_t(p->processId()), SIGKILL);
            QVERIFY(p->waitForFinished());
            QCOMPARE(p->exitStatus(), QProcess::CrashExit);
        }

        // Started again on each file: recovery is offered and the edit is back, unsaved.
        for (int i = 0; i < 2; ++i) {
            QProcess again;
            QProcessEnvironment env = editorEnv(home);
            env.insert("VELVET_TEST_ACCEPT_RECOVERY", "1");
            again.setProcessEnvironment(env);
            again.start(VELVET_BINARY, {files[i]});
            QVERIFY(again.waitForFinished(120000));
            const QString err = QString::fromUtf8(again.readAllStandardError());
            QCOMPARE(again.exitCode(), 0);
            QStringList found;
            QDirIterator it(home.filePath("data"), QDir::Files | QDir::Hidden,
                            QDirIterator::Subdirectories);
            while (it.hasNext())
                found << it.next();
            QVERIFY2(err.contains("velvet-test: recovery offered"),
                     qPrintable(err + "\nfirst run:\n" + QString::fromUtf8(seen[i]) +
                                "\nautosave folder:\n" + found.join('\n')));
            QVERIFY2(err.contains(QStringLiteral("roughness=%1 dirty=1").arg(edits[i])),
                     qPrintable(err));
        }
    }

    // The untitled document too: a plain start after the kill lists its autosave, and
    // recovering it brings the edit back, dirty.
    void untitledEditSurvivesAKill() {
        if (qEnvironmentVariableIsEmpty("DISPLAY"))
            QSKIP("needs a display (run through ctest: xvfb-run)");
        QTemporaryDir home;
        QVERIFY(home.isValid());
        QProcess editor;
        QProcessEnvironment env = editorEnv(home);
        env.insert("VELVET_TEST_EDIT", "0.789");
        editor.setProcessEnvironment(env);
        editor.start(VELVET_BINARY, {});
        QVERIFY(editor.waitForStarted());
        QByteArray seen;
        QVERIFY2(waitForText(editor, seen, "velvet-test: edited", 120000), seen.constData());
        QThread::msleep(3000);
        ::kill(pid_t(editor.processId()), SIGKILL);
        QVERIFY(editor.waitForFinished());
        QCOMPARE(editor.exitStatus(), QProcess::CrashExit);

        QProcess again;
        QProcessEnvironment againEnv = editorEnv(home);
        againEnv.insert("VELVET_TEST_ACCEPT_RECOVERY", "1");
        again.setProcessEnvironment(againEnv);
        again.start(VELVET_BINARY, {});
        QVERIFY(again.waitForFinished(120000));
        const QString err = QString::fromUtf8(again.readAllStandardError());
        QCOMPARE(again.exitCode(), 0);
        QVERIFY2(err.contains("velvet-test: startup recovery offered 1"),
                 qPrintable(err + "\nfirst run:\n" + QString::fromUtf8(seen)));
        QVERIFY2(err.contains("roughness=0.789 dirty=1"), qPrintable(err));
    }
};

QTEST_GUILESS_MAIN(TestUiKilledEditor)
#include "test_ui_killed_editor.moc"
