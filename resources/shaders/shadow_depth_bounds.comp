#version 450 core
// One level of the shadow maps' depth bounds (render/shadow_depth_bounds.h): the least and the
// greatest stored depth over a square of map texels, what the shadow mask's lookup tests a whole
// filter footprint against before it filters (shadow_sampling.glsl, shadowVisibilityBound). Level
// 0 reduces BOUNDS_BLOCK x BOUNDS_BLOCK texels of the depth map; each further level 2x2 texels of
// the level above (a min-max mip chain: Dmitriev and Uralsky 2007, "Soft shadows using
// hierarchical min-max shadow maps").
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2DArray uDepth;           // level 0's source: the depth maps
layout(binding = 0, rg32f) uniform readonly image2DArray uAbove; // other levels' source
layout(binding = 1, rg32f) uniform writeonly image2DArray uTarget;
layout(location = 0) uniform int uLevel;
layout(location = 1) uniform int uLayer;
layout(location = 2) uniform int uSize; // the target level's size
// BOUNDS_BLOCK: map texels per level-0 texel, per side (kShadowBoundsBlock, defined by the build)

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (texel.x >= uSize || texel.y >= uSize)
        return;
    vec2 bounds = vec2(1.0, 0.0);
    if (uLevel == 0) {
        // A gather per 2x2 texels, at their shared corner (a quarter of the fetches).
        vec2 texelSize = 1.0 / vec2(textureSize(uDepth, 0).xy);
        vec2 origin = vec2(texel * BOUNDS_BLOCK);
        for (int y = 0; y < BOUNDS_BLOCK; y += 2)
            for (int x = 0; x < BOUNDS_BLOCK; x += 2) {
                vec4 d = textureGather(uDepth, vec3((origin + vec2(x + 1, y + 1)) * texelSize,
                                                   float(uLayer)));
                bounds = vec2(min(bounds.x, min(min(d.x, d.y), min(d.z, d.w))),
                              max(bounds.y, max(max(d.x, d.y), max(d.z, d.w))));
            }
    } else {
        for (int i = 0; i < 4; ++i) {
            vec2 b = imageLoad(uAbove, ivec3(texel * 2 + ivec2(i & 1, i >> 1), uLayer)).rg;
            bounds = vec2(min(bounds.x, b.x), max(bounds.y, b.y));
        }
    }
    imageStore(uTarget, ivec3(texel, uLayer), vec4(bounds, 0.0, 0.0));
}
