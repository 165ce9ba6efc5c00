// bench_viewport [--window WxH] [--frames N] [--rounds R] [--no-check]: what the editor's viewport
// adds per frame over the bare renderer at the same size (issue 5, `viewport_overhead_ms`). Needs
// a display (run under xvfb-run); prints one JSON object. Three hosts draw the editor's default
// document (scene and frame settings taken from the editor) continuously:
//   editor    the real ui::MainWindow at WxH (docks, toolbars, status bar updated every frame);
//             its ViewportWidget draws in a QOpenGLWindow inside createWindowContainer. The
//             viewport's size in device pixels is the size every host renders at;
//   bare      Renderer::render into an offscreen framebuffer of a QOffscreenSurface context, each
//             frame waited for (its last timer query);
//   widget    for the record, the former host: a QOpenGLWidget drawing with the same renderer at
//             the viewport's size, beside a filler panel in a top-level of the editor's size (Qt
//             renders it into an FBO, then composes it with the window's backing store, so its
//             cost grows with the whole window).
// A host's frame time is the median interval between frameSwapped signals with a new frame asked
// for at each; its overhead is that minus the bare frame. Swap interval 0 (no vsync). The hosts
// take turns, R rounds of N frames each (after warm-up frames), and each median is over all
// rounds, so a burst of load on a shared machine lands on every host alike.
//
// Unless --no-check (the ctest runs the defaults: the editor at its own 1280x800, 3 rounds of 9
// frames): exit 1 unless the editor's viewport adds at most kMaxOverheadMs (5 ms, the issue's
// target) or kMaxOverheadFraction of the bare frame, whichever is larger. The fraction absorbs
// the run-to-run noise (a few ms) of frames that take tens of milliseconds on a shared llvmpipe
// machine (DESIGN.md, "Measuring": no bare absolute times); a measurement over the limit is taken
// once more before failing. The QOpenGLWidget figure is reported, not asserted: at small window
// sizes its extra cost is within that noise.
#include "core/scene.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "ui/document_controller.h"
#include "ui/main_window.h"
#include "ui/viewport_widget.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QHBoxLayout>
#include <QLabel>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLWidget>
#include <QOpenGLWindow>
#include <QStandardPaths>
#include <QTimer>
#include <QWidget>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

using namespace velvet;

namespace {

constexpr double kMaxOverheadMs = 5.0;
constexpr double kMaxOverheadFraction = 0.10;
constexpr int kWarmUp = 3;

double median(std::vector<double> v) {
    if (v.empty())
        return -1.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void append(std::vector<double>& to, const std::vector<double>& from) {
    to.insert(to.end(), from.begin(), from.end());
}

/// The former host, for the record: a QOpenGLWidget over the same renderer.
class RendererWidget : public QOpenGLWidget {
public:
    RendererWidget(Scene scene, render::FrameSettings settings)
        : m_scene(std::move(scene)), m_settings(std::move(settings)) {}
    ~RendererWidget() override {
        makeCurrent();
        renderer.reset();
        doneCurrent();
    }
    std::unique_ptr<render::Renderer> renderer;
    std::string error;

protected:
    void initializeGL() override {
        renderer = std::make_unique<render::Renderer>();
        if (!renderer->initialize(&error)) {
            renderer.reset();
            return;
        }
        renderer->setScene(m_scene);
        renderer->finishEnvironment();
        renderer->finishGraph();
    }
    void paintGL() override {
        if (!renderer)
            return;
        render::FrameSettings fs = m_settings;
        const qreal dpr = devicePixelRatioF();
        fs.width = std::max(1, int(width() * dpr));
        fs.height = std::max(1, int(height() * dpr));
        if (!renderer->render(fs, defaultFramebufferObject(), &error))
            renderer.reset();
    }

private:
    Scene m_scene;
    render::FrameSettings m_settings;
};

/// Intervals between @p signal of @p host over @p frames frames, after kWarmUp frames, calling
/// @p request for a new frame at each.
template <class Host>
std::vector<double> frameIntervals(Host* host, void (Host::*signal)(),
                                   const std::function<void()>& request, int frames) {
    std::vector<double> intervals;
    QElapsedTimer clock;
    int seen = 0;
    QEventLoop loop;
    auto conn = QObject::connect(host, signal, host, [&] {
        ++seen;
        if (seen > kWarmUp) {
            if (clock.isValid())
                intervals.push_back(double(clock.nsecsElapsed()) / 1e6);
            clock.restart();
        }
        if (int(intervals.size()) >= frames)
            loop.quit();
        else
            request();
    });
    QTimer timeout;
    timeout.setSingleShot(true);
    QObject::connect(&timeout, &QTimer::timeout, &loop, &QEventLoop::quit);
    timeout.start(300000);
    request();
    loop.exec();
    QObject::disconnect(conn);
    return intervals;
}

} // namespace

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // the editor's settings and autosave go elsewhere
    QSurfaceFormat format = ui::ViewportWidget::requiredFormat();
    format.setSwapInterval(0);
    QSurfaceFormat::setDefaultFormat(format);
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetBenchViewport"));
    int windowWidth = 1280, windowHeight = 800, frames = 9, rounds = 3;
    bool check = true;
    const QStringList args = QApplication::arguments();
    for (int i = 1; i < args.size(); ++i) {
        const bool hasValue = i + 1 < args.size();
        if (args[i] == QLatin1String("--no-check")) {
            check = false;
        } else if (args[i] == QLatin1String("--window") && hasValue) {
            const QStringList wh = args[++i].split(QLatin1Char('x'));
            if (wh.size() == 2)
                windowWidth = wh[0].toInt(), windowHeight = wh[1].toInt();
        } else if (args[i] == QLatin1String("--frames") && hasValue) {
            frames = std::max(3, args[++i].toInt());
        } else if (args[i] == QLatin1String("--rounds") && hasValue) {
            rounds = std::max(1, args[++i].toInt());
        }
    }

