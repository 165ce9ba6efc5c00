#pragma once
/// @file color_param_editor.h
/// A Color parameter: a swatch button that opens the linear colour picker
/// (linear_color_picker.h: live, one undo step per gesture). The document stores scene-linear
/// Rec.709; the swatch and the picker show display values through the viewport's display / view
/// (PickerColorSpace; plain sRGB with the built-in tone mapper).

#include "ui/color_picking.h"
#include "ui/properties/linear_color_picker.h"
#include "ui/properties/param_editor.h"

#include <QPointer>

class QToolButton;

namespace velvet::ui {


class ColorParamEditor : public ParamEditor {
    Q_OBJECT
public:
    ColorParamEditor(const ParamMeta& meta, const QString& name, QWidget* parent = nullptr);
    void setValue(glm::vec3 linear) override;
    /// How values are shown and picked; redraws the swatch.
    void setColorSpace(const PickerColorSpace& space);
    const PickerColorSpace& colorSpace() const { return m_space; }

    QToolButton* swatch() const { return m_swatch; }
    /// The picker while it is open (null otherwise).
    LinearColorPicker* picker() const { return m_picker; }
    /// The picker also offers this intensity (emissive strength for the emissive colour): an
    /// intensity beyond 1 without a colour beyond 1. Edits come out of intensityEdited.
    void setIntensity(const ParamMeta& meta, float value);
    void setIntensityValue(float value);
    /// The linear value shown.
    glm::vec3 value() const { return m_linear; }

signals:
    void intensityEdited(float value, int mergeKey);

private:
    void pick();

    QToolButton* m_swatch;
    glm::vec3 m_linear{0.0f};
    PickerColorSpace m_space;
    QPointer<LinearColorPicker> m_picker;
    const ParamMeta* m_intensityMeta = nullptr;
    float m_intensity = 0.0f;
};

} // namespace velvet::ui
