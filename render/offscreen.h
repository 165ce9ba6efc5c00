#pragma once
/// @file offscreen.h
/// One-call headless rendering for the CLI and tests.

#include "core/diagnostics.h"
#include "core/image.h"
#include "core/scene.h"
#include "render/renderer.h"

#include <memory>
#include <string>

namespace velvet::render {

/// Renders @p scene off screen (creating a headless EGL context when none is current).
/// @p linear receives scene-linear RGBA float, @p display the display-encoded RGBA; either may be
/// null. @p colorManagement is the OCIO config for settings.display/displayView/look (null: the
/// renderer loads the default one when it needs it). False + message when no context can be made
/// or rendering fails.
bool renderSceneOffscreen(const Scene& scene, const FrameSettings& settings, Image* linear,
                          Image* display, std::string* error, Problems* problems = nullptr,
                          std::shared_ptr<const ColorManagement> colorManagement = nullptr);

/// A display-format (RGBA8) framebuffer to render into without a window (CLI, tests, bench).
/// Needs a current context for its whole life.
class OffscreenTarget {
public:
    OffscreenTarget();
    ~OffscreenTarget();
    /// (Re)allocates; false + message when the framebuffer is incomplete.
    bool resize(int width, int height, std::string* error);
    /// The GL framebuffer name, for Renderer::render.
    unsigned framebuffer() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace velvet::render
