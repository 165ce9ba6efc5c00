// Per-frame constants: FrameBlock (instance `frame`, MAX_LIGHTS), IblBlock (instance `ibl`) and
// the debug-view ids with isLightView() / isLobeView(), generated from their one C++
// description in render/render_interface.cpp (std140 offsets static_asserted there).
#include "render_bindings.glsl"
#include "render_interface.glsl"

// How many directional lights frame.lightDirection / lightRadiance hold: FIXED_DIRECTIONAL_LIGHTS
// where the program is specialised to the frame (render/lighting_features.h), so that a loop over
// them has a constant count and unrolls, else the frame block's count.
int directionalLightCount() {
#ifdef FIXED_DIRECTIONAL_LIGHTS
    return FIXED_DIRECTIONAL_LIGHTS;
#else
    return frame.modes.x;
#endif
}
