#include "ui/library/thumbnail_renderer.h"

#include "core/default_stage.h"
#include "core/document_io.h"
#include "core/image.h"
#include "render/headless_context.h"
#include "render/offscreen.h"
#include "render/renderer.h"

#include <QCryptographicHash>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QMetaObject>
#include <QStandardPaths>
#include <algorithm>
#include <cmath>
#include <memory>

namespace velvet::ui {
namespace {

/// A display-encoded image (values in [0, 1]) as an opaque 8-bit QImage.
QImage toQImage(const Image& pixels) {
    QImage image(pixels.width, pixels.height, QImage::Format_RGB32);
    auto to8 = [](float v) {
        return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    };
    for (int y = 0; y < pixels.height; ++y) {
        auto* line = reinterpret_cast<QRgb*>(image.scanLine(y));
        for (int x = 0; x < pixels.width; ++x) {
            const glm::vec4 c = pixels.rgba(x, y);
            line[x] = qRgb(to8(c.r), to8(c.g), to8(c.b));
        }
    }
    return image;
}

} // namespace

/// Runs on the thumbnail thread. The context, renderer and target are made on the first job and
/// destroyed in the destructor, which runs on the same thread (QThread::finished -> deleteLater).
class ThumbnailWorker : public QObject {
    Q_OBJECT
public:
    explicit ThumbnailWorker(std::atomic<int>* renders) : m_renders(renders) {}
    ~ThumbnailWorker() override {
        // GL objects first, with their context still current; then the context.
        m_target.reset();
        m_renderer.reset();
        m_context.reset();
    }

public slots:
    void render(const QString& presetFile, const QByteArray& contents, const QString& cachePath) {
        QString error;
        const Image pixels = renderPreset(presetFile, contents, &error);
        QImage image;
        if (!pixels.empty()) {
            m_renders->fetch_add(1);
            image = toQImage(pixels);
            // The cache goes through the project's image I/O (OpenImageIO, atomic temp + rename),
            // as an 8-bit PNG of the display-encoded frame. A failed write only costs a re-render.
            QDir().mkpath(QFileInfo(cachePath).absolutePath());
            std::string message;
            if (!writeImage(cachePath.toStdString(), pixels, PixelFormat::UInt8, &message))
                qWarning("thumbnail cache: %s", message.c_str());
        }
        emit rendered(presetFile, image, error);
    }

signals:
    void rendered(const QString& presetFile, const QImage& image, const QString& error);

private:
    bool ensureRenderer(std::string* error) {
        if (m_failed)
            return false;
        if (!m_context) {
            // A context of our own on this thread; never another thread's (EGL contexts are
            // current per thread).
            m_context = render::HeadlessContext::create(error);
            if (!m_context) {
                m_failed = true;
                return false;
            }
            m_renderer = std::make_unique<render::Renderer>();
            if (!m_renderer->initialize(error)) {
                m_failed = true;
                return false;
            }
            m_target = std::make_unique<render::OffscreenTarget>();
            if (!m_target->resize(ThumbnailRenderer::kSize, ThumbnailRenderer::kSize, error)) {
                m_failed = true;
                return false;
            }
        }
        return true;
    }

    /// The preset's display-encoded thumbnail (RGBA in [0, 1]); empty + @p error on failure.
    Image renderPreset(const QString& presetFile, const QByteArray& contents, QString* error) {
        Problems problems;
        const std::filesystem::path file(presetFile.toStdString());
        std::optional<Material> material =
            parseMaterial(std::string_view(contents.constData(), size_t(contents.size())),
                          file.string(), file.parent_path(), problems);
        if (!material || problems.hasErrors()) {
            *error = tr("%1: not a material preset").arg(presetFile);
            return {};
        }
        std::string message;
        if (!ensureRenderer(&message)) {
            *error = QString::fromStdString(message);
            return {};
        }
        // The rule `velvet thumbnails` uses too (core/default_stage.h): fabrics on the drape.
        Problems sceneProblems; // a missing texture falls back; the thumbnail still helps
        const Scene scene = thumbnailScene(std::move(*material), &sceneProblems);
        m_renderer->setScene(scene, &sceneProblems);
        m_renderer->finishEnvironment();
        m_renderer->finishGraph(); // one frame: it must show this preset's graph
        render::FrameSettings settings;
        settings.width = ThumbnailRenderer::kSize;
        settings.height = ThumbnailRenderer::kSize;
        if (!m_renderer->render(settings, m_target->framebuffer(), &message)) {
            *error = QString::fromStdString(message);
            return {};
        }
        Image pixels = m_renderer->readDisplay();
        if (pixels.empty())
            *error = tr("%1: the renderer returned no image").arg(presetFile);
        return pixels;
    }

