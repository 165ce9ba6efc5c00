// Film grain: a pointwise shader function, post_film_grain() in
// resources/shaders/post_film_grain.frag, fused with its pointwise neighbours.
#include "render/post_effect.h"

namespace velvet::render {
namespace {

/// Film grain: white noise per grain cell, changing 24 times a second, strongest in midtones.
/// Uniforms: uParams[base + FILM_GRAIN_*].
class FilmGrainEffect final : public FusableEffect {
public:
    FilmGrainEffect() : FusableEffect("film_grain") {}
};

} // namespace

std::unique_ptr<PostEffect> makeFilmGrainEffect() {
    return std::make_unique<FilmGrainEffect>();
}

} // namespace velvet::render
