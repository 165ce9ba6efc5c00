#pragma once
/// @file run_velvet.h
/// Runs the real `velvet` executable for the app tests: its exit code and status, stdout and
/// stderr, with a time limit so a hang fails instead of blocking the suite. By default without a
/// display (the CLI must not need one).

#include <QMap>
#include <QProcess>
#include <QString>
#include <QStringList>

namespace velvet::test {

struct Result {
    int exitCode = -1;
    QProcess::ExitStatus status = QProcess::CrashExit;
    QString out, err;
};

enum class Display { Keep, None };

struct RunOptions {
    Display display = Display::None;
    QString workingDir;              ///< empty: the test's own
    QMap<QString, QString> extraEnv; ///< added to (or replacing) the environment
    int timeoutMs = 180000;
};

inline Result runVelvet(const QStringList& args, const RunOptions& options = {}) {
    QProcess p;
    if (!options.workingDir.isEmpty())
        p.setWorkingDirectory(options.workingDir);
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    if (options.display == Display::None) {
        env.remove("DISPLAY");
        env.remove("WAYLAND_DISPLAY");
        env.remove("QT_QPA_PLATFORM");
    }
    for (auto it = options.extraEnv.begin(); it != options.extraEnv.end(); ++it)
        env.insert(it.key(), it.value());
    p.setProcessEnvironment(env);
    p.start(VELVET_BINARY, args);
    Result r;
    if (!p.waitForFinished(options.timeoutMs)) {
        p.kill();
        p.waitForFinished();
        return r;
    }
    r.exitCode = p.exitCode();
    r.status = p.exitStatus();
    r.out = QString::fromUtf8(p.readAllStandardOutput());
    r.err = QString::fromUtf8(p.readAllStandardError());
    return r;
}

} // namespace velvet::test
