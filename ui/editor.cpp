#include "ui/editor.h"

#include "ui/autosave.h"
#include "ui/document_controller.h"
#include "ui/main_window.h"
#include "ui/screenshot.h"
#include "ui/viewport_widget.h"

#include <QApplication>
#include <QOpenGLContext>
#include <QSurfaceFormat>
#include <QTimer>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <utility>

namespace velvet::ui {
namespace {

constexpr int kExitRenderFailure = 3;
constexpr int kScreenshotTimeoutMs = 120000; // llvmpipe compiles shaders slowly; never hang
/// The longest a screenshot waits for the still view's anti-aliasing to settle.
constexpr int kRefineWaitMs = 10000;

/// True when Qt's platform plugin would find a display to talk to.
bool haveDisplay() {
    if (!qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM"))
        return true; // the user chose a platform; let Qt report its own problems
#if defined(Q_OS_LINUX)
    return !qEnvironmentVariableIsEmpty("DISPLAY") ||
           !qEnvironmentVariableIsEmpty("WAYLAND_DISPLAY");
#else
    return true;
#endif
}

/// Whether the default format gives an OpenGL 4.5 core context on this display.
bool haveGl45(QString* found) {
    QOpenGLContext context;
    if (!context.create()) {
        *found = QStringLiteral("no OpenGL context could be created");
        return false;
    }
    const QSurfaceFormat f = context.format();
    *found = QStringLiteral("got OpenGL %1.%2%3")
                 .arg(f.majorVersion())
                 .arg(f.minorVersion())
                 .arg(f.profile() == QSurfaceFormat::CoreProfile ? " core" : "");
    return f.version() >= qMakePair(4, 5) && f.profile() == QSurfaceFormat::CoreProfile;
}

void fail(const QString& message) {
    std::fprintf(stderr, "velvet: %s\n", qPrintable(message));
}

/// Test hooks for the process tests (tests/ui/test_ui_killed_editor.cpp), off unless set:
/// VELVET_TEST_EDIT=V sets the material's roughness to V through the undo stack after the first
/// frame (a real edit: dirty, debounced autosave) and prints "velvet-test: edited";
/// VELVET_TEST_ACCEPT_RECOVERY=1 answers the recovery question with yes, prints
/// "velvet-test: recovery offered" (at a plain start: recovers the newest untitled autosave), then
/// prints the document's roughness and dirty state and quits.
void installTestHooks(MainWindow& window) {
    const QByteArray edit = qgetenv("VELVET_TEST_EDIT");
    if (!edit.isEmpty()) {
        // After the first frame, as an artist edits a window that shows: the start-up's shader
        // compiles (seconds on llvmpipe) are not what the autosave's 2 s are measured against.
        const float value = edit.toFloat();
        auto done = std::make_shared<bool>(false);
        QObject::connect(window.viewport(), &ViewportWidget::frameCompleted, &window,
                         [&window, value, done] {
                             if (std::exchange(*done, true))
                                 return;
                             window.controller()->editParam(ParamId::Roughness, glm::vec3(value));
                             std::fprintf(stderr, "velvet-test: edited\n");
                         });
    }
    if (qEnvironmentVariableIsSet("VELVET_TEST_ACCEPT_RECOVERY")) {
        window.autosave()->setPrompt([](const QString&, const QDateTime&) {
            std::fprintf(stderr, "velvet-test: recovery offered\n");
            return true;
        });
        // A plain start lists every autosave: the test takes the newest untitled one.
        window.autosave()->setStartupChooser([](const QList<Autosave::Recoverable>& found) {
            std::fprintf(stderr, "velvet-test: startup recovery offered %lld\n",
                         static_cast<long long>(found.size()));
            std::optional<Autosave::Recoverable> chosen;
            for (const Autosave::Recoverable& r : found)
                if (r.documentPath.isEmpty()) {
                    chosen = r;
                    break;
                }
            return chosen;
        });
        QTimer::singleShot(0, &window, [&window] {
            const DocumentController* doc = window.controller();
            std::fprintf(stderr, "velvet-test: roughness=%g dirty=%d\n",
                         double(doc->scene().material.value(ParamId::Roughness).x),
                         doc->isDirty() ? 1 : 0);
            QApplication::exit(0);
        });
    }
}

} // namespace

int runEditor(int& argc, char** argv, const EditorOptions& options) {
    if (!haveDisplay()) {
        fail(QStringLiteral("no display to open the editor on (DISPLAY is not set); "
                            "use `velvet render` to render without one"));
        return kExitRenderFailure;
    }
    // Must precede QApplication: the shared default format is read when contexts are made.
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("Velvet"));
    QApplication::setOrganizationName(QStringLiteral("Velvet"));
    QApplication::setApplicationDisplayName(QStringLiteral("Velvet"));

