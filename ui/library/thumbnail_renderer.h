#pragma once
/// @file thumbnail_renderer.h
/// Material preset thumbnails rendered by Velvet itself (issue 5, "Library"): a worker QThread
/// with its own headless OpenGL context (render::HeadlessContext, made once on that thread and
/// destroyed there) renders thumbnailScene(preset) (core/default_stage.h, the rule `velvet
/// thumbnails` shares: fabrics on the cloth drape) at kSize x kSize, one preset after the
/// other, and writes a PNG into the cache folder keyed by a hash of the preset file's contents and
/// kRendererVersion, so later starts load them without rendering. No GL calls here: the worker
/// only uses render/ (HeadlessContext, Renderer, OffscreenTarget).

#include <QImage>
#include <QObject>
#include <QString>
#include <QThread>
#include <atomic>

namespace velvet::ui {

class ThumbnailWorker;

class ThumbnailRenderer : public QObject {
    Q_OBJECT
public:
    /// Thumbnail side in pixels.
    static constexpr int kSize = 96;
    /// Bump when the renderer's look changes (shaders, default scene) so cached thumbnails
    /// are rendered again.
    /// Bumped when thumbnails change look (2: fabrics on the cloth drape; lobes per pixel;
    /// 3: the look-dev stage of core/default_stage.h, shared with `velvet thumbnails`).
    static constexpr const char* kRendererVersion = "velvet-thumbnails-3";

    /// @p cacheDir: where PNGs are kept; empty: QStandardPaths::CacheLocation/thumbnails.
    explicit ThumbnailRenderer(const QString& cacheDir = {}, QObject* parent = nullptr);
    /// Stops the worker after the render in progress (pending requests are dropped).
    ~ThumbnailRenderer() override;

    QString cacheDir() const { return m_cacheDir; }
    /// The cache file of a preset with file contents @p contents.
    QString cachePath(const QByteArray& contents) const;

    /// Asks for @p presetFile's thumbnail. A cached one is read at once and thumbnailReady is
    /// emitted (queued, so callers can connect after requesting); otherwise the preset is queued
    /// for the worker. Returns false when the file cannot be read (thumbnailFailed is emitted).
    bool request(const QString& presetFile);

    /// Renders the worker has done (cache hits are not renders).
    int renderCount() const { return m_renders.load(); }
    /// Requests answered from the cache.
    int cacheHits() const { return m_cacheHits; }
    /// Requests not answered yet.
    int pending() const { return m_pending; }

signals:
    void thumbnailReady(const QString& presetFile, const QImage& image);
    void thumbnailFailed(const QString& presetFile, const QString& error);

private:
    void onRendered(const QString& presetFile, const QImage& image, const QString& error);

    QString m_cacheDir;
    QThread m_thread;
    ThumbnailWorker* m_worker = nullptr; ///< lives on m_thread, deleted there
    std::atomic<int> m_renders{0};
    int m_cacheHits = 0;
    int m_pending = 0;
};

} // namespace velvet::ui
