#include "ui/screenshot.h"

#include "core/color_management.h"
#include "core/image.h"
#include "ui/viewport_widget.h"

#include <QFileInfo>
#include <QImage>
#include <QPainter>
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

QImage grabWithViewports(QWidget* widget) {
    QImage image = widget->grab().toImage();
    if (image.isNull())
        return image;
    // A viewport draws in a native GL window inside a window container, which QWidget::grab
    // leaves out: paint each visible viewport's own frame where it sits.
    QList<ViewportWidget*> viewports = widget->findChildren<ViewportWidget*>();
    if (auto* self = qobject_cast<ViewportWidget*>(widget))
        viewports.prepend(self);
    QPainter painter(&image);
    for (ViewportWidget* viewport : viewports) {
        if (!viewport->isVisible())
            continue;
        const QImage frame = viewport->grabDecorated();
        if (frame.isNull())
            continue;
        painter.drawImage(QRect(viewport->mapTo(widget, QPoint(0, 0)), viewport->size()), frame);
    }
    return image;
}

bool saveScreenshot(QWidget* widget, const QString& file, QString* error) {
    const QImage grabbed = grabWithViewports(widget);
    if (grabbed.isNull()) {
        if (error)
            *error = QStringLiteral("the window could not be grabbed");
        return false;
    }
    Image image = toImage(grabbed);
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
