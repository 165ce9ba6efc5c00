#version 450 core
// The final pass when an OpenColorIO display/view is chosen: scene-linear HDR in, display-encoded
// out, entirely through OCIO's own GPU shader (OCIO 2.1 GpuShaderDesc, GLSL 4.0), injected by
// render/display_transform.cpp as the generated include "ocio_display.glsl". That function applies
// exposure (a dynamic ExposureContrast uniform), the look and the display/view transform, so this
// shader adds nothing to the colour: it only fetches, calls and clamps to the [0, 1] a UNORM
// target stores. OCIO_DISPLAY is defined to the generated function's name.
#include "render_bindings.glsl"
#include "ocio_display.glsl"

layout(binding = BINDING_HDR_TEX) uniform sampler2D uHdr;
layout(location = 0) out vec4 outColor;

void main() {
    vec3 c = texelFetch(uHdr, ivec2(gl_FragCoord.xy), 0).rgb;
    outColor = vec4(clamp(OCIO_DISPLAY(vec4(c, 1.0)).rgb, 0.0, 1.0), 1.0);
}
