// G-buffer encodings; the attachments themselves come from the generated gbuffer_layout.glsl
// (render/gbuffer_layout.cpp). CPU twins live in render/gbuffer_layout.cpp.
#include "gbuffer_layout.glsl"
#include "common_math.glsl"

// Cigolle et al. 2014, "A Survey of Efficient Representations for Independent Unit Vectors"
vec2 octEncode(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 e = n.xy;
    if (n.z < 0.0)
        e = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return e;
}
vec3 octDecode(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0)
        n.xy = (1.0 - abs(e.yx)) * vec2(e.x >= 0.0 ? 1.0 : -1.0, e.y >= 0.0 ? 1.0 : -1.0);
    return normalize(n);
}
// The paper's precise variant (oct32P): of the four neighbouring 16-bit points, keep the one that
// decodes closest to n (squared distance: a dot product cannot resolve these angles in float).
// Returns unorm values ready for the RG16 target.
vec2 octEncodeUnorm16(vec3 n) {
    vec2 base = floor((octEncode(n) * 0.5 + 0.5) * 65535.0);
    vec2 best = base;
    float bestDist = 1e30;
    for (int i = 0; i < 4; ++i) {
        vec2 c = clamp(base + vec2(float(i & 1), float(i >> 1)), 0.0, 65535.0);
        vec3 d = octDecode(c / 65535.0 * 2.0 - 1.0) - n;
        if (dot(d, d) < bestDist) {
            bestDist = dot(d, d);
            best = c;
        }
    }
    return best / 65535.0;
}
vec3 octDecodeUnorm16(vec2 u) { return octDecode(u * 2.0 - 1.0); }

// Base colour is stored sRGB-encoded in 8 bits so that dark albedos keep their precision.
vec3 encodeBaseColor(vec3 linear) { return srgbEncode(linear); }
vec3 decodeBaseColor(vec3 stored) { return srgbDecode(stored); }

int decodeMaterialId(float stored) { return int(stored * 255.0 + 0.5); }
