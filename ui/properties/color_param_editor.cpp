#include "ui/properties/color_param_editor.h"

#include "ui/properties/linear_color_picker.h"
#include "ui/viewport_widget.h"

#include <QHBoxLayout>
#include <QPainter>
#include <QPixmap>
#include <QToolButton>
#include <algorithm>

namespace velvet::ui {

ColorParamEditor::ColorParamEditor(const ParamMeta& spec, const QString& name, QWidget* parent)
    : ParamEditor(spec, name, parent), m_swatch(new QToolButton(this)) {
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
    if (m_picker && m_picker->linear() != linear)
        m_picker->setLinear(linear); // undo, or an edit elsewhere, while the picker is open
    const QColor shown = m_space.toQColor(linear);
    QPixmap pixmap(m_swatch->iconSize());
    pixmap.fill(shown);
    {
        QPainter painter(&pixmap);
        painter.setPen(palette().color(QPalette::Mid));
        painter.drawRect(pixmap.rect().adjusted(0, 0, -1, -1));
    }
    m_swatch->setIcon(QIcon(pixmap));
    m_swatch->setToolTip(tr("%1\nscene-linear %2, %3, %4 · %6 %5")
                             .arg(QString::fromUtf8(meta().tooltip))
                             .arg(linear.x, 0, 'f', 3)
                             .arg(linear.y, 0, 'f', 3)
                             .arg(linear.z, 0, 'f', 3)
                             .arg(shown.name(), m_space.name()));
}

void ColorParamEditor::setColorSpace(const PickerColorSpace& space) {
    m_space = space;
    setValue(m_linear);
}

void ColorParamEditor::setIntensity(const ParamMeta& meta, float value) {
    m_intensityMeta = &meta;
    m_intensity = value;
}

void ColorParamEditor::setIntensityValue(float value) {
    m_intensity = value;
    if (m_picker)
        m_picker->setIntensityValue(value);
}

void ColorParamEditor::pick() {
    if (m_picker) { // already open: bring it forward
        m_picker->raise();
        m_picker->activateWindow();
        return;
    }
    m_picker =
        new LinearColorPicker(tr("%1 (%2)").arg(QString::fromUtf8(meta().label), m_space.name()),
                              m_linear, m_space, this);
    if (m_intensityMeta)
        m_picker->setIntensity(m_intensity, m_intensityMeta->max,
                               QString::fromUtf8(m_intensityMeta->unit));
    m_picker->setViewport(window()->findChild<ViewportWidget*>());
    // Live: every change is an edit; a wheel or slider drag shares one merge key (one step).
    connect(m_picker, &LinearColorPicker::colorEdited, this,
            [this](glm::vec3 linear, int key) { emitEdited(linear, key); });
    connect(m_picker, &LinearColorPicker::intensityEdited, this,
            &ColorParamEditor::intensityEdited);
    m_picker->show();
}

} // namespace velvet::ui
