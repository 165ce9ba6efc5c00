#pragma once
/// @file scene_panel.h
/// The Scene dock: the preview mesh, the environment (HDRI, intensity, rotation, background) and
/// the lights — a rig to start from, the list (add, duplicate, remove) and the selected light's
/// every field. Every change is one undoable command through the DocumentController; spin-box
/// and slider gestures merge into one (like Properties).

#include "core/scene.h"
#include "core/scene_parts.h"
#include "ui/scene/scene_choosers.h"

#include <QWidget>
#include <optional>
#include <vector>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QFormLayout;
class QLabel;
class QLineEdit;
class QListWidget;
class QPushButton;
class QToolButton;

namespace velvet::ui {

class DocumentController;
class Vec3Editor;

class ScenePanel : public QWidget {
    Q_OBJECT
public:
    explicit ScenePanel(DocumentController* controller, QWidget* parent = nullptr);

    /// The row of the selected light (-1: none).
    int selectedLight() const;
    void selectLight(int index);
    /// Adds a light of @p type in front of the mesh (one command) and selects it.
    void addLight(LightType type, AreaShape shape = AreaShape::Sphere);
    void duplicateSelectedLight();
    void removeSelectedLight();

private:
    void buildEnvironmentGroup(QFormLayout* form);
    void buildLightEditor(QFormLayout* form);
    /// Refills what shows @p parts of the scene (DocumentController::sceneChanged).
    void refresh(velvet::ScenePart parts);
    void refreshLightList();
    void refreshLightEditor();
    /// Replaces the selected light with @p light (one command named @p text, merged by
    /// @p mergeKey).
    void editSelected(const Light& light, const QString& text, int mergeKey);
    void editBackground(BackgroundMode mode, glm::vec3 color);
    bool eventFilter(QObject* watched, QEvent* event) override;

    DocumentController* m_controller;
    bool m_updating = false;
    int m_envKey = 0;      ///< merge key of the environment gesture in progress
    int m_lightKey = 0;    ///< merge key of the light gesture in progress (new per selection)
    int m_shownLight = -1; ///< the light the editor shows

    // Mesh and environment.
    QComboBox* m_mesh;
    QLabel* m_meshError; ///< the last refused mesh file and why (hidden once the mesh changes)
    QComboBox* m_hdri;
    QDoubleSpinBox* m_envIntensity;
    QDoubleSpinBox* m_envRotation;
    QComboBox* m_background;
    QPushButton* m_backgroundColor;

    // Lights.
    QComboBox* m_rig;
    QListWidget* m_lights;
    QToolButton* m_add;
    QPushButton* m_duplicate;
    QPushButton* m_remove;
    QWidget* m_editor;
    QFormLayout* m_editorForm;
    QLineEdit* m_name;
    QComboBox* m_type;
    QComboBox* m_shape;
    QPushButton* m_color;
    QDoubleSpinBox* m_intensity;
    Vec3Editor* m_position;
    Vec3Editor* m_direction;
    QDoubleSpinBox* m_range;
    QDoubleSpinBox* m_inner;
    QDoubleSpinBox* m_outer;
    QDoubleSpinBox* m_sizeX;
    QDoubleSpinBox* m_sizeY;
    QCheckBox* m_castShadows;
    QDoubleSpinBox* m_sourceSize; ///< directional: angle (°); point and spot: radius (m)
};

} // namespace velvet::ui
