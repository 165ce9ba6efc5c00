// Tone mapping as a chain stage (pointwise, fused with the effects around it): exposure, a curve
// (display-linear Rec.709 out), then the display encoding, so later LDR effects see
// display-encoded values. displayEncode() is OCIO's own GPU shader for the current display's
// un-tone-mapped view, the generated include "display_encode.glsl" (render/display_encoding.h).
// The full OCIO display transform ("display" operator, or a tone-mapping view) is drawn by
// render/display_transform.cpp instead. Included by a generated main.
#include "post_common.glsl"
#include "common_tonemap.glsl"
#include "display_encode.glsl"

// Hable 2010, "Filmic Tonemapping Operators" (Uncharted 2 curve, white point 11.2)
vec3 hableCurve(vec3 x) {
    const float A = 0.15, B = 0.50, C = 0.10, D = 0.20, E = 0.02, F = 0.30;
    return ((x * (A * x + C * B) + D * E) / (x * (A * x + B) + D * F)) - E / F;
}
vec3 toneMapFilmic(vec3 c) { return hableCurve(2.0 * c) / hableCurve(vec3(11.2)); }

// Wrensch 2023, "Minimal AgX Implementation" (Sobotka's AgX base contrast, polynomial fit)
vec3 agxContrast(vec3 x) {
    vec3 x2 = x * x, x4 = x2 * x2;
    return 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 +
           0.1191 * x - 0.00232;
}
vec3 toneMapAgx(vec3 c) {
    const mat3 inset = mat3(0.842479062253094, 0.0423282422610123, 0.0423756549057051,
                            0.0784335999999992, 0.878468636469772, 0.0784336,
                            0.0792237451477643, 0.0791661274605434, 0.879142973793104);
    const mat3 outset = mat3(1.19687900512017, -0.0528968517574562, -0.0529716355144438,
                             -0.0980208811401368, 1.15190312990417, -0.0980434501171241,
                             -0.0990297440797205, -0.0989611768448433, 1.15107367264116);
    vec3 v = clamp((log2(max(inset * c, 1e-10)) + 12.47393) / 16.5, 0.0, 1.0);
    v = agxContrast(v);
    // agxContrast returns sRGB-encoded values: decode so the display encoding below applies.
    return clamp(srgbDecode(clamp(outset * v, 0.0, 1.0)), 0.0, 1.0);
}

vec4 post_tonemap(vec4 color, ivec2 px, int b) {
    vec3 c = max(color.rgb, vec3(0.0)) * exp2(PARAM(b, TONEMAP_EXPOSURE).x) * post.misc.y;
#ifdef TONEMAP_OPERATOR_FIXED // the pass built for one operator (render/post_chain.cpp)
    const int op = TONEMAP_OPERATOR_FIXED;
#else
    int op = int(PARAM(b, TONEMAP_OPERATOR).x + 0.5);
#endif
    if (op == TONEMAP_OPERATOR_PBR_NEUTRAL)
        c = toneMap(c, TONEMAP_PBR_NEUTRAL);
    else if (op == TONEMAP_OPERATOR_ACES)
        c = toneMap(c, TONEMAP_ACES_FITTED);
    else if (op == TONEMAP_OPERATOR_REINHARD)
        c = toneMap(c, TONEMAP_REINHARD);
    else if (op == TONEMAP_OPERATOR_FILMIC)
        c = clamp(toneMapFilmic(c), 0.0, 1.0);
    else if (op == TONEMAP_OPERATOR_AGX)
        c = toneMapAgx(c);
    else
        c = clamp(c, 0.0, 1.0);
    return vec4(displayEncode(c), 1.0);
}
