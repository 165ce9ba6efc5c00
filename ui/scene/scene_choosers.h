#pragma once
/// @file scene_choosers.h
/// The combo boxes that choose a preview mesh, an HDRI and a light rig, shared by the Scene
/// toolbar over the viewport and the Scene dock (one behaviour, two places). fill* shows the
/// document's current choice without emitting edits; apply* turns the artist's pick into one
/// undoable edit through the DocumentController (opening a file dialog for "Custom mesh…" and
/// "Other HDRI…").

#include "core/scene.h"

#include <QString>

class QComboBox;
class QWidget;

namespace velvet::ui {

class DocumentController;

/// Combo items that open a file dialog carry true under this role.
inline constexpr int kComboRoleAction = 0x0100 + 1; // Qt::UserRole + 1

/// Absolute, normal, '/'-separated: the form core stores resource paths in (document_io.cpp).
QString normalPath(const QString& path);

void fillMeshCombo(QComboBox* combo, const Scene& scene);
void applyMeshChoice(DocumentController* controller, QComboBox* combo, int index,
                     QWidget* dialogParent);

void fillHdriCombo(QComboBox* combo, const Scene& scene);
void applyHdriChoice(DocumentController* controller, QComboBox* combo, int index,
                     QWidget* dialogParent);

/// Every rig of core/light_rigs.h, plus "Custom" while the lights match none of them.
void fillLightRigCombo(QComboBox* combo, const Scene& scene);
void applyLightRigChoice(DocumentController* controller, QComboBox* combo, int index);

} // namespace velvet::ui
