#version 450 core
// FXAA (Lottes 2009, "FXAA", NVIDIA white paper; the compact "FXAA 2" console variant): the
// local luma gradient gives an edge direction, two or four taps along it blend the edge; taps
// whose luma leaves the local range are rejected. Runs on display-encoded colour.
#include "post_common.glsl"
layout(location = 0) out vec4 outColor;

float lumaAt(vec2 uv) { return luminance(texture(uInput, uv).rgb); }

void main() {
    vec2 texel = uTexel.xy;
    vec2 uv = gl_FragCoord.xy * texel;
    float nw = lumaAt(uv + vec2(-0.5, -0.5) * texel), ne = lumaAt(uv + vec2(0.5, -0.5) * texel);
    float sw = lumaAt(uv + vec2(-0.5, 0.5) * texel), se = lumaAt(uv + vec2(0.5, 0.5) * texel);
    vec4 centre = texelFetch(uInput, ivec2(gl_FragCoord.xy), 0);
    float m = luminance(centre.rgb);
    float lo = min(m, min(min(nw, ne), min(sw, se))), hi = max(m, max(max(nw, ne), max(sw, se)));
    if (hi - lo < max(1.0 / 32.0, PARAM(0, FXAA_EDGETHRESHOLD).x * hi)) {
        outColor = centre;
        return;
    }
    vec2 dir = vec2(-((nw + ne) - (sw + se)), (nw + sw) - (ne + se));
    float reduceMul = mix(1.0 / 4.0, 1.0 / 16.0, PARAM(0, FXAA_SUBPIXEL).x);
    float reduce = max((nw + ne + sw + se) * 0.25 * reduceMul, 1.0 / 128.0);
    float rcpMin = 1.0 / (min(abs(dir.x), abs(dir.y)) + reduce);
    dir = clamp(dir * rcpMin, vec2(-8.0), vec2(8.0)) * texel;
    vec3 a = 0.5 * (texture(uInput, uv + dir * (1.0 / 3.0 - 0.5)).rgb +
                    texture(uInput, uv + dir * (2.0 / 3.0 - 0.5)).rgb);
    vec3 b = a * 0.5 + 0.25 * (texture(uInput, uv - dir * 0.5).rgb +
                               texture(uInput, uv + dir * 0.5).rgb);
    float lb = luminance(b);
    outColor = vec4((lb < lo || lb > hi) ? a : b, centre.a);
}
