#pragma once
/// @file reference_job.h
/// The editor's ground truth in the background (issue 15, "a Reference toggle renders the
/// reference progressively on worker threads"): runs reference::render on a thread of its own,
/// one CPU thread fewer than the machine has (at least one), so the UI stays responsive, and
/// hands each converging image to the UI thread with its per-pixel CIEDE2000 against the
/// viewport's image, computed on the worker too. start() again cancels the running render first
/// (a scene edit or a camera move restarts it).

#include "core/image.h"
#include "core/image_compare.h"
#include "core/scene.h"

#include <QImage>
#include <QObject>
#include <QString>
#include <atomic>
#include <memory>
#include <thread>

namespace velvet::ui {

/// One converging image of the reference and how far the viewport's departs from it.
struct ReferenceFrame {
    QImage image;      ///< the reference, display-referred (displayImage), RGB888
    Image deltaE;      ///< per-pixel ΔE2000 against the viewport's image; empty without one
    Image coverage;    ///< per pixel, the fraction of the reference's samples on the mesh
    DeltaEStats stats; ///< of deltaE over the pixels the mesh covers (coverage 1)
    int passes = 0;    ///< samples per pixel so far
    /// Which viewport image deltaE is against: 0 the one given to start, n the n-th given to
    /// setViewport since.
    int viewportVersion = 0;
};

class ReferenceJob : public QObject {
    Q_OBJECT
public:
    explicit ReferenceJob(QObject* parent = nullptr);
    ~ReferenceJob() override;

    /// Renders @p scene at @p width x @p height, @p samples samples per pixel at most, each image
    /// through displayImage(@p exposureEv) and compared with @p viewport (display-referred, the
    /// same size; empty: no comparison).
    void start(const Scene& scene, int width, int height, const Image& viewport,
               float exposureEv = 0.0f, int samples = 1024);
    /// Compares the running render's next images with @p viewport instead (display-referred,
    /// the size given to start): the viewport's view at rest, once it has settled.
    void setViewport(const Image& viewport);
    /// Cancels the running render (returns once its thread has stopped).
    void stop();
    bool running() const { return m_thread.joinable() && !m_done->load(); }

    /// The display transform both sides of the comparison go through, so the ΔE is the
    /// difference between two images shown alike: scene-linear x 2^@p exposureEv, then `velvet
    /// compare`'s transform (defaultDisplayTransform: Khronos PBR Neutral, sRGB encoding), each
    /// channel rounded to 8 bits as the view shows it. RGB.
    static Image displayImage(const Image& linear, float exposureEv);
    /// A display-referred RGB image in [0, 1] as 8-bit RGB (values already on 8-bit levels).
    static QImage toQImage(const Image& display);
    /// The inverse: an 8-bit image's channels / 255, RGB.
    static Image fromQImage(const QImage& image);

signals:
    /// The image so far, its comparison with the viewport, after frame.passes samples per pixel.
    void imageReady(const velvet::ui::ReferenceFrame& frame);
    void failed(const QString& message);

private:
    struct Compared; ///< the viewport's image the worker compares with, replaceable meanwhile
    std::shared_ptr<Compared> m_compared;
    std::thread m_thread;
    std::shared_ptr<std::atomic<bool>> m_cancel;
    std::shared_ptr<std::atomic<bool>> m_done;
    int m_generation = 0;
};

} // namespace velvet::ui
