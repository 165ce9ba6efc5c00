// Per-frame constants: FrameBlock (instance `frame`, MAX_LIGHTS), IblBlock (instance `ibl`) and
// the debug-view ids with isLightView() / isLobeView(), generated from their one C++
// description in render/render_interface.cpp (std140 offsets static_asserted there).
#include "render_bindings.glsl"
#include "render_interface.glsl"
