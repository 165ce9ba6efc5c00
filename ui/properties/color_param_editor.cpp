#include "ui/properties/color_param_editor.h"

#include <QColorDialog>
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

void ColorParamEditor::pick() {
    const QColor initial = m_space.toQColor(m_linear);
    const QColor chosen = QColorDialog::getColor(
        initial, this, tr("%1 (%2)").arg(QString::fromUtf8(meta().label), m_space.name()));
    // Unchanged (or cancelled): keep the stored value exactly, rather than its round trip.
    if (!chosen.isValid() || chosen.rgb() == initial.rgb())
        return;
    emitEdited(m_space.fromQColor(chosen), 0);
}

} // namespace velvet::ui
