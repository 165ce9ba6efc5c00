#pragma once
/// @file color_param_editor.h
/// A Color parameter: a swatch button that opens a colour picker. The document stores
/// scene-linear Rec.709; the swatch and the picker show display values through the viewport's
/// display / view (PickerColorSpace; plain sRGB with the built-in tone mapper).

#include "ui/color_picking.h"
#include "ui/properties/param_editor.h"

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
    /// The linear value shown.
    glm::vec3 value() const { return m_linear; }

private:
    void pick();

    QToolButton* m_swatch;
    glm::vec3 m_linear{0.0f};
    PickerColorSpace m_space;
};

} // namespace velvet::ui
