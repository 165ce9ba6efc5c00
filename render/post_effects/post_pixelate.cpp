// Pixelation: one pass of resources/shaders/post_pixelate.frag.
#include "render/post_effect.h"

namespace velvet::render {
namespace {

/// Pixelation (seed 000): every `cellSize` square cell takes the colour at its centre, so each cell
/// is exactly constant. Reads the cell centre, not its own pixel: not fusable. Uniforms:
/// uParams[PIXELATE_CELLSIZE].
class PixelateEffect final : public SinglePassEffect {
public:
    PixelateEffect() : SinglePassEffect("pixelate") {}
};

} // namespace

std::unique_ptr<PostEffect> makePixelateEffect() {
    return std::make_unique<PixelateEffect>();
}

} // namespace velvet::render
