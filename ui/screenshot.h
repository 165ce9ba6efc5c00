#pragma once
/// @file screenshot.h
/// Saving a widget (the whole editor window) as an image file through core's OpenImageIO writer.

#include <QString>

class QImage;
class QWidget;

namespace velvet {
struct Image;
}

namespace velvet::ui {

/// @p image (any format) as float RGBA, display-encoded values in [0, 1].
Image toImage(const QImage& image);

/// @p widget as QWidget::grab draws it, with the frame of every visible ViewportWidget in it (or
/// of @p widget itself) painted where the viewport sits: the viewport's GL window is a native
/// window that QWidget::grab leaves out.
QImage grabWithViewports(QWidget* widget);

/// Grabs @p widget (grabWithViewports) and writes it to @p file:
/// .png as 8-bit display-encoded sRGB, .exr as linear half float (sRGB EOTF applied), other
/// extensions as OpenImageIO chooses, 8-bit. False + @p error on failure.
bool saveScreenshot(QWidget* widget, const QString& file, QString* error);

} // namespace velvet::ui
