#pragma once
/// @file reference_job.h
/// The editor's ground truth in the background (issue 15, "a Reference toggle renders the
/// reference progressively on worker threads"): runs reference::render on a thread of its own,
/// one CPU thread fewer than the machine has (at least one), so the UI stays responsive, and
/// hands each converging image to the UI thread. start() again cancels the running render first
/// (a scene edit or a camera move restarts it).

#include "core/image.h"
#include "core/scene.h"

#include <QImage>
#include <QObject>
#include <QString>
#include <atomic>
#include <memory>
#include <thread>

namespace velvet::ui {

class ReferenceJob : public QObject {
    Q_OBJECT
public:
    explicit ReferenceJob(QObject* parent = nullptr);
    ~ReferenceJob() override;

    /// Renders @p scene at @p width x @p height, @p samples samples per pixel at most.
    void start(const Scene& scene, int width, int height, int samples = 1024);
    /// Cancels the running render (returns once its thread has stopped).
    void stop();
    bool running() const { return m_thread.joinable() && !m_done->load(); }

    /// Scene-linear RGB to the display: exposure 1, Khronos PBR Neutral, sRGB (IEC 61966-2-1).
    static QImage toDisplay(const Image& linear);

signals:
    /// The image so far (display-encoded) after @p passes samples per pixel.
    void imageReady(const QImage& image, int passes);
    void failed(const QString& message);

private:
    std::thread m_thread;
    std::shared_ptr<std::atomic<bool>> m_cancel;
    std::shared_ptr<std::atomic<bool>> m_done;
    int m_generation = 0;
};

} // namespace velvet::ui
