#pragma once
/// @file inline_post.h
/// Render-private: what the post chain or the display output hands the lighting pass to compile
/// in (docs/architecture.md, "The display step inside the lighting pass").

#include "render/shader_program.h"

#include <string>

namespace velvet::render {

/// The display step compiled into the final image's lighting programs (lighting.frag's
/// LIGHTING_INLINE_POST, issue 16): the generated include "inline_post.glsl", which defines
/// `vec4 postInline(vec4 linear, ivec2 px)`, with the generated includes it needs
/// (PostChainRenderer::inlineSource, DisplayOutput::inlineSource). Programs are kept per key.
struct InlinePost {
    std::string key;
    GeneratedSources sources;
};

} // namespace velvet::render
