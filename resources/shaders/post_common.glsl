// Shared by every post-effect shader (render/post_chain.cpp). Parameter slots and bindings come
// from the generated "post_params.glsl" (one #define per catalogue parameter, core/post_effects.cpp).
#include "post_params.glsl"
#include "common_gbuffer.glsl"
#include "common_hash.glsl"

// Each parameter of an effect is one vec4 slot (scalars and choices in x, colours in xyz); fused
// passes give each effect its own base slot.
layout(location = 0) uniform vec4 uParams[POST_MAX_SLOTS];
#define PARAM(base, k) uParams[(base) + (k)]
// x: pass index, y: level / tap count; effects document their own use.
layout(location = POST_PASS_LOCATION) uniform ivec4 uPass;
// xy: 1 / size of uInput, zw: output size in pixels.
layout(location = POST_TEXEL_LOCATION) uniform vec4 uTexel;
// Multi-pass effects compile one program per pass (POST_PASS defined), so llvmpipe, which runs
// every side of a branch under a mask, executes only the pass's own code.
#ifndef POST_PASS
#define POST_PASS uPass.x
#endif

// A chain drawn inside the lighting pass (POST_INLINE, render/post_chain.h inlineSource) reads
// the lit colour, not an image, and its units hold the lighting's own textures.
#ifndef POST_INLINE
layout(binding = POST_INPUT_UNIT) uniform sampler2D uInput; // bilinear, clamped
layout(binding = POST_AUX_UNIT) uniform sampler2D uAux;     // a second image (pre-pass, blur)
#endif

// PostFrame (instance `post`), generated from render/render_interface.cpp's PostFrameBlock.
#include "post_interface.glsl"

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// Hardware depth at a pixel (1: background).
float sceneDepth(ivec2 px) { return texelFetch(gDepthTex, px, 0).r; }
// Positive view-space distance along -Z reconstructed with the inverse projection.
float viewDistance(ivec2 px) {
    vec2 uv = (vec2(px) + 0.5) * post.viewport.zw;
    vec4 v = post.invProj * vec4(uv * 2.0 - 1.0, sceneDepth(px) * 2.0 - 1.0, 1.0);
    return -v.z / v.w;
}
vec3 sceneNormal(ivec2 px) { return octDecodeUnorm16(texelFetch(gNormalTex, px, 0).rg); }
vec2 pixelUv(ivec2 px) { return (vec2(px) + 0.5) * post.viewport.zw; }
