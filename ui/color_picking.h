#pragma once
/// @file color_picking.h
/// How colour pickers and swatches show scene-linear colours (docs/color-management.md): through
/// the viewport's current OCIO display / view / look (OCIO's CPU processor, exposure left out), or
/// plain sRGB while the viewport uses the built-in tone mapper. Picked display values go back to
/// scene-linear through the inverse: exact for sRGB, and for OCIO views a numerical inverse of the
/// CPU processor (core offers no inverse display transform), which falls back to the sRGB inverse
/// when it cannot converge (values a tone-mapping view never reaches, e.g. display white).

#include "core/color_management.h"

#include <QColor>
#include <glm/vec3.hpp>
#include <memory>

namespace velvet::ui {

struct PickerColorSpace {
    /// The config the display names refer to; null means plain sRGB.
    std::shared_ptr<const ColorManagement> colorManagement;
    /// Display, view and look of the viewport; all empty: plain sRGB (the built-in tone mapper).
    DisplaySettings display;

    bool isSrgb() const {
        return !colorManagement || !colorManagement->isLoaded() ||
               (display.display.empty() && display.view.empty() && display.look.empty());
    }
    /// Scene-linear Rec.709 -> display-encoded, clamped to [0, 1].
    glm::vec3 toDisplay(glm::vec3 linear) const;
    /// Display-encoded -> scene-linear Rec.709 (the inverse of toDisplay where one exists).
    glm::vec3 toLinear(glm::vec3 display) const;
    QColor toQColor(glm::vec3 linear) const;
    glm::vec3 fromQColor(const QColor& color) const;
    /// "sRGB" or "<display> / <view>" for tooltips.
    QString name() const;
};

} // namespace velvet::ui
