#version 450 core
// Exposure and a built-in tone-mapping curve (display-linear Rec.709 out), then the display
// encoding into the target framebuffer: displayEncode() is OCIO's own GPU shader for the current
// display's un-tone-mapped view, the generated include "display_encode.glsl"
// (render/display_encoding.h). Debug views get a display mapping of their raw values instead.
#include "common_frame.glsl"
#include "common_tonemap.glsl"
#include "display_encode.glsl"
#include "debug_views.glsl"

layout(binding = BINDING_HDR_TEX) uniform sampler2D uHdr;
layout(location = 0) out vec4 outColor;

void main() {
    vec3 c = texelFetch(uHdr, ivec2(gl_FragCoord.xy), 0).rgb;
    int view = frame.modes.y;
    vec3 display;
    if (view == DEBUG_FINAL)
        display = displayEncode(toneMap(c * frame.post.x, frame.modes.z));
    else if (view == DEBUG_ALBEDO)
        display = displayEncode(c);
    else if (view == DEBUG_NORMAL || view == DEBUG_POSITION)
        display = c * 0.5 + 0.5;
    else if (view == DEBUG_DEPTH)
        display = vec3(c.x > 0.0 ? 1.0 - saturate(c.x / frame.post.y) : 0.0);
    else {
        bool encode;
        if (!debugDisplay(view, c, frame.post.x, display, encode))
            display = c;
        else if (encode)
            display = displayEncode(display);
    }
    outColor = vec4(clamp(display, 0.0, 1.0), 1.0);
}
