#include "ui/reference/reference_job.h"

#include "reference/reference_renderer.h"

#include <QMetaObject>
#include <QPointer>
#include <algorithm>
#include <cmath>
#include <mutex>

namespace velvet::ui {

struct ReferenceJob::Compared {
    std::mutex mutex;
    std::shared_ptr<const Image> image;
    int version = -1;

    std::pair<std::shared_ptr<const Image>, int> get() {
        const std::lock_guard lock(mutex);
        return {image, version};
    }
    void set(std::shared_ptr<const Image> next) {
        const std::lock_guard lock(mutex);
        image = std::move(next);
        ++version;
    }
};

ReferenceJob::ReferenceJob(QObject* parent) : QObject(parent) {}

ReferenceJob::~ReferenceJob() {
    stop();
}

Image ReferenceJob::displayImage(const Image& linear, float exposureEv) {
    Image scaled(linear.width, linear.height, 3);
    const float gain = std::exp2(exposureEv);
    for (int y = 0; y < linear.height; ++y)
        for (int x = 0; x < linear.width; ++x) {
            const glm::vec4 c = linear.rgba(x, y);
            float* o = scaled.at(x, y);
            o[0] = c.r * gain, o[1] = c.g * gain, o[2] = c.b * gain;
        }
    Image out = defaultDisplayTransform(scaled);
    // On 8-bit levels: the ΔE is of the pixels the view shows, and a test can recompute it
    // from the QImages exactly.
    for (float& v : out.pixels)
        v = float(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)) / 255.0f;
    return out;
}

QImage ReferenceJob::toQImage(const Image& display) {
    QImage out(display.width, display.height, QImage::Format_RGB888);
    for (int y = 0; y < display.height; ++y) {
        uchar* row = out.scanLine(y);
        for (int x = 0; x < display.width; ++x) {
            const glm::vec4 c = display.rgba(x, y);
            for (int k = 0; k < 3; ++k)
                row[x * 3 + k] = uchar(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
        }
    }
    return out;
}

Image ReferenceJob::fromQImage(const QImage& image) {
    const QImage rgb = image.convertToFormat(QImage::Format_RGB888);
    Image out(rgb.width(), rgb.height(), 3);
    for (int y = 0; y < rgb.height(); ++y) {
        const uchar* row = rgb.constScanLine(y);
        for (int x = 0; x < rgb.width(); ++x)
            for (int k = 0; k < 3; ++k)
                out.at(x, y)[k] = float(row[x * 3 + k]) / 255.0f;
    }
    return out;
}

void ReferenceJob::setViewport(const Image& viewport) {
    if (m_compared)
        m_compared->set(std::make_shared<const Image>(viewport));
}

void ReferenceJob::stop() {
    if (m_cancel)
        m_cancel->store(true);
    if (m_thread.joinable())
        m_thread.join();
}

void ReferenceJob::start(const Scene& scene, int width, int height, const Image& viewport,
                         float exposureEv, int samples) {
    stop();
    const int generation = ++m_generation;
    m_cancel = std::make_shared<std::atomic<bool>>(false);
    m_done = std::make_shared<std::atomic<bool>>(false);
    QPointer<ReferenceJob> self(this);
    reference::Options options;
    options.width = std::max(width, 1);
    options.height = std::max(height, 1);
    options.samplesPerPixel = samples;
    options.threads = std::max(1, int(std::thread::hardware_concurrency()) - 1);
    // Each image is encoded and compared on the worker and delivered to the UI thread only if
    // this render is still the current one (a restart bumps the generation).
    m_compared = std::make_shared<Compared>();
    m_compared->set(std::make_shared<const Image>(viewport));
    options.onPassImage = [self, generation, compared = m_compared,
                           exposureEv](const Image& soFar, const Image& coverage, int passes) {
        const auto [compareWith, version] = compared->get();
        ReferenceFrame frame;
        const Image display = displayImage(soFar, exposureEv);
        frame.image = toQImage(display);
        frame.passes = passes;
        frame.viewportVersion = version;
        frame.coverage = coverage;
        // The statistics are the material's: over the pixels the mesh covers, not the background
        // (the viewport may blur it, the path tracer shows it sharp) nor the silhouette's
        // partly covered pixels.
        DeltaEStats all;
        if (!compareWith->empty() &&
            compareImages(*compareWith, display, frame.deltaE, all, nullptr))
            frame.stats = deltaEStats(frame.deltaE, coverage);
        else
            frame.deltaE = Image(); // sizes differ: no comparison (the panel says so)
        QMetaObject::invokeMethod(
            self.data(),
            [self, generation, frame = std::move(frame)] {
                if (self && self->m_generation == generation)
                    emit self->imageReady(frame);
            },
            Qt::QueuedConnection);
    };
    m_thread = std::thread([scene, options, self, generation, cancel = m_cancel, done = m_done] {
        reference::Result result;
        std::string error;
        const bool ok =
            reference::render(scene, options, result, &error, nullptr, {}, cancel.get());
        done->store(true);
        if (!ok)
            QMetaObject::invokeMethod(
                self.data(),
                [self, generation, message = QString::fromStdString(error)] {
                    if (self && self->m_generation == generation)
                        emit self->failed(message);
                },
                Qt::QueuedConnection);
    });
}

} // namespace velvet::ui
