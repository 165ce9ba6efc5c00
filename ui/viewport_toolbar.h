#pragma once
/// @file viewport_toolbar.h
/// The viewport's toolbars.
///
/// ViewportToolbar holds *view state*: debug view, OCIO display / view / look, exposure and the
/// per-pass timing overlay. It is persisted in QSettings and never undoable (issue 6: what the
/// artist looks through is not part of the material).
///
/// SceneToolbar edits *the document*: preview mesh, HDRI, environment intensity and rotation,
/// light rig.
/// Each change is an undo command through DocumentController (drags merge into one).

#include "core/scene_parts.h"
#include "render/renderer.h"
#include "ui/color_picking.h"
#include "ui/scene/scene_choosers.h"

#include <QToolBar>
#include <memory>
#include <optional>
#include <span>

class QAction;
class QComboBox;
class QDoubleSpinBox;
class QSlider;
class QToolButton;

namespace velvet {
class ColorManagement;
}

namespace velvet::ui {

class DocumentController;

/// One debug view entry of the toolbar's combo. render::DebugView has no reflection: this table
/// is the one place to add a new value (ViewportToolbar::debugViews()).
struct DebugViewEntry {
    render::DebugView view;
    const char* label;
};

class ViewportToolbar : public QToolBar {
    Q_OBJECT
public:
    /// @p colorManagement lists displays, views and looks (null or unloaded: built-in only).
    ViewportToolbar(std::shared_ptr<const ColorManagement> colorManagement,
                    QWidget* parent = nullptr);

    /// Every debug view the combo offers, in combo order.
    static std::span<const DebugViewEntry> debugViews();

    /// The view state as frame settings (width and height left at their defaults).
    render::FrameSettings frameSettings() const;
    /// The colour pickers' space: the chosen display/view/look, or sRGB when built-in.
    PickerColorSpace pickerColorSpace() const;
    bool timingOverlay() const;
    /// The still view refined by progressive anti-aliasing (ViewportWidget; on by default).
    bool progressiveAntialias() const;
    /// The view drawn at half size while it moves (ViewportWidget::setReducedResolution; on by
    /// default); off, full size, the stage's soft terms coarser while the camera moves.
    bool reducedWhileMoving() const;

    /// Reads the view state from QSettings (unknown names fall back to the defaults).
    void restoreSettings();
    /// Writes the view state to QSettings (also done on every change).
    void saveSettings() const;

signals:
    /// Debug view, display, view, look or exposure changed.
    void viewStateChanged();
    void timingOverlayToggled(bool visible);
    void progressiveAntialiasToggled(bool on);
    void reducedWhileMovingToggled(bool on);

private:
    void fillViews();
    void onChanged();

    std::shared_ptr<const ColorManagement> m_colorManagement;
    QComboBox* m_debugView;
    QComboBox* m_display;
    QComboBox* m_view;
    QComboBox* m_look;
    QDoubleSpinBox* m_exposure;
    QSlider* m_exposureSlider;
    QAction* m_antialias;
    QAction* m_reduced;
    QAction* m_overlay;
    bool m_updating = false;
};

class SceneToolbar : public QToolBar {
    Q_OBJECT
public:
    SceneToolbar(DocumentController* controller, QWidget* parent = nullptr);

    /// Shows the document's mesh and environment (emits no edits).
    /// Refills what shows @p parts of the scene (DocumentController::sceneChanged).
    void refresh(velvet::ScenePart parts);

private:
    void onMeshChosen(int index);
    void onHdriChosen(int index);
    void editEnvironment(const QString& text, int mergeKey, float intensity, float rotationDeg);

    DocumentController* m_controller;
    QComboBox* m_mesh;
    QComboBox* m_hdri;
    QDoubleSpinBox* m_intensity;
    QSlider* m_rotation;
    QComboBox* m_lightRig;
    QToolButton* m_ground; ///< the ground on (shadow catcher) or off (docs/shadows.md)
    int m_intensityKey = 0;
    int m_rotationKey = 0;
    bool m_updating = false;
};

} // namespace velvet::ui
