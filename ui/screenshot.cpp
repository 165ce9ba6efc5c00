#include "ui/screenshot.h"

#include "core/color_management.h"
#include "core/image.h"

#include <QFileInfo>
#include <QImage>
#include <QPixmap>
#include <QWidget>

namespace velvet::ui {

Image toImage(const QImage& source) {
    const QImage rgba = source.convertToFormat(QImage::Format_RGBA8888);
    Image image(rgba.width(), rgba.height(), 4);
    for (int y = 0; y < rgba.height(); ++y) {
        const uchar* row = rgba.constScanLine(y);
        float* out = image.at(0, y);
        for (int i = 0; i < rgba.width() * 4; ++i)
            out[i] = static_cast<float>(row[i]) / 255.0f;
    }
    return image;
}

bool saveScreenshot(QWidget* widget, const QString& file, QString* error) {
    const QPixmap pixmap = widget->grab();
    if (pixmap.isNull()) {
        if (error)
            *error = QStringLiteral("the window could not be grabbed");
        return false;
    }
    Image image = toImage(pixmap.toImage());
    PixelFormat format = PixelFormat::UInt8;
    if (QFileInfo(file).suffix().compare(QLatin1String("exr"), Qt::CaseInsensitive) == 0) {
        // EXR holds scene-linear values by convention: undo the display encoding, keep alpha.
        for (size_t i = 0; i < image.pixels.size(); i += 4)
            for (size_t c = 0; c < 3; ++c)
                image.pixels[i + c] = srgbToLinear(image.pixels[i + c]);
        format = PixelFormat::Half;
    }
    std::string message;
    if (!writeImage(std::filesystem::path(file.toStdString()), image, format, &message)) {
        if (error)
            *error = QString::fromStdString(message);
        return false;
    }
    return true;
}

} // namespace velvet::ui
