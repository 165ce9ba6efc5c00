#include "ui/reference/reference_job.h"

#include "core/tone_curves.h"
#include "reference/reference_renderer.h"

#include <QMetaObject>
#include <glm/common.hpp>
#include <QPointer>
#include <algorithm>
#include <cmath>

namespace velvet::ui {

namespace {

float srgbEncode(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

} // namespace

ReferenceJob::ReferenceJob(QObject* parent) : QObject(parent) {}

ReferenceJob::~ReferenceJob() {
    stop();
}

QImage ReferenceJob::toDisplay(const Image& linear) {
    QImage out(linear.width, linear.height, QImage::Format_RGB888);
    for (int y = 0; y < linear.height; ++y) {
        uchar* row = out.scanLine(y);
        for (int x = 0; x < linear.width; ++x) {
            const glm::vec4 c = linear.rgba(x, y);
            const glm::vec3 mapped =
                tone::khronosPbrNeutral(glm::max(glm::vec3(c), glm::vec3(0.0f)));
            for (int k = 0; k < 3; ++k)
                row[x * 3 + k] = uchar(std::lround(srgbEncode(mapped[k]) * 255.0f));
        }
    }
    return out;
}

void ReferenceJob::stop() {
    if (m_cancel)
        m_cancel->store(true);
    if (m_thread.joinable())
        m_thread.join();
}

void ReferenceJob::start(const Scene& scene, int width, int height, int samples) {
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
    // Each image is encoded on the worker and delivered to the UI thread only if this render is
    // still the current one (a restart bumps the generation).
    options.onPassImage = [self, generation](const Image& soFar, int passes) {
        const QImage image = toDisplay(soFar);
        QMetaObject::invokeMethod(
            self.data(),
            [self, generation, image, passes] {
                if (self && self->m_generation == generation)
                    emit self->imageReady(image, passes);
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
