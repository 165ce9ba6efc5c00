// bench_viewport [--size WxH] [--frames N]: what the editor's viewport adds per frame over the
// bare renderer at the same size (issue 5, `viewport_overhead_ms`). Needs a display (run under
// xvfb-run); prints one JSON object. Three hosts draw the default sphere continuously:
//   bare    Renderer::render into an offscreen framebuffer of a QOffscreenSurface context, each
//           frame waited for (its last timer query);
//   widget  the editor's ViewportWidget (a QOpenGLWidget: Qt renders into an FBO, then composes
//           it into the window's backing store);
//   window  a QOpenGLWindow drawing with the same renderer, inside createWindowContainer.
// A host's frame time is the median interval between frameSwapped signals with update() asked
// for at each; its overhead is that minus the bare frame. Swap interval 0 (no vsync).
#include "render/offscreen.h"
#include "render/renderer.h"
#include "ui/viewport_widget.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLWindow>
#include <QTimer>
#include <QVBoxLayout>
#include <QWidget>
#include <algorithm>
#include <cstdio>
#include <memory>
#include <utility>
#include <vector>

using namespace velvet;

namespace {

double median(std::vector<double> v) {
    if (v.empty())
        return -1.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// A QOpenGLWindow over the same renderer: the alternative to QOpenGLWidget.
class RendererWindow : public QOpenGLWindow {
public:
    ~RendererWindow() override {
        makeCurrent();
        renderer.reset();
        doneCurrent();
    }
    std::unique_ptr<render::Renderer> renderer;
    std::string error;

protected:
    void initializeGL() override {
        renderer = std::make_unique<render::Renderer>();
        if (!renderer->initialize(&error))
            renderer.reset();
        else
            renderer->finishEnvironment();
    }
    void paintGL() override {
        if (!renderer)
            return;
        render::FrameSettings fs;
        const qreal dpr = devicePixelRatio();
        fs.width = std::max(1, int(width() * dpr));
        fs.height = std::max(1, int(height() * dpr));
        if (!renderer->render(fs, defaultFramebufferObject(), &error))
            renderer.reset();
    }
};

/// Median interval between frameSwapped signals of @p emitter over @p frames frames, after
/// @p warmUp frames, asking for a new frame at each swap.
template <class Host>
double frameInterval(Host* host, int warmUp, int frames) {
    std::vector<double> intervals;
    QElapsedTimer clock;
    int seen = 0;
    QEventLoop loop;
    auto conn = QObject::connect(host, &Host::frameSwapped, host, [&] {
        ++seen;
        if (seen > warmUp) {
            if (clock.isValid())
                intervals.push_back(double(clock.nsecsElapsed()) / 1e6);
            clock.restart();
        }
        if (int(intervals.size()) >= frames)
            loop.quit();
        else
            host->update();
    });
    QTimer::singleShot(300000, &loop, &QEventLoop::quit);
    host->update();
    loop.exec();
    QObject::disconnect(conn);
    return median(intervals);
}

} // namespace

int main(int argc, char** argv) {
    QSurfaceFormat format = ui::ViewportWidget::requiredFormat();
    format.setSwapInterval(0);
    QSurfaceFormat::setDefaultFormat(format);
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    int width = 320, height = 240, frames = 10;
    const QStringList args = QApplication::arguments();
    for (int i = 1; i + 1 < args.size(); ++i) {
        if (args[i] == QLatin1String("--size")) {
            const QStringList wh = args[i + 1].split(QLatin1Char('x'));
            if (wh.size() == 2)
                width = wh[0].toInt(), height = wh[1].toInt();
        } else if (args[i] == QLatin1String("--frames")) {
            frames = std::max(3, args[i + 1].toInt());
        }
    }
    const int warmUp = 3;

    // 1. Bare renderer.
    double bareMs = -1.0;
    std::string glRenderer;
    {
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
        // Freed before doneCurrent (their GL objects need the context).
        auto owned = std::make_unique<std::pair<render::Renderer, render::OffscreenTarget>>();
        render::Renderer& renderer = owned->first;
        render::OffscreenTarget& target = owned->second;
        if (!renderer.initialize(&error) || !target.resize(width, height, &error)) {
            std::fprintf(stderr, "bench_viewport: %s\n", error.c_str());
            return 3;
        }
        renderer.finishEnvironment();
        render::FrameSettings fs;
        fs.width = width, fs.height = height;
        std::vector<double> times;
        for (int i = 0; i < warmUp + frames; ++i) {
            QElapsedTimer t;
            t.start();
            if (!renderer.render(fs, target.framebuffer(), &error)) {
                std::fprintf(stderr, "bench_viewport: %s\n", error.c_str());
                return 3;
            }
            renderer.lastTimings(); // waits for the frame's timer queries
            if (i >= warmUp)
                times.push_back(double(t.nsecsElapsed()) / 1e6);
        }
        bareMs = median(times);
        owned.reset();
        context.doneCurrent();
    }

    // 2. The editor's QOpenGLWidget.
    double widgetMs = -1.0;
    {
        QWidget top;
        auto* layout = new QVBoxLayout(&top);
        layout->setContentsMargins(0, 0, 0, 0);
        auto* viewport = new ui::ViewportWidget(&top);
        viewport->setReducedResolution(false);
        viewport->setFixedSize(width, height);
        layout->addWidget(viewport);
        top.show();
        // Let the environment bake finish before timing.
        QElapsedTimer wait;
        wait.start();
        while ((viewport->renderer() == nullptr || viewport->environmentProgress() < 1.0) &&
               viewport->errorMessage().isEmpty() && wait.elapsed() < 120000) {
            viewport->update();
            QApplication::processEvents(QEventLoop::AllEvents, 50);
        }
        if (!viewport->errorMessage().isEmpty()) {
            std::fprintf(stderr, "bench_viewport: %s\n", qPrintable(viewport->errorMessage()));
            return 3;
        }
        widgetMs = frameInterval<QOpenGLWidget>(viewport, warmUp, frames);
    }

    // 3. A QOpenGLWindow in a window container.
    double windowMs = -1.0;
    {
        QWidget top;
        auto* layout = new QVBoxLayout(&top);
        layout->setContentsMargins(0, 0, 0, 0);
        auto* window = new RendererWindow;
        QWidget* container = QWidget::createWindowContainer(window, &top);
        container->setFixedSize(width, height);
        layout->addWidget(container);
        top.show();
        windowMs = frameInterval<QOpenGLWindow>(window, warmUp, frames);
        if (!window->renderer && !window->error.empty()) {
            std::fprintf(stderr, "bench_viewport: %s\n", window->error.c_str());
            return 3;
        }
    }

    std::printf("{\"width\": %d, \"height\": %d, \"frames\": %d, \"bare_ms\": %.3f, "
                "\"widget_frame_ms\": %.3f, \"window_frame_ms\": %.3f, "
                "\"widget_overhead_ms\": %.3f, \"window_overhead_ms\": %.3f, "
                "\"viewport_overhead_ms\": %.3f}\n",
                width, height, frames, bareMs, widgetMs, windowMs, widgetMs - bareMs,
                windowMs - bareMs, widgetMs - bareMs);
    return bareMs > 0 && widgetMs > 0 && windowMs > 0 ? 0 : 1;
}
