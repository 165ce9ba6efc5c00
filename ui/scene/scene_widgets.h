#pragma once
/// @file scene_widgets.h
/// Pieces the Scene dock's two halves share (ui/scene/scene_panel.cpp: mesh, environment and the
/// light list; ui/scene/scene_light_editor.cpp: the selected light's fields): a three-box vector
/// editor, the light types' labels and units, colour swatches and the spin-box factory.

#include "core/scene.h"

#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QSignalBlocker>
#include <QString>
#include <QWidget>
#include <functional>
#include <glm/vec3.hpp>
#include <optional>

class QPushButton;

namespace velvet::ui {

/// Three spin boxes for a vector (position or direction); calls back on every change.
class Vec3Editor : public QWidget {
public:
    Vec3Editor(const QString& name, double range, QWidget* parent) : QWidget(parent) {
        setObjectName(name);
        auto* row = new QHBoxLayout(this);
        row->setContentsMargins(0, 0, 0, 0);
        const char* axes[] = {"x", "y", "z"};
        for (int i = 0; i < 3; ++i) {
            m_boxes[i] = new QDoubleSpinBox(this);
            m_boxes[i]->setObjectName(name + QLatin1Char('.') + QLatin1String(axes[i]));
            m_boxes[i]->setRange(-range, range);
            m_boxes[i]->setDecimals(2);
            m_boxes[i]->setSingleStep(0.1);
            m_boxes[i]->setPrefix(QLatin1String(axes[i]) + QLatin1Char(' '));
            m_boxes[i]->setKeyboardTracking(false); // a typed "2.5" is one value, not 2 then 25
            row->addWidget(m_boxes[i]);
            connect(m_boxes[i], &QDoubleSpinBox::valueChanged, this, [this, i](double v) {
                if (onChanged)
                    onChanged(i, float(v));
            });
            connect(m_boxes[i], &QDoubleSpinBox::editingFinished, this, [this] {
                if (onFinished)
                    onFinished();
            });
        }
    }
    glm::vec3 value() const {
        return {float(m_boxes[0]->value()), float(m_boxes[1]->value()), float(m_boxes[2]->value())};
    }
    void setValue(glm::vec3 v) {
        for (int i = 0; i < 3; ++i) {
            const QSignalBlocker block(m_boxes[i]);
            m_boxes[i]->setValue(double(v[i]));
        }
    }
    /// One component changed (@p axis 0..2): the others keep the light's own values (the boxes
    /// round to two decimals and clamp to their range).
    std::function<void(int axis, float value)> onChanged;
    std::function<void()> onFinished;

private:
    QDoubleSpinBox* m_boxes[3];
};

/// The light type's name as the dock shows it.
QString typeLabel(LightType type);
/// The unit of Light::intensity for @p type (docs/units.md).
QString intensityUnit(LightType type);
/// Shows scene-linear @p linear on @p button (sRGB encoded) with its value as the tool tip.
void showSwatch(QPushButton* button, glm::vec3 linear);
/// Opens the colour dialog on @p linear; the picked sRGB colour as scene-linear, or nullopt.
std::optional<glm::vec3> pickLinearColor(QWidget* parent, glm::vec3 linear, const QString& title);
/// A spin box that edits on Return, focus loss, arrows and wheel, not per keystroke.
QDoubleSpinBox* makeSpin(const QString& name, double min, double max, double step, int decimals,
                         const QString& tip, QWidget* parent);

} // namespace velvet::ui
