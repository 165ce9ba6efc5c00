#include "ui/scene/scene_widgets.h"

#include "core/color_management.h"

#include <QColor>
#include <QColorDialog>
#include <QObject>
#include <QPushButton>
#include <algorithm>

namespace velvet::ui {
namespace {

QColor swatchColor(glm::vec3 linear) {
    return QColor::fromRgbF(linearToSrgb(std::clamp(linear.r, 0.0f, 1.0f)),
                            linearToSrgb(std::clamp(linear.g, 0.0f, 1.0f)),
                            linearToSrgb(std::clamp(linear.b, 0.0f, 1.0f)));
}

} // namespace

QString typeLabel(LightType type) {
    switch (type) {
    case LightType::Directional:
        return QObject::tr("Directional");
    case LightType::Point:
        return QObject::tr("Point");
    case LightType::Spot:
        return QObject::tr("Spot");
    case LightType::Area:
        return QObject::tr("Area");
    case LightType::Ambient:
        return QObject::tr("Ambient");
    }
    return {};
}

QString intensityUnit(LightType type) {
    switch (type) {
    case LightType::Directional:
        return QObject::tr(" lx");
    case LightType::Point:
    case LightType::Spot:
        return QObject::tr(" cd");
    case LightType::Area:
        return QObject::tr(" nt");
    case LightType::Ambient:
        return QObject::tr(" ×");
    }
    return {};
}

void showSwatch(QPushButton* button, glm::vec3 linear) {
    const QColor c = swatchColor(linear);
    button->setStyleSheet(QStringLiteral("background-color: %1;").arg(c.name()));
    button->setToolTip(QObject::tr("Linear Rec.709 %1, %2, %3 (shown sRGB encoded); click to pick")
                           .arg(double(linear.r), 0, 'f', 3)
                           .arg(double(linear.g), 0, 'f', 3)
                           .arg(double(linear.b), 0, 'f', 3));
}

std::optional<glm::vec3> pickLinearColor(QWidget* parent, glm::vec3 linear, const QString& title) {
    const QColor picked = QColorDialog::getColor(swatchColor(linear), parent, title);
    if (!picked.isValid())
        return std::nullopt;
    return glm::vec3(srgbToLinear(float(picked.redF())), srgbToLinear(float(picked.greenF())),
                     srgbToLinear(float(picked.blueF())));
}

QDoubleSpinBox* makeSpin(const QString& name, double min, double max, double step, int decimals,
                         const QString& tip, QWidget* parent) {
    auto* spin = new QDoubleSpinBox(parent);
    spin->setObjectName(name);
    spin->setRange(min, max);
    spin->setSingleStep(step);
    spin->setDecimals(decimals);
    spin->setToolTip(tip);
    // Edits on Return, focus loss, arrows and wheel, not per keystroke: a refresh between
    // keystrokes would rewrite the text being typed.
    spin->setKeyboardTracking(false);
    return spin;
}

} // namespace velvet::ui
