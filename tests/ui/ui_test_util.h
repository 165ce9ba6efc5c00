#pragma once
// Shared helpers of the widget tests (run under xvfb-run): pixels read from a grabbed viewport
// and where a user grabs a slider; bringing the main window up is ui_test_window.h's.

#include "core/material.h"
#include "ui_test_window.h"

#include <QColor>
#include <QCoreApplication>
#include <QDropEvent>
#include <QImage>
#include <QMimeData>
#include <QSlider>
#include <QString>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QTest>
#include <QUrl>
#include <QVector>
#include <algorithm>
#include <cmath>

namespace velvet::test {

/// A glossy copper (roughness 0.25, no sheen): a material whose reflections the viewport samples
/// at rest (FrameSettings::reflectionSamples).
inline Material glossyCopper() {
    Material copper;
    copper.setColor(ParamId::BaseColor, glm::vec3(0.95f, 0.64f, 0.54f));
    copper.setScalar(ParamId::Metallic, 1.0f);
    copper.setScalar(ParamId::Roughness, 0.25f);
    copper.setScalar(ParamId::SheenWeight, 0.0f);
    return copper;
}

/// Mean colour of a 5x5 block around the centre (on the preview mesh), in 0..255 units.
inline QVector<double> centrePixel(const QImage& image) {
    QVector<double> sum(3, 0.0);
    const int cx = image.width() / 2, cy = image.height() / 2;
    for (int y = cy - 2; y <= cy + 2; ++y)
        for (int x = cx - 2; x <= cx + 2; ++x) {
            const QColor c = image.pixelColor(x, y);
            sum[0] += c.red();
            sum[1] += c.green();
            sum[2] += c.blue();
        }
    for (double& s : sum)
        s /= 25.0;
    return sum;
}

/// Largest per-channel difference of two centrePixel() results.
inline double maxDifference(const QVector<double>& a, const QVector<double>& b) {
    double d = 0.0;
    for (int i = 0; i < 3; ++i)
        d = std::max(d, std::abs(a[i] - b[i]));
    return d;
}

/// Relative luminance (Rec. 709 weights) of a centrePixel() result, 0..255.
inline double luma(const QVector<double>& p) {
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

/// A centrePixel() result as "(r, g, b)", for failure messages.
inline QString describe(const QVector<double>& p) {
    return QStringLiteral("(%1, %2, %3)").arg(p[0]).arg(p[1]).arg(p[2]);
}

/// Largest channel difference between two frames of the same size, in 0..255 units.
inline int maxImageDifference(const QImage& a, const QImage& b) {
    int worst = 0;
    for (int y = 0; y < std::min(a.height(), b.height()); ++y)
        for (int x = 0; x < std::min(a.width(), b.width()); ++x) {
            const QColor p = a.pixelColor(x, y), q = b.pixelColor(x, y);
            worst = std::max({worst, std::abs(p.red() - q.red()), std::abs(p.green() - q.green()),
                              std::abs(p.blue() - q.blue())});
        }
    return worst;
}

/// Centre of the slider's handle, from the style (where a user would grab it).
inline QPoint handleCentre(QSlider* slider) {
    QStyleOptionSlider option;
    option.initFrom(slider);
    option.orientation = slider->orientation();
    option.minimum = slider->minimum();
    option.maximum = slider->maximum();
    option.sliderPosition = slider->sliderPosition();
    option.sliderValue = slider->value();
    option.subControls = QStyle::SC_SliderGroove | QStyle::SC_SliderHandle;
    return slider->style()
        ->subControlRect(QStyle::CC_Slider, &option, QStyle::SC_SliderHandle, slider)
        .center();
}

/// The child of @p root named @p name (a widget or an action), with a warning naming it when
/// there is none (the tests then fail on the null pointer's check).
template <class T>
T* findNamed(const QObject* root, const QString& name) {
    T* found = root->findChild<T*>(name);
    if (!found)
        qWarning("no widget named %s", qPrintable(name));
    return found;
}

/// Sends a file drop of @p file to @p target (enter, move, drop, as QGuiApplication does).
inline bool dropFile(QObject* target, QPoint pos, const QString& file) {
    QMimeData mime;
    mime.setUrls({QUrl::fromLocalFile(file)});
    QDragEnterEvent enter(pos, Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    enter.setAccepted(false);
    QCoreApplication::sendEvent(target, &enter);
    if (!enter.isAccepted())
        return false;
    QDragMoveEvent move(pos, Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    move.setDropAction(enter.dropAction());
    move.setAccepted(true);
    QCoreApplication::sendEvent(target, &move);
    QDropEvent drop(QPointF(pos), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    drop.setAccepted(false);
    QCoreApplication::sendEvent(target, &drop);
    return drop.isAccepted();
}

} // namespace velvet::test
