#version 450 core
// Brute force, for comparison: one full-screen pass over every light, added by blending.
#include "light_common.glsl"

layout(location = 0) out vec4 outColor;

void main() {
    ShadingPoint p;
    vec4 shadows;
    if (!loadShadingPoint(ivec2(gl_FragCoord.xy), p, shadows))
        discard;
    int view = frame.modes.y;
    vec3 sum = vec3(0.0);
    for (int i = 0; i < uLightCount; ++i)
        sum += shadeLocalLight(lights[i], p, shadows, view);
    outColor = vec4(sum, 0.0);
}
