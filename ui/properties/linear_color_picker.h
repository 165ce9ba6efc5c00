#pragma once
/// @file linear_color_picker.h
/// A colour picker for a scene-linear workflow (issue 17 item 7), after Blender's: a hue /
/// saturation wheel and a value slider in display space, the display-referred values and the
/// stored scene-linear values side by side, hex in display space (#RRGGBB of what the screen
/// shows), an intensity beyond 1 where the parameter has one (emission: its strength), and an
/// eyedropper that picks a pixel of the viewport and stores the linear value that displays as
/// that pixel (the inverse of the viewport's display transform, PickerColorSpace). The colour
/// spaces are named as the OCIO config names them.
///
/// It is not modal: every change is sent at once (colorEdited) so the viewport previews it live,
/// with one merge key per gesture (a wheel or slider drag is one undo step); typed values are a
/// step each. The document stays the truth: setLinear() follows undo while the picker is open.

#include "ui/color_picking.h"

#include <QDialog>
#include <glm/vec3.hpp>

class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QSlider;

namespace velvet::ui {

class ViewportWidget;

class LinearColorPicker : public QDialog {
    Q_OBJECT
public:
    LinearColorPicker(const QString& title, glm::vec3 linear, const PickerColorSpace& space,
                      QWidget* parent = nullptr);

    /// Shows an intensity field (e.g. emissive strength in nits) next to the colour.
    void setIntensity(float value, float max, const QString& unit);
    /// The viewport the eyedropper picks from (none: no eyedropper button).
    void setViewport(ViewportWidget* viewport);

    /// The document's value (after undo, or an edit elsewhere): shown, nothing sent.
    void setLinear(glm::vec3 linear);
    void setIntensityValue(float value);
    glm::vec3 linear() const { return m_linear; }
    glm::vec3 display() const { return m_display; }
    /// "#RRGGBB" of the display-encoded colour.
    QString hex() const;

    /// @name Parts, for tests
    /// @{
    QWidget* wheel() const { return m_wheel; }
    QSlider* valueSlider() const { return m_value; }
    QLineEdit* hexField() const { return m_hex; }
    QDoubleSpinBox* displayBox(int channel) const { return m_displayBoxes[channel]; }
    QDoubleSpinBox* linearBox(int channel) const { return m_linearBoxes[channel]; }
    QDoubleSpinBox* intensityBox() const { return m_intensity; }
    QPushButton* eyedropper() const { return m_eyedropper; }
    QLabel* spaceLabel() const { return m_spaceLabel; }
    /// @}

    /// A new gesture key (shared with ParamEditor's).
    static int nextGestureKey();

signals:
    /// The colour changed by the artist: scene-linear, with the gesture's merge key (0: a step).
    void colorEdited(glm::vec3 linear, int mergeKey);
    void intensityEdited(float value, int mergeKey);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    friend class HueWheel;
    /// From the wheel and slider (display HSV).
    void setFromHsv(float h, float s, float v, int key);
    void setFromDisplay(glm::vec3 display, int key);
    void setFromLinearValue(glm::vec3 linear, int key);
    void showValues();
    void pickAt(QPoint pos);

    PickerColorSpace m_space;
    glm::vec3 m_linear{0.0f};
    glm::vec3 m_display{0.0f};
    float m_hue = 0.0f, m_sat = 0.0f, m_val = 0.0f; ///< display HSV (hue kept through grey)
    QWidget* m_wheel = nullptr;
    QSlider* m_value = nullptr;
    QLineEdit* m_hex = nullptr;
    QDoubleSpinBox* m_displayBoxes[3] = {};
    QDoubleSpinBox* m_linearBoxes[3] = {};
    QDoubleSpinBox* m_intensity = nullptr;
    QLabel* m_intensityLabel = nullptr;
    QPushButton* m_eyedropper = nullptr;
    QLabel* m_spaceLabel = nullptr;
    QWidget* m_swatch = nullptr;
    ViewportWidget* m_viewport = nullptr;
    int m_sliderKey = 0;
    bool m_showing = false; ///< values flowing into the fields
};

} // namespace velvet::ui
