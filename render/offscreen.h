#pragma once
/// @file offscreen.h
/// One-call headless rendering for the CLI and tests.

#include <string>

#include "core/diagnostics.h"
#include "core/image.h"
#include "core/scene.h"
#include "render/renderer.h"

namespace velvet::render {

/// Renders @p scene off screen (creating a headless EGL context when none is current).
/// @p linear receives scene-linear RGBA float, @p display the display-encoded RGBA; either may be
/// null. False + message when no context can be made or rendering fails.
bool renderSceneOffscreen(const Scene& scene, const FrameSettings& settings, Image* linear,
                          Image* display, std::string* error, Problems* problems = nullptr);

} // namespace velvet::render
