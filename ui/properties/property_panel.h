#pragma once
/// @file property_panel.h
/// The Properties panel, generated from paramMetas(): one group box per ParamMeta::group, one
/// ParamEditor per parameter. Edits become undo commands through the DocumentController; document
/// changes (undo, redo, open) refresh the editors without creating commands.

#include "core/material.h"
#include "ui/color_picking.h"

#include <QWidget>
#include <vector>

namespace velvet::ui {

class DocumentController;
class ParamEditor;

class PropertyPanel : public QWidget {
    Q_OBJECT
public:
    PropertyPanel(DocumentController* controller, QWidget* parent = nullptr);

    /// The editor of @p id (never null).
    ParamEditor* editor(ParamId id) const { return m_editors[static_cast<size_t>(id)]; }
    /// How colour swatches and pickers show and pick values (the viewport's display / view).
    void setPickerColorSpace(const PickerColorSpace& space);

private:
    void refresh(ParamId id);
    void refreshAll();
    void onEdited(ParamId id, glm::vec3 value, int mergeKey);

    DocumentController* m_controller;
    std::vector<ParamEditor*> m_editors; ///< indexed by ParamId
    bool m_refreshing = false;           ///< set while document values flow into the editors
};

} // namespace velvet::ui
