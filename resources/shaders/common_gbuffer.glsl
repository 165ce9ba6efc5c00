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

// What an 8-bit unsigned normalised target holds of @p v, read back (OpenGL 4.5 §2.3.5.1:
// round(clamp(v) x 255), then / 255).
float unorm8(float v) { return floor(clamp(v, 0.0, 1.0) * 255.0 + 0.5) / 255.0; }

// ---- Lobe channels (render/lobe_channels.h) ---------------------------------------------------
// The first channel of lobe value @p value in the material's map (GpuMaterial::terms2.w), or
// LOBE_PER_MATERIAL.
int lobeChannel(int map, int value) { return (map >> (4 * value)) & 15; }

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited" (JCGT 6(1)): a frame around the
// unit normal n, continuous except across n.z = 0. Both passes build it from the stored normal
// (octDecodeUnorm16 of what the G-buffer holds), so they agree on every side of that seam.
void normalFrame(vec3 n, out vec3 b1, out vec3 b2) {
    float sgn = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sgn + n.z);
    float b = n.x * n.y * a;
    b1 = vec3(1.0 + sgn * n.x * n.x * a, sgn * b, -sgn * n.x);
    b2 = vec3(b, sgn + n.y * n.y * a, -n.y);
}
// An anisotropy direction t (perpendicular to n) as its angle in n's frame over pi, in [0, 1]:
// t and -t stretch the lobe alike, so half a turn suffices (8 bits: 0.7 degree steps).
float encodeTangentAngle(vec3 t, vec3 n) {
    vec3 b1, b2;
    normalFrame(n, b1, b2);
    float phi = atan(dot(t, b2), dot(t, b1)); // (-pi, pi]
    if (phi < 0.0)
        phi += PI;
    return saturate(phi / PI);
}
vec3 decodeTangentAngle(float stored, vec3 n) {
    vec3 b1, b2;
    normalFrame(n, b1, b2);
    float phi = stored * PI;
    return cos(phi) * b1 + sin(phi) * b2;
}
// A normal c within 90 degrees of n as its components along n's frame, [0, 1]^2 (8 bits each:
// about 0.45 degree steps near n, where a coat's normal stays).
vec2 encodeNormalInFrame(vec3 c, vec3 n) {
    vec3 b1, b2;
    normalFrame(n, b1, b2);
    return vec2(dot(c, b1), dot(c, b2)) * 0.5 + 0.5;
}
vec3 decodeNormalInFrame(vec2 stored, vec3 n) {
    vec3 b1, b2;
    normalFrame(n, b1, b2);
    vec2 xy = stored * 2.0 - 1.0;
    return normalize(xy.x * b1 + xy.y * b2 + sqrt(saturate(1.0 - dot(xy, xy))) * n);
}
