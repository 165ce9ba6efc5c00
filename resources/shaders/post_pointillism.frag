#version 450 core
// Pointillism (seed 004): an imaginary grid; each cell holds a dot of its centre's colour whose
// radius grows as the cell gets darker; a pixel looks at the 3x3 cells around it and shows the
// first dot that covers it, else the paper colour. Deterministic (no time).
#include "post_common.glsl"
layout(location = 0) out vec4 outColor;

void main() {
    float cell = max(PARAM(0, POINTILLISM_CELLSIZE).x, 2.0);
    vec2 p = gl_FragCoord.xy;
    ivec2 home = ivec2(floor(p / cell));
    ivec2 size = textureSize(uInput, 0) - 1;
    vec3 result = PARAM(0, POINTILLISM_PAPERCOLOR).rgb;
    float best = 1e9;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            ivec2 c = home + ivec2(i, j);
            vec2 jitter = vec2(hash13(vec3(c, 1.0)), hash13(vec3(c, 2.0))) - 0.5;
            vec2 centre = (vec2(c) + 0.5 + 0.3 * jitter) * cell;
            vec3 colour = texelFetch(uInput, clamp(ivec2(centre), ivec2(0), size), 0).rgb;
            float darkness = 1.0 - clamp(luminance(colour), 0.0, 1.0);
            float radius = 0.75 * cell * PARAM(0, POINTILLISM_DOTSCALE).x * sqrt(darkness + 0.05);
            float d = length(p - centre);
            if (d < radius && d / radius < best) {
                best = d / radius;
                result = colour;
            }
        }
    outColor = vec4(result, 1.0);
}