    QString found;
    if (!haveGl45(&found)) {
        fail(QStringLiteral("OpenGL 4.5 core is needed and this display does not offer it (%1)")
                 .arg(found));
        return kExitRenderFailure;
    }

    const bool screenshot = !options.screenshotFile.empty();
    MainWindow window(/*restoreLayout=*/!screenshot);
    const QString openFile = QString::fromStdString(options.openFile);
    if (!screenshot) {
        window.show();
        installTestHooks(window);
        if (!openFile.isEmpty())
            window.openFile(openFile); // problems appear in a message box over the default scene
        else
            // Every autosave a crash or kill left behind, saved documents' and untitled ones'.
            window.autosave()->offerStartupRecovery(&window);
        return QApplication::exec();
    }
    if (!openFile.isEmpty()) {
        QStringList problems;
        if (!window.controller()->openFile(openFile, &problems)) {
            for (const QString& line : problems)
                fail(line);
            return 2; // bad input, as the CLI reports it
        }
    }

    // Screenshot mode: a fixed size for reproducible README images, then one frame, then exit.
    const QString file = QString::fromStdString(options.screenshotFile);
    int exitCode = kExitRenderFailure;
    ViewportWidget* viewport = window.viewport();
    bool grabbed = false, refining = false;
    const auto grab = [&] {
        if (grabbed)
            return;
        grabbed = true;
        // Let the frame reach the window before grabbing it.
        QTimer::singleShot(0, &window, [&] {
            QString error;
            if (saveScreenshot(&window, file, &error)) {
                exitCode = 0;
            } else {
                fail(QStringLiteral("could not save the screenshot %1: %2").arg(file, error));
            }
            QApplication::exit(exitCode);
        });
    };
    QObject::connect(viewport, &ViewportWidget::frameCompleted, &window, [&] {
        // Wait for the environment bake (the main window keeps frames coming meanwhile), so the
        // image shows the finished lighting, and for the still view's anti-aliasing to settle
        // (ViewportWidget's progressive frames; a scene that animates never settles).
        const double progress = viewport->environmentProgress();
        if (grabbed || (progress >= 0.0 && progress < 1.0))
            return;
        const bool settled = !viewport->progressiveAntialiasing() || viewport->isAnimating() ||
                             viewport->progressiveSamples() >= ViewportWidget::kProgressiveSamples;
        if (settled)
            return grab();
        if (!refining) { // whatever keeps the view from settling, the screenshot still comes
            refining = true;
            QTimer::singleShot(kRefineWaitMs, &window, grab);
        }
    });
    QObject::connect(viewport, &ViewportWidget::renderFailed, &window, [&](const QString& m) {
        fail(m);
        QApplication::exit(kExitRenderFailure);
    });
    QTimer::singleShot(kScreenshotTimeoutMs, &window, [&] {
        fail(QStringLiteral("no frame was drawn within %1 s").arg(kScreenshotTimeoutMs / 1000));
        QApplication::exit(kExitRenderFailure);
    });
    window.resize(1280, 800);
    window.show();
    QApplication::exec();
    return exitCode;
}

} // namespace velvet::ui