    std::atomic<int>* m_renders;
    std::unique_ptr<render::HeadlessContext> m_context;
    std::unique_ptr<render::Renderer> m_renderer;
    std::unique_ptr<render::OffscreenTarget> m_target;
    bool m_failed = false;
};

ThumbnailRenderer::ThumbnailRenderer(const QString& cacheDir, QObject* parent)
    : QObject(parent), m_cacheDir(cacheDir) {
    if (m_cacheDir.isEmpty())
        m_cacheDir = QStandardPaths::writableLocation(QStandardPaths::CacheLocation) +
                     QStringLiteral("/thumbnails");
    m_thread.setObjectName(QStringLiteral("velvet-thumbnails"));
    m_worker = new ThumbnailWorker(&m_renders);
    m_worker->moveToThread(&m_thread);
    connect(&m_thread, &QThread::finished, m_worker, &QObject::deleteLater);
    connect(m_worker, &ThumbnailWorker::rendered, this, &ThumbnailRenderer::onRendered,
            Qt::QueuedConnection);
    m_thread.start(QThread::LowPriority);
}

ThumbnailRenderer::~ThumbnailRenderer() {
    m_thread.requestInterruption();
    m_thread.quit(); // queued jobs are dropped; the worker is deleted on its thread
    m_thread.wait();
}

QString ThumbnailRenderer::cachePath(const QByteArray& contents) const {
    QCryptographicHash hash(QCryptographicHash::Sha1);
    hash.addData(contents);
    hash.addData(QByteArray(kRendererVersion));
    hash.addData(QByteArray::number(kSize));
    return m_cacheDir + QLatin1Char('/') + QString::fromLatin1(hash.result().toHex()) +
           QStringLiteral(".png");
}

bool ThumbnailRenderer::request(const QString& presetFile) {
    QFile file(presetFile);
    if (!file.open(QIODevice::ReadOnly)) {
        QMetaObject::invokeMethod(
            this,
            [this, presetFile, error = file.errorString()] {
                emit thumbnailFailed(presetFile, error);
            },
            Qt::QueuedConnection);
        return false;
    }
    const QByteArray contents = file.readAll();
    const QString cached = cachePath(contents);
    ++m_pending;
    Image pixels;
    if (QFileInfo::exists(cached) && readImage(cached.toStdString(), pixels, nullptr) &&
        !pixels.empty()) {
        ++m_cacheHits;
        const QImage image = toQImage(pixels);
        QMetaObject::invokeMethod(
            this, [this, presetFile, image] { onRendered(presetFile, image, QString()); },
            Qt::QueuedConnection);
        return true;
    }
    QMetaObject::invokeMethod(
        m_worker,
        [worker = m_worker, presetFile, contents, cached] {
            if (!QThread::currentThread()->isInterruptionRequested())
                worker->render(presetFile, contents, cached);
        },
        Qt::QueuedConnection);
    return true;
}

void ThumbnailRenderer::onRendered(const QString& presetFile, const QImage& image,
                                   const QString& error) {
    m_pending = std::max(0, m_pending - 1);
    if (image.isNull())
        emit thumbnailFailed(presetFile, error);
    else
        emit thumbnailReady(presetFile, image);
}

} // namespace velvet::ui

#include "thumbnail_renderer.moc"
