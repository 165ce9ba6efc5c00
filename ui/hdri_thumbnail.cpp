#include "ui/hdri_thumbnail.h"

#include "core/image.h"

#include <QDateTime>
#include <QFileInfo>
#include <QHash>
#include <QImage>
#include <QPixmap>
#include <algorithm>
#include <cmath>

namespace velvet::ui {
namespace {

/// IEC 61966-2-1 sRGB encoding of a linear value in [0, 1].
float encodeSrgb(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

QImage render(const Image& hdr, QSize size) {
    const int w = size.width(), h = size.height();
    // Box filter: every source pixel lands in exactly one thumbnail pixel.
    std::vector<double> sum(size_t(w) * size_t(h) * 3, 0.0);
    std::vector<int> count(size_t(w) * size_t(h), 0);
    for (int y = 0; y < hdr.height; ++y) {
        const int ty = std::min(h - 1, y * h / hdr.height);
        for (int x = 0; x < hdr.width; ++x) {
            const int tx = std::min(w - 1, x * w / hdr.width);
            const glm::vec4 p = hdr.rgba(x, y);
            const size_t t = size_t(ty) * size_t(w) + size_t(tx);
            for (int c = 0; c < 3; ++c)
                sum[t * 3 + size_t(c)] += std::max(0.0f, p[c]);
            ++count[t];
        }
    }
    // Reinhard, Stark, Shirley, Ferwerda 2002, "Photographic Tone Reproduction for Digital
    // Images": scale by key / log-average luminance (key 0.18), then L / (1 + L). Rec. 709 luma.
    double logSum = 0.0;
    for (size_t t = 0; t < count.size(); ++t) {
        for (int c = 0; c < 3; ++c)
            sum[t * 3 + size_t(c)] /= std::max(1, count[t]);
        const double l = 0.2126 * sum[t * 3] + 0.7152 * sum[t * 3 + 1] + 0.0722 * sum[t * 3 + 2];
        logSum += std::log(1e-4 + l);
    }
    const double scale = 0.18 / std::exp(logSum / double(count.size()));
    QImage image(size, QImage::Format_RGB32);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t t = size_t(y) * size_t(w) + size_t(x);
            int rgb[3];
            for (int c = 0; c < 3; ++c) {
                const double v = sum[t * 3 + size_t(c)] * scale;
                rgb[c] = int(std::lround(255.0 * encodeSrgb(float(v / (1.0 + v)))));
            }
            image.setPixel(x, y, qRgb(rgb[0], rgb[1], rgb[2]));
        }
    return image;
}

} // namespace

QIcon hdriThumbnail(const QString& file, QSize size) {
    static QHash<QString, QIcon> cache;
    const QFileInfo info(file);
    const QString key = QStringLiteral("%1|%2|%3x%4")
                            .arg(info.absoluteFilePath())
                            .arg(info.lastModified().toMSecsSinceEpoch())
                            .arg(size.width())
                            .arg(size.height());
    if (const auto it = cache.constFind(key); it != cache.constEnd())
        return *it;
    Image hdr;
    std::string error;
    QIcon icon;
    if (!size.isEmpty() && readImage(info.absoluteFilePath().toStdString(), hdr, &error) &&
        hdr.width > 0 && hdr.height > 0)
        icon = QIcon(QPixmap::fromImage(render(hdr, size)));
    cache.insert(key, icon); // a file that cannot be read is not read again until it changes
    return icon;
}

} // namespace velvet::ui
