#pragma once
/// @file color_param_editor.h
/// A Color parameter: a swatch button that opens a colour picker. The document stores
/// scene-linear Rec.709; the swatch and the picker show display-encoded sRGB.

#include "ui/properties/param_editor.h"

class QToolButton;

namespace velvet::ui {

class ColorParamEditor : public ParamEditor {
    Q_OBJECT
public:
    ColorParamEditor(ParamId id, QWidget* parent = nullptr);
    void setValue(glm::vec3 linear) override;

    QToolButton* swatch() const { return m_swatch; }
    /// The linear value shown.
    glm::vec3 value() const { return m_linear; }

private:
    void pick();

    QToolButton* m_swatch;
    glm::vec3 m_linear{0.0f};
};

} // namespace velvet::ui
