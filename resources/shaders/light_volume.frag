#version 450 core
// Light volumes: shades the pixel under one proxy fragment with that light, added by blending.
#include "light_common.glsl"

layout(location = 0) flat in int vLight;
layout(location = 0) out vec4 outColor;

void main() {
    ShadingPoint p;
    vec4 shadows;
    if (!loadShadingPoint(ivec2(gl_FragCoord.xy), p, shadows))
        discard;
    outColor = vec4(shadeLocalLight(lights[vLight], p, shadows, frame.modes.y), 0.0);
}
