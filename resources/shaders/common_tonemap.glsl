// Tone-mapping operators (scene-linear Rec.709 in, display-linear [0, 1] out).
#include "common_math.glsl"

// Khronos PBR Neutral Tone Mapper (Khronos Group 2024, "PBR Neutral" specification)
vec3 toneMapPbrNeutral(vec3 color) {
    const float startCompression = 0.8 - 0.04;
    const float desaturation = 0.15;
    float x = min(color.r, min(color.g, color.b));
    float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    color -= offset;
    float peak = max3(color);
    if (peak < startCompression)
        return color;
    const float d = 1.0 - startCompression;
    float newPeak = 1.0 - d * d / (peak + d - startCompression);
    color *= newPeak / peak;
    float g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
    return mix(color, vec3(newPeak), g);
}

// Hill 2016, "ACES fitted" (BakingLab): sRGB -> AP1-ish input matrix, RRT+ODT fit, output matrix
vec3 toneMapAcesFitted(vec3 color) {
    const mat3 inputMat = mat3(0.59719, 0.07600, 0.02840, 0.35458, 0.90834, 0.13383, 0.04823,
                               0.01566, 0.83777);
    const mat3 outputMat = mat3(1.60475, -0.10208, -0.00327, -0.53108, 1.10813, -0.07276,
                                -0.07367, -0.00605, 1.07602);
    vec3 v = inputMat * color;
    vec3 a = v * (v + 0.0245786) - 0.000090537;
    vec3 b = v * (0.983729 * v + 0.4329510) + 0.238081;
    return clamp(outputMat * (a / b), 0.0, 1.0);
}

// Reinhard et al. 2002, "Photographic Tone Reproduction for Digital Images" (simple operator)
vec3 toneMapReinhard(vec3 color) { return color / (1.0 + color); }

// TONEMAP_PBR_NEUTRAL .. TONEMAP_LINEAR: render::ToneMapper's numbers, generated into
// render_interface.glsl from render/render_interface.cpp.
#include "render_interface.glsl"

vec3 toneMap(vec3 color, int op) {
    color = max(color, vec3(0.0));
    if (op == TONEMAP_ACES_FITTED)
        return toneMapAcesFitted(color);
    if (op == TONEMAP_REINHARD)
        return toneMapReinhard(color);
    if (op == TONEMAP_LINEAR)
        return clamp(color, 0.0, 1.0);
    return clamp(toneMapPbrNeutral(color), 0.0, 1.0);
}
