#version 450 core
// Light volumes: shades the pixel under one proxy fragment with that light, added by blending.
#include "light_common.glsl"

layout(location = 0) flat in int vLight;
layout(location = 0) out vec4 outColor;

void main() {
    ShadingPoint p;
    if (!loadShadingPoint(ivec2(gl_FragCoord.xy), p))
        discard;
    outColor = vec4(shadeLocalLight(lights[vLight], p, frame.modes.y), 0.0);
}
