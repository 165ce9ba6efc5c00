// Toon shading (seed 002): luminance scaled by the light intensity and cut into `bands` flat
// levels, keeping hue; an outline where depth or normals change sharply. Pointwise in colour
// (reads depth and normals of the neighbours); included by a generated main.
#include "post_common.glsl"

vec4 post_toon(vec4 color, ivec2 px, int b) {
    if (sceneDepth(px) >= 1.0)
        return color; // the background is not shaded
    float l = luminance(color.rgb);
    float n = floor(PARAM(b, TOON_BANDS).x + 0.5);
    float x = l * PARAM(b, TOON_LIGHTINTENSITY).x;
    float q = (min(floor(x * n), n - 1.0) + 1.0) / n; // one of n levels in (0, 1]
    vec3 c = l > 1e-6 ? color.rgb * (q / l) : vec3(0.0);
    if (PARAM(b, TOON_OUTLINE).x > 0.5) {
        ivec2 size = ivec2(post.viewport.xy) - 1;
        float z = viewDistance(px);
        vec3 nc = sceneNormal(px);
        float edge = 0.0;
        const ivec2 offsets[4] = ivec2[](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
        for (int i = 0; i < 4; ++i) {
            ivec2 q2 = clamp(px + offsets[i], ivec2(0), size);
            float zn = sceneDepth(q2) >= 1.0 ? 1e6 : viewDistance(q2);
            edge = max(edge, abs(zn - z) / max(z, 1e-3));
            edge = max(edge, 1.0 - dot(nc, sceneNormal(q2)));
        }
        if (edge > PARAM(b, TOON_OUTLINETHRESHOLD).x)
            c = PARAM(b, TOON_OUTLINECOLOR).rgb;
    }
    return vec4(c, color.a);
}
