// Per-frame constants; mirrors struct FrameBlock in render/renderer.cpp (std140, vec4 only).
#include "render_bindings.glsl"
#define MAX_LIGHTS 16

layout(std140, binding = BINDING_FRAME_UBO) uniform FrameBlock {
    mat4 viewMatrix;
    mat4 projMatrix;
    mat4 invProjMatrix;
    mat4 invViewMatrix;
    mat4 viewProjMatrix;
    vec4 cameraPosition;   // xyz world, w: 1 orthographic
    vec4 viewport;         // width, height, 1/width, 1/height
    vec4 envSh[9];         // SH9 of the environment radiance, intensity applied
    vec4 envParams;        // cos(rotation), sin(rotation), intensity, max mip level
    vec4 ambientRadiance;  // rgb: uniform radiance of ambient lights
    vec4 backgroundColor;  // rgb, w: background mip level
    ivec4 modes;           // light count, debug view, tone mapper, background mode
    vec4 post;             // exposure multiplier, depth view range, environment width, unused
    vec4 lightDirection[MAX_LIGHTS]; // xyz: towards the light, world
    vec4 lightRadiance[MAX_LIGHTS];  // rgb: colour x illuminance
} frame;

#define DEBUG_FINAL 0
#define DEBUG_ALBEDO 1
#define DEBUG_NORMAL 2
#define DEBUG_DEPTH 3
#define DEBUG_ROUGHNESS 4
#define DEBUG_METALLIC 5
#define DEBUG_POSITION 6