    // 1. The editor, on its default document; its environment baked before timing.
    ui::MainWindow editor(/*restoreLayout=*/false);
    ui::ViewportWidget* viewport = editor.viewport();
    viewport->setReducedResolution(false);
    editor.resize(windowWidth, windowHeight);
    editor.show();
    QElapsedTimer wait;
    wait.start();
    while ((viewport->renderer() == nullptr || viewport->environmentProgress() < 1.0) &&
           viewport->errorMessage().isEmpty() && wait.elapsed() < 120000) {
        viewport->requestFrame();
        QApplication::processEvents(QEventLoop::AllEvents, 50);
    }
    if (!viewport->errorMessage().isEmpty() || !viewport->renderer()) {
        std::fprintf(stderr, "bench_viewport: %s\n", qPrintable(viewport->errorMessage()));
        return 3;
    }
    const qreal dpr = viewport->glWindow()->devicePixelRatio();
    const int width = std::max(1, int(std::lround(viewport->glWindow()->width() * dpr)));
    const int height = std::max(1, int(std::lround(viewport->glWindow()->height() * dpr)));
    const Scene scene = editor.controller()->scene();
    const render::FrameSettings settings = viewport->frameSettings();
    editor.hide();

    // 2. Bare renderer: its own context on an offscreen surface.
    QOffscreenSurface surface;
    surface.setFormat(format);
    surface.create();
    QOpenGLContext context;
    context.setFormat(format);
    if (!context.create() || !context.makeCurrent(&surface)) {
        std::fprintf(stderr, "bench_viewport: no OpenGL context\n");
        return 3;
    }
    std::string error;
    // Freed before the context (their GL objects need it current).
    auto bare = std::make_unique<std::pair<render::Renderer, render::OffscreenTarget>>();
    if (!bare->first.initialize(&error) || !bare->second.resize(width, height, &error)) {
        std::fprintf(stderr, "bench_viewport: %s\n", error.c_str());
        return 3;
    }
    bare->first.setScene(scene);
    bare->first.finishEnvironment();
    bare->first.finishGraph();
    context.doneCurrent();
    auto bareFrames = [&](int count, std::vector<double>* times) {
        context.makeCurrent(&surface);
        render::FrameSettings fs = settings;
        fs.width = width, fs.height = height;
        for (int i = 0; i < kWarmUp + count; ++i) {
            QElapsedTimer t;
            t.start();
            if (!bare->first.render(fs, bare->second.framebuffer(), &error))
                break;
            bare->first.lastTimings(); // waits for the frame's timer queries
            if (i >= kWarmUp)
                times->push_back(double(t.nsecsElapsed()) / 1e6);
        }
        context.doneCurrent();
        return error.empty();
    };

