#include "ui/properties/texture_slot_editor.h"

#include "core/color_management.h"
#include "core/image.h"
#include "render/texture_set.h"
#include "ui/document_controller.h"
#include "ui/properties/uv_transform_editor.h"

#include <QComboBox>
#include <QCoreApplication>
#include <QDateTime>
#include <QDir>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHash>
#include <QLabel>
#include <QMimeData>
#include <QPixmap>
#include <QPointer>
#include <QSignalBlocker>
#include <QThreadPool>
#include <QToolButton>
#include <QUrl>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <mutex>

namespace velvet::ui {
namespace {

constexpr int kThumbnailSide = 64;

QString fromView(std::string_view s) {
    return QString::fromUtf8(s.data(), static_cast<qsizetype>(s.size()));
}

QString regionText(const TextureRef& ref) {
    return QStringLiteral("%1, %2, %3 x %4")
        .arg(ref.region.x)
        .arg(ref.region.y)
        .arg(ref.region.width)
        .arg(ref.region.height);
}

/// One thumbnail read: the image (null on failure) and why it failed.
struct ThumbnailResult {
    QImage image;
    QString error;
};

/// Thumbnails by file (path, size, modification time), colour space, region and usage. Shared
/// by every row and guarded: workers fill it, the UI thread reads it.
class ThumbnailCache {
public:
    static ThumbnailCache& instance() {
        static ThumbnailCache cache;
        return cache;
    }
    bool find(const QString& key, ThumbnailResult& out) {
        const std::lock_guard lock(m_mutex);
        const auto it = m_entries.constFind(key);
        if (it == m_entries.constEnd())
            return false;
        out = *it;
        return true;
    }
    void insert(const QString& key, const ThumbnailResult& result) {
        const std::lock_guard lock(m_mutex);
        if (m_entries.size() > 512)
            m_entries.clear(); // small images: dropping all now and then is simpler than an LRU
        m_entries.insert(key, result);
    }

private:
    std::mutex m_mutex;
    QHash<QString, ThumbnailResult> m_entries;
};

QString thumbnailKey(const TextureRef& ref, const QString& colorSpace, bool isColor) {
    const QFileInfo info(QString::fromStdString(ref.file));
    return QStringLiteral("%1|%2|%3|%4|%5|%6")
        .arg(info.absoluteFilePath())
        .arg(info.size())
        .arg(info.lastModified().toMSecsSinceEpoch())
        .arg(colorSpace)
        .arg(ref.useRegion ? regionText(ref) : QString())
        .arg(isColor ? 1 : 0);
}

/// Box-filters @p image (or its @p region) down to at most kThumbnailSide on the longer side.
Image shrink(const Image& image, int x0, int y0, int w, int h) {
    const double scale = std::max(1.0, double(std::max(w, h)) / kThumbnailSide);
    const int tw = std::max(1, int(std::lround(w / scale)));
    const int th = std::max(1, int(std::lround(h / scale)));
    Image out(tw, th, 4);
    for (int ty = 0; ty < th; ++ty) {
        const int sy0 = y0 + int(ty * double(h) / th);
        const int sy1 = std::max(sy0 + 1, y0 + int((ty + 1) * double(h) / th));
        for (int tx = 0; tx < tw; ++tx) {
            const int sx0 = x0 + int(tx * double(w) / tw);
            const int sx1 = std::max(sx0 + 1, x0 + int((tx + 1) * double(w) / tw));
            glm::vec4 sum(0.0f);
            for (int y = sy0; y < sy1; ++y)
                for (int x = sx0; x < sx1; ++x)
                    sum += image.rgba(x, y);
            sum /= float((sy1 - sy0) * (sx1 - sx0));
            float* p = out.at(tx, ty);
            for (int c = 0; c < 4; ++c)
                p[c] = sum[c];
        }
    }
    return out;
}

/// Reads and converts one thumbnail (any thread).
ThumbnailResult readThumbnail(const TextureRef& ref, const std::string& colorSpace, bool isColor,
                              const std::shared_ptr<const ColorManagement>& cm) {
    ThumbnailResult result;
    Image image;
    std::string error;
    if (!readImage(ref.file, image, &error)) {
        result.error = QString::fromStdString(error);
        return result;
    }
    int x0 = 0, y0 = 0, w = image.width, h = image.height;
    if (ref.useRegion) {
        x0 = std::clamp(ref.region.x, 0, image.width);
        y0 = std::clamp(ref.region.y, 0, image.height);
        w = std::min(ref.region.width, image.width - x0);
        h = std::min(ref.region.height, image.height - y0);
        if (w <= 0 || h <= 0) {
            result.error = QObject::tr("%1: the region %2 lies outside the %3 x %4 image")
                               .arg(QString::fromStdString(ref.file), regionText(ref))
                               .arg(image.width)
                               .arg(image.height);
            return result;
        }
    }
    Image small = shrink(image, x0, y0, w, h);
    if (isColor) {
        // Into scene-linear from the input colour space, then display-encoded (sRGB).
        if (cm && cm->isLoaded() && !cm->toSceneLinear(small, colorSpace, &error)) {
            result.error = QString::fromStdString(error);
            return result;
        }
        if (cm && cm->isLoaded())
            for (size_t i = 0; i < small.pixels.size(); i += 4)
                for (size_t c = 0; c < 3; ++c)
                    small.pixels[i + c] = linearToSrgb(small.pixels[i + c]);
    }
    QImage q(small.width, small.height, QImage::Format_RGB32);
    for (int y = 0; y < small.height; ++y)
        for (int x = 0; x < small.width; ++x) {
            const float* p = small.at(x, y);
            auto byte = [](float v) {
                return int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
            };
            q.setPixel(x, y, qRgb(byte(p[0]), byte(p[1]), byte(p[2])));
        }
    result.image = q;
    return result;
}

} // namespace

const QStringList& TextureSlotEditor::imageExtensions() {
    // The readers OpenImageIO ships (its "extension_list"), the common ones first.
    static const QStringList extensions = {
        QStringLiteral("png"), QStringLiteral("jpg"),  QStringLiteral("jpeg"),
        QStringLiteral("tif"), QStringLiteral("tiff"), QStringLiteral("exr"),
        QStringLiteral("hdr"), QStringLiteral("tga"),  QStringLiteral("bmp"),
        QStringLiteral("tx"),  QStringLiteral("tex"),  QStringLiteral("psd"),
        QStringLiteral("gif"), QStringLiteral("webp"), QStringLiteral("jp2"),
        QStringLiteral("j2k"), QStringLiteral("dpx"),  QStringLiteral("cin"),
        QStringLiteral("pnm"), QStringLiteral("ppm"),  QStringLiteral("pgm"),
        QStringLiteral("pbm"), QStringLiteral("pfm"),  QStringLiteral("sgi"),
        QStringLiteral("rgb"), QStringLiteral("rgbe"), QStringLiteral("ico"),
        QStringLiteral("dds"), QStringLiteral("heic"), QStringLiteral("avif"),
        QStringLiteral("iff"), QStringLiteral("rla"),  QStringLiteral("pic"),
    };
    return extensions;
}

bool TextureSlotEditor::hasImageExtension(const QString& path) {
    return imageExtensions().contains(QFileInfo(path).suffix().toLower());
}

QString TextureSlotEditor::imageFileFilter() {
    QStringList patterns;
    for (const QString& ext : imageExtensions())
        patterns << QStringLiteral("*.") + ext;
    return tr("Images (%1)").arg(patterns.join(QLatin1Char(' '))) + QStringLiteral(";;") +
           tr("All files (*)");
}

TextureSlotEditor::TextureSlotEditor(DocumentController* controller, TextureSlot slot,
                                     QWidget* parent)
    : QWidget(parent), m_controller(controller), m_slot(slot),
      m_isColor(textureSlotMeta(slot).isColor) {
    const QString name = QStringLiteral("textureSlot:") + fromView(textureSlotMeta(slot).id);
    setObjectName(name);
    setAcceptDrops(true);
    // Every slot reaches the viewport per pixel (render/lobe_channels.h).
    setToolTip(fromView(textureSlotMeta(slot).tooltip));

    auto* outer = new QVBoxLayout(this);
    outer->setContentsMargins(0, 0, 0, 0);
    outer->setSpacing(2);
    auto* row = new QHBoxLayout;
    outer->addLayout(row);
    m_thumbLabel = new QLabel(this);
    m_thumbLabel->setObjectName(name + QStringLiteral("/thumbnail"));
    m_thumbLabel->setFixedSize(kThumbnailSide + 2, kThumbnailSide + 2);
    m_thumbLabel->setAlignment(Qt::AlignCenter);
    m_thumbLabel->setFrameShape(QFrame::StyledPanel);
    row->addWidget(m_thumbLabel);

    auto* column = new QVBoxLayout;
    m_fileLabel = new QLabel(this);
    m_fileLabel->setObjectName(name + QStringLiteral("/file"));
    m_fileLabel->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    m_fileLabel->setTextInteractionFlags(Qt::TextSelectableByMouse);
    column->addWidget(m_fileLabel);

    auto* buttons = new QHBoxLayout;
    m_browse = new QToolButton(this);
    m_browse->setObjectName(name + QStringLiteral("/browse"));
    m_browse->setText(tr("Browse…"));
    m_browse->setToolTip(tr("Choose an image file for %1 (or drop one onto the row)").arg(label()));
    connect(m_browse, &QToolButton::clicked, this, &TextureSlotEditor::browse);
    buttons->addWidget(m_browse);
    m_clear = new QToolButton(this);
    m_clear->setObjectName(name + QStringLiteral("/clear"));
    m_clear->setText(tr("Clear"));
    m_clear->setToolTip(tr("Empty the slot: the parameter value applies again"));
    connect(m_clear, &QToolButton::clicked, this, &TextureSlotEditor::clearSlot);
    buttons->addWidget(m_clear);
    m_colorSpace = new QComboBox(this);
    m_colorSpace->setObjectName(name + QStringLiteral("/colorSpace"));
    m_colorSpace->setToolTip(tr("The input colour space of the file"));
    m_colorSpace->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    m_colorSpace->setMinimumContentsLength(8);
    connect(m_colorSpace, &QComboBox::activated, this, &TextureSlotEditor::onColorSpaceActivated);
    buttons->addStretch(1);
    column->addLayout(buttons);
    column->addWidget(m_colorSpace); // its own line: "Default (sRGB texture)" needs the width
    row->addLayout(column, 1);
    // The UV transform under the row, full width (a column beside the thumbnail would widen
    // the whole panel).
    m_uv = new UvTransformEditor(controller, slot, name, this);
    outer->addWidget(m_uv);

    refresh();
}

TextureSlotEditor::~TextureSlotEditor() = default;

QString TextureSlotEditor::label() const {
    return fromView(textureSlotMeta(m_slot).label);
}

std::shared_ptr<const ColorManagement> TextureSlotEditor::colorManagement() {
    if (!m_colorManagement) {
        static const std::shared_ptr<const ColorManagement> fallback = [] {
            auto cm = std::make_shared<ColorManagement>();
            std::string error;
            cm->loadDefault(&error); // not loaded: thumbnails show the stored values
            return std::shared_ptr<const ColorManagement>(std::move(cm));
        }();
        m_colorManagement = fallback;
    }
    return m_colorManagement;
}

void TextureSlotEditor::setColorManagement(std::shared_ptr<const ColorManagement> colorManagement) {
    if (colorManagement == m_colorManagement)
        return;
    m_colorManagement = std::move(colorManagement);
    m_shownValid = false; // colour space names and thumbnails may differ
    refresh();
}

QString TextureSlotEditor::defaultColorSpace() const {
    const ColorManagement* cm = m_colorManagement.get();
    const bool loaded = cm && cm->isLoaded();
    if (!m_isColor) {
        const std::string data = loaded ? cm->roleColorSpace("data") : std::string();
        return data.empty() ? QStringLiteral("Raw") : QString::fromStdString(data);
    }
    if (loaded && !m_shown.file.empty()) {
        const std::string byRule = cm->colorSpaceForFile(m_shown.file);
        if (!byRule.empty())
            return QString::fromStdString(byRule);
    }
    return QStringLiteral("sRGB texture");
}

void TextureSlotEditor::fillColorSpaces() {
    const QSignalBlocker block(m_colorSpace);
    m_colorSpace->clear();
    m_colorSpace->addItem(tr("Default (%1)").arg(defaultColorSpace()), QString());
    if (const auto cm = colorManagement(); cm->isLoaded())
        for (const std::string& space : cm->colorSpaces())
            m_colorSpace->addItem(QString::fromStdString(space), QString::fromStdString(space));
    const QString current = QString::fromStdString(m_shown.colorSpace);
    int index = m_colorSpace->findData(current);
    if (index < 0) { // a name the config does not list: keep it, so it shows as it is
        m_colorSpace->addItem(current, current);
        index = m_colorSpace->count() - 1;
    }
    m_colorSpace->setCurrentIndex(index);
}

void TextureSlotEditor::refresh() {
    const TextureRef& ref = m_controller->material().texture(m_slot);
    m_uv->refresh();
    if (m_shownValid && ref == m_shown)
        return;
    colorManagement();
    m_shown = ref;
    m_shownValid = true;
    fillColorSpaces(); // the default item follows the file rules

    const bool empty = ref.empty();
    const QString path = QString::fromStdString(ref.file);
    m_fileLabel->setText(empty ? tr("(none)") : QFileInfo(path).fileName());
    m_fileLabel->setEnabled(!empty);
    QString tip;
    if (empty)
        tip = tr("%1: no texture; the parameter value applies").arg(label());
    else {
        const QString space = ref.colorSpace.empty()
                                  ? tr("%1 (the slot's default)").arg(defaultColorSpace())
                                  : QString::fromStdString(ref.colorSpace);
        tip = tr("%1\nColour space: %2").arg(QDir::toNativeSeparators(path), space);
        if (ref.useRegion)
            tip += tr("\nRegion: %1 (x, y, width x height)").arg(regionText(ref));
    }
    m_fileLabel->setToolTip(tip);
    m_thumbLabel->setToolTip(tip);
    m_clear->setEnabled(!empty);
    m_colorSpace->setEnabled(!empty);
    requestThumbnail();
}

void TextureSlotEditor::requestThumbnail() {
    const std::uint64_t request = ++m_request;
    if (m_shown.empty()) {
        m_pending = false;
        setThumbnail(QImage(), false, QString());
        return;
    }
    const std::string space =
        m_shown.colorSpace.empty() ? defaultColorSpace().toStdString() : m_shown.colorSpace;
    const QString key = thumbnailKey(m_shown, QString::fromStdString(space), m_isColor);
    ThumbnailResult cached;
    if (ThumbnailCache::instance().find(key, cached)) {
        m_pending = false;
        setThumbnail(cached.image, cached.image.isNull(), cached.error);
        return;
    }
    m_pending = true;
    m_thumbnail = QImage(); // the old file's picture must not pass for the new one's
    m_thumbLabel->setPixmap(QPixmap());
    m_thumbLabel->setText(tr("…"));
    QPointer<TextureSlotEditor> self(this);
    QThreadPool::globalInstance()->start(
        [self, request, key, ref = m_shown, space, isColor = m_isColor, cm = colorManagement()] {
            ThumbnailResult result = readThumbnail(ref, space, isColor, cm);
            ThumbnailCache::instance().insert(key, result);
            // Back on the UI thread; the row may be gone or showing another file by then.
            QMetaObject::invokeMethod(
                qApp,
                [self, request, result] {
                    if (!self || self->m_request != request)
                        return;
                    self->m_pending = false;
                    self->setThumbnail(result.image, result.image.isNull(), result.error);
                },
                Qt::QueuedConnection);
        });
}

void TextureSlotEditor::setThumbnail(const QImage& image, bool failed, const QString& error) {
    m_thumbnail = image;
    m_thumbnailError = error;
    if (!image.isNull()) {
        m_thumbLabel->setText(QString());
        m_thumbLabel->setPixmap(QPixmap::fromImage(image.scaled(
            kThumbnailSide, kThumbnailSide, Qt::KeepAspectRatio,
            image.width() < kThumbnailSide ? Qt::FastTransformation : Qt::SmoothTransformation)));
    } else {
        m_thumbLabel->setPixmap(QPixmap());
        m_thumbLabel->setText(failed ? tr("missing") : QString());
        if (failed)
            m_thumbLabel->setToolTip(m_fileLabel->toolTip() + QStringLiteral("\n") + error);
    }
    emit thumbnailChanged();
}

bool TextureSlotEditor::assignFile(const QString& path) {
    if (!hasImageExtension(path)) {
        emit message(tr("%1: not an image file OpenImageIO reads (%2); %3 texture unchanged")
                         .arg(QDir::toNativeSeparators(path),
                              QFileInfo(path).suffix().isEmpty()
                                  ? tr("no extension")
                                  : QStringLiteral(".") + QFileInfo(path).suffix(),
                              label()));
        return false;
    }
    ImageInfo info;
    std::string error;
    if (!readImageInfo(QDir::cleanPath(QFileInfo(path).absoluteFilePath()).toStdString(), info,
                       &error)) {
        emit message(
            tr("Could not use %1 as the %2 texture: %3")
                .arg(QDir::toNativeSeparators(path), label(), QString::fromStdString(error)));
        return false;
    }
    TextureRef ref = m_controller->material().texture(m_slot);
    ref.file = QDir::cleanPath(QFileInfo(path).absoluteFilePath()).toStdString();
    ref.useRegion = false; // a new file: the whole image
    ref.region = {};
    // Into an empty colour slot the colour factor goes white with it (one undo step), so the map
    // shows as painted (DocumentController::assignTextureImage).
    m_controller->assignTextureImage(m_slot, ref, tr("Set %1 texture").arg(label()));
    return true;
}

void TextureSlotEditor::clearSlot() {
    m_controller->editTexture(m_slot, TextureRef{}, tr("Clear %1 texture").arg(label()));
}

void TextureSlotEditor::browse() {
    const TextureRef& ref = m_controller->material().texture(m_slot);
    QString dir = ref.empty() ? QFileInfo(m_controller->filePath()).absolutePath()
                              : QFileInfo(QString::fromStdString(ref.file)).absolutePath();
    if (m_controller->filePath().isEmpty() && ref.empty())
        dir.clear();
    const QString path =
        QFileDialog::getOpenFileName(this, tr("%1 texture").arg(label()), dir, imageFileFilter());
    if (!path.isEmpty())
        assignFile(path);
}

void TextureSlotEditor::onColorSpaceActivated(int index) {
    TextureRef ref = m_controller->material().texture(m_slot);
    if (ref.empty() || index < 0)
        return;
    ref.colorSpace = m_colorSpace->itemData(index).toString().toStdString();
    m_controller->editTexture(m_slot, ref, tr("Set %1 texture colour space").arg(label()));
}

namespace {
/// The first local file among @p mime's URLs, or "".
QString droppedFile(const QMimeData* mime) {
    if (!mime || !mime->hasUrls())
        return {};
    for (const QUrl& url : mime->urls())
        if (url.isLocalFile())
            return url.toLocalFile();
    return {};
}
} // namespace

void TextureSlotEditor::dragEnterEvent(QDragEnterEvent* event) {
    const QString file = droppedFile(event->mimeData());
    if (!file.isEmpty() && hasImageExtension(file))
        event->acceptProposedAction();
    else
        event->ignore();
}

void TextureSlotEditor::dragMoveEvent(QDragMoveEvent* event) {
    const QString file = droppedFile(event->mimeData());
    if (!file.isEmpty() && hasImageExtension(file))
        event->acceptProposedAction();
    else
        event->ignore();
}

void TextureSlotEditor::dropEvent(QDropEvent* event) {
    const QString file = droppedFile(event->mimeData());
    if (file.isEmpty()) {
        emit message(tr("Only image files can be dropped onto the %1 texture").arg(label()));
        event->ignore();
        return;
    }
    if (assignFile(file))
        event->acceptProposedAction();
    else
        event->ignore();
}

} // namespace velvet::ui
