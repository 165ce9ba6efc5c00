#include "ui/properties/float_param_editor.h"

#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QSignalBlocker>
#include <QSlider>
#include <QToolButton>
#include <algorithm>
#include <cmath>

namespace velvet::ui {

FloatParamEditor::FloatParamEditor(const ParamMeta& spec, const QString& name, QWidget* parent)
    : ParamEditor(spec, name, parent), m_slider(new QSlider(Qt::Horizontal, this)),
      m_spin(new QDoubleSpinBox(this)) {
    const ParamMeta& m = meta();
    const QString tip = QString::fromUtf8(m.tooltip);

    m_slider->setObjectName(partName("slider"));
    m_slider->setRange(0, kSliderSteps);
    m_slider->setSingleStep(kSliderSteps / 100);
    m_slider->setPageStep(kSliderSteps / 10);
    m_slider->setToolTip(tip);
    m_slider->setFocusPolicy(Qt::StrongFocus);

    const float range = m.max - m.min;
    m_spin->setObjectName(partName("spin"));
    m_spin->setRange(m.min, m.max);
    m_spin->setDecimals(range > 100.0f ? 1 : 3);
    m_spin->setSingleStep((sliderEnd() - sliderStart()) / 100.0);
    m_spin->setKeyboardTracking(false); // typed text commits on Enter or focus out: one command
    m_spin->setToolTip(tip);
    m_spin->setFixedWidth(m_spin->fontMetrics().horizontalAdvance(QStringLiteral("0000.000 nits")));
    if (!m.unit.empty())
        m_spin->setSuffix(QLatin1Char(' ') + QString::fromUtf8(m.unit));

    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(m_slider, 1);
    layout->addWidget(m_spin);
    layout->addWidget(makeResetButton());

    connect(m_slider, &QSlider::sliderPressed, this, [this] { m_gesture = nextGestureKey(); });
    connect(m_slider, &QSlider::sliderReleased, this, [this] { m_gesture = 0; });
    connect(m_slider, &QSlider::valueChanged, this, &FloatParamEditor::onSliderMoved);
    connect(m_spin, &QDoubleSpinBox::valueChanged, this,
            [this](double v) { emitEdited(glm::vec3(static_cast<float>(v)), 0); });

    setValue(m.defaultValue);
}

void FloatParamEditor::setValue(glm::vec3 value) {
    const QSignalBlocker blockSlider(m_slider);
    const QSignalBlocker blockSpin(m_spin);
    m_spin->setValue(value.x);
    // While the artist drags, the handle stays where the mouse put it.
    if (!m_slider->isSliderDown())
        m_slider->setValue(toSlider(value.x));
}

float FloatParamEditor::sliderStart() const {
    const ParamMeta& m = meta();
    constexpr float kUnbounded = -1000.0f; // below this the hard minimum is no slider end
    if (m.min > kUnbounded)
        return m.min;
    const float end = sliderEnd();
    return end > 0.0f ? std::min(0.0f, end - 1.0f) : end - 1.0f;
}

float FloatParamEditor::sliderEnd() const {
    const ParamMeta& m = meta();
    // softMax 0 means "no soft end" (param_meta.h), also for ranges that contain 0.
    return (m.softMax != 0.0f && m.softMax > m.min && m.softMax < m.max) ? m.softMax : m.max;
}

int FloatParamEditor::toSlider(float v) const {
    const float lo = sliderStart();
    const float t = (v - lo) / (sliderEnd() - lo);
    return std::clamp(static_cast<int>(std::lround(t * kSliderSteps)), 0, kSliderSteps);
}

float FloatParamEditor::fromSlider(int position) const {
    const float lo = sliderStart();
    return lo + (sliderEnd() - lo) * static_cast<float>(position) / kSliderSteps;
}

void FloatParamEditor::onSliderMoved(int position) {
    const int key = m_slider->isSliderDown() ? m_gesture : 0;
    emitEdited(glm::vec3(fromSlider(position)), key);
}

} // namespace velvet::ui
