#pragma once
/// @file stage_group.h
/// The Scene dock's "Ground and occlusion" group (docs/shadows.md): the ground under the mesh
/// (off, shadow catcher, plain with its colour and roughness) and the screen-space ambient
/// occlusion (on/off, radius). Every change is one undoable environment edit; spin-box gestures
/// merge into one.

#include "core/scene_parts.h"

#include <QGroupBox>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QPushButton;

namespace velvet::ui {

class DocumentController;

class StageGroup : public QGroupBox {
    Q_OBJECT
public:
    explicit StageGroup(DocumentController* controller, QWidget* parent = nullptr);

private:
    void refresh(velvet::ScenePart parts);

    DocumentController* m_controller;
    QComboBox* m_ground;
    QPushButton* m_groundColor;
    QDoubleSpinBox* m_groundRoughness;
    QCheckBox* m_occlusion;
    QDoubleSpinBox* m_occlusionRadius;
    int m_key = 0;
    bool m_updating = false;
};

} // namespace velvet::ui