    // 3. The former QOpenGLWidget host, in a top-level of the editor's size.
    QWidget widgetTop;
    auto* layout = new QHBoxLayout(&widgetTop);
    layout->setContentsMargins(0, 0, 0, 0);
    auto* widget = new RendererWidget(scene, settings);
    widget->setFixedSize(QSize(width, height) / dpr);
    layout->addWidget(widget);
    layout->addWidget(new QLabel(QStringLiteral("panels"), &widgetTop), 1);
    widgetTop.resize(editor.size());

    // One measurement: R rounds, the hosts taking turns. False on a rendering error.
    struct Result {
        double bare = -1, editor = -1, widget = -1;
        double viewportOverhead() const { return editor - bare; }
        double widgetOverhead() const { return widget - bare; }
        double allowed() const { return std::max(kMaxOverheadMs, kMaxOverheadFraction * bare); }
        bool valid() const { return bare > 0 && editor > 0 && widget > 0; }
    };
    auto measure = [&](Result* result) {
        std::vector<double> bareMs, editorMs, widgetMs;
        for (int round = 0; round < rounds; ++round) {
            if (!bareFrames(frames, &bareMs)) {
                std::fprintf(stderr, "bench_viewport: %s\n", error.c_str());
                return false;
            }
            editor.show();
            append(editorMs, frameIntervals<QOpenGLWindow>(
                                 viewport->glWindow(), &QOpenGLWindow::frameSwapped,
                                 [&] { viewport->requestFrame(); }, frames));
            editor.hide();
            widgetTop.show();
            append(widgetMs,
                   frameIntervals<QOpenGLWidget>(
                       widget, &QOpenGLWidget::frameSwapped, [&] { widget->update(); }, frames));
            widgetTop.hide();
            if (!widget->renderer && !widget->error.empty()) {
                std::fprintf(stderr, "bench_viewport: %s\n", widget->error.c_str());
                return false;
            }
            if (!viewport->errorMessage().isEmpty()) {
                std::fprintf(stderr, "bench_viewport: %s\n", qPrintable(viewport->errorMessage()));
                return false;
            }
        }
        *result = {median(bareMs), median(editorMs), median(widgetMs)};
        return result->valid();
    };
    auto print = [&](const Result& r, int attempt) {
        std::printf("{\"window_width\": %d, \"window_height\": %d, \"width\": %d, "
                    "\"height\": %d, \"frames\": %d, \"rounds\": %d, \"attempt\": %d, "
                    "\"bare_ms\": %.3f, \"viewport_frame_ms\": %.3f, \"widget_frame_ms\": %.3f, "
                    "\"viewport_overhead_ms\": %.3f, \"widget_overhead_ms\": %.3f, "
                    "\"viewport_overhead_allowed_ms\": %.3f}\n",
                    editor.width(), editor.height(), width, height, frames, rounds, attempt, r.bare,
                    r.editor, r.widget, r.viewportOverhead(), r.widgetOverhead(), r.allowed());
        std::fflush(stdout);
    };

    Result result;
    bool ok = measure(&result);
    if (ok)
        print(result, 1);
    // A burst of load from elsewhere can push one measurement over; a real regression (a host
    // that adds a fixed cost to every frame) fails a second one as well.
    if (ok && check && result.viewportOverhead() > result.allowed()) {
        ok = measure(&result);
        if (ok)
            print(result, 2);
    }

    // Free the bare renderer with its context current.
    context.makeCurrent(&surface);
    bare.reset();
    context.doneCurrent();

    if (!ok)
        return 1;
    if (check && result.viewportOverhead() > result.allowed()) {
        std::fprintf(stderr,
                     "bench_viewport: the editor's viewport adds %.2f ms a frame over the bare "
                     "renderer (%.2f ms); allowed %.2f ms\n",
                     result.viewportOverhead(), result.bare, result.allowed());
        return 1;
    }
    return 0;
}
