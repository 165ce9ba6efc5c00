#pragma once
/// @file uv_transform_editor.h
/// A texture slot's UV transform on the Properties page (issue 17 item 6): tiling (u, v),
/// offset (u, v) and rotation in degrees, the order and sense of the Image texture node
/// (core/texture_ref.h UvTransform). Every committed value (Enter, focus out, an arrow step) is
/// one SetTextureCommand through DocumentController::editTexture, so undo covers it; refresh()
/// shows the document's value without creating commands. Disabled while the slot is empty.
///
/// Widget names: "textureSlot:<id>/uvScaleU", "/uvScaleV", "/uvOffsetU", "/uvOffsetV",
/// "/uvRotation" and "/uvReset".

#include "core/texture_ref.h"

#include <QWidget>
#include <array>

class QDoubleSpinBox;
class QToolButton;

namespace velvet::ui {

class DocumentController;

class UvTransformEditor : public QWidget {
    Q_OBJECT
public:
    UvTransformEditor(DocumentController* controller, TextureSlot slot, const QString& namePrefix,
                      QWidget* parent = nullptr);

    /// Shows the document's UV transform of the slot (no command).
    void refresh();

private:
    void commit();

    DocumentController* m_controller;
    TextureSlot m_slot;
    /// scale u, scale v, offset u, offset v, rotation
    std::array<QDoubleSpinBox*, 5> m_boxes{};
    QToolButton* m_reset = nullptr;
    bool m_refreshing = false;
};

} // namespace velvet::ui
