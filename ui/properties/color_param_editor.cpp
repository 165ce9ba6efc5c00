#include "ui/properties/color_param_editor.h"

#include "core/color_management.h"

#include <QColorDialog>
#include <QHBoxLayout>
#include <QPainter>
#include <QPixmap>
#include <QToolButton>
#include <algorithm>

namespace velvet::ui {
namespace {

// The picker works in display-encoded sRGB; the document stores scene-linear Rec.709.
QColor displayColor(glm::vec3 linear) {
    auto encode = [](float v) { return std::clamp(linearToSrgb(v), 0.0f, 1.0f); };
    return QColor::fromRgbF(encode(linear.x), encode(linear.y), encode(linear.z));
}

glm::vec3 linearColor(const QColor& display) {
    return {srgbToLinear(static_cast<float>(display.redF())),
            srgbToLinear(static_cast<float>(display.greenF())),
            srgbToLinear(static_cast<float>(display.blueF()))};
}

} // namespace

ColorParamEditor::ColorParamEditor(ParamId id, QWidget* parent)
    : ParamEditor(id, parent), m_swatch(new QToolButton(this)) {
    m_swatch->setObjectName(partName("swatch"));
    m_swatch->setIconSize(QSize(48, 16));
    m_swatch->setFocusPolicy(Qt::StrongFocus);

    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(m_swatch);
    layout->addStretch(1);
    layout->addWidget(makeResetButton());

    connect(m_swatch, &QToolButton::clicked, this, &ColorParamEditor::pick);
    setValue(meta().defaultValue);
}

void ColorParamEditor::setValue(glm::vec3 linear) {
    m_linear = linear;
    const QColor shown = displayColor(linear);
    QPixmap pixmap(m_swatch->iconSize());
    pixmap.fill(shown);
    {
        QPainter painter(&pixmap);
        painter.setPen(palette().color(QPalette::Mid));
        painter.drawRect(pixmap.rect().adjusted(0, 0, -1, -1));
    }
    m_swatch->setIcon(QIcon(pixmap));
    m_swatch->setToolTip(tr("%1\nlinear %2, %3, %4 · sRGB %5")
                             .arg(QString::fromUtf8(meta().tooltip))
                             .arg(linear.x, 0, 'f', 3)
                             .arg(linear.y, 0, 'f', 3)
                             .arg(linear.z, 0, 'f', 3)
                             .arg(shown.name()));
}

void ColorParamEditor::pick() {
    const QColor chosen =
        QColorDialog::getColor(displayColor(m_linear), this, QString::fromUtf8(meta().label));
    if (!chosen.isValid())
        return;
    emit edited(param(), linearColor(chosen), 0);
}

} // namespace velvet::ui
