#pragma once
/// @file gl_util.h
/// Render-private: the GL error queue as messages, the `false + message` failure idiom of the
/// renderer's passes, and colour read-backs. Needs a current OpenGL 4.5 context.

#include "core/image.h"

#include <string>

namespace velvet::render {

/// GL_INVALID_ENUM … GL_OUT_OF_MEMORY by name ("GL error N" for anything else).
std::string glErrorName(unsigned error);

/// Drains the GL error queue (at most 32 entries); the first error's name, or "" when empty.
std::string takeGlErrors();

/// Stores @p message in @p error (when given) and returns false: `return fail(error, "…");`.
bool fail(std::string* error, const std::string& message);

/// RGBA float pixels of framebuffer @p fbo's colour attachment 0 (0: the default back buffer),
/// top row first. The read binding is restored.
Image readFramebuffer(unsigned fbo, int width, int height);

} // namespace velvet::render
