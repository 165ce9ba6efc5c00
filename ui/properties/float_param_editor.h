#pragma once
/// @file float_param_editor.h
/// A Float parameter: a slider over the soft range and a spin box over the hard range, in sync.

#include "ui/properties/param_editor.h"

class QDoubleSpinBox;
class QSlider;

namespace velvet::ui {

class FloatParamEditor : public ParamEditor {
    Q_OBJECT
public:
    /// Slider positions between the ends of its range.
    static constexpr int kSliderSteps = 1000;

    FloatParamEditor(const ParamMeta& meta, const QString& name, QWidget* parent = nullptr);
    void setValue(glm::vec3 value) override;

    QSlider* slider() const { return m_slider; }
    QDoubleSpinBox* spinBox() const { return m_spin; }

private:
    /// The slider's ends: the hard range, narrowed to the soft end (softMax) and, for values
    /// without a practical lower bound (a constant node's -10000), to 0 or the soft end minus 1.
    float sliderStart() const;
    float sliderEnd() const;
    int toSlider(float v) const;
    float fromSlider(int position) const;
    void onSliderMoved(int position);

    QSlider* m_slider;
    QDoubleSpinBox* m_spin;
    int m_gesture = 0; ///< non-zero while the slider is held down
};

} // namespace velvet::ui
