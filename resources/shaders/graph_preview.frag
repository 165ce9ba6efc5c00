#version 450 core
// A material-graph node's thumbnail (render/graph_preview.h): the generated include defines
// velvetGraphPreview(uv), the previewed output's value as RGBA (core/graph/graph_compiler.h).
#include "graph_preview_nodes.glsl"

layout(location = 0) uniform float u_side;       // the target's side in pixels
layout(location = 1) uniform int u_encodeSrgb;   // 1: a colour, sRGB-encode it; 0: data, as is

layout(location = 0) out vec4 fragColor;

// sRGB encoding, IEC 61966-2-1:1999 (the piecewise curve, not gamma 2.2).
vec3 encodeSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
    // Pixel centres: (x + 0.5) / side; row 0 (the bottom of the target, read back first) is v ~ 0.
    vec2 uv = gl_FragCoord.xy / u_side;
    vec4 v = velvetGraphPreview(uv);
    vec3 rgb = u_encodeSrgb != 0 ? encodeSrgb(v.rgb) : clamp(v.rgb, 0.0, 1.0);
    fragColor = vec4(rgb, clamp(v.a, 0.0, 1.0));
}
