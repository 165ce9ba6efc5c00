#version 450 core
// Screen-space ambient occlusion at half resolution (a quarter while the camera moves: texel t
// stands for pixel D t, D = stage.counts.y): GTAO (Jimenez et al. 2016, "Practical
// Real-Time Strategies for Accurate Indirect Occlusion"), the horizon search on both sides of
// two slices per pixel and the slice's cosine-weighted visibility integrated in closed form with
// the projected normal (as Intel's XeGTAO). Writes r: visibility in [0, 1] (1 on an open plane),
// g: the view depth (m) of the pixel it stands for (r is clamped by the blur), for the depth-aware blur and upsample.
// Built twice (render/ao_pass.h): WITH_GEOMETRIC_HORIZON 0 when no drawn material bends its normal.
#include "gbuffer_read.glsl"
#include "stage_interface.glsl"

layout(location = 0) out vec2 outOcclusion;

const int SLICES = 2;
// Three steps a side: the 4x4 pattern's jitter and the blur fill in between (a fourth is a third
// more horizon samples and moved test_render_shadows' crease term only from 0.88 to 0.86).
const int STEPS = 3;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    ivec2 pixel = min(texel * stage.counts.y, ivec2(frame.viewport.xy) - 1);
    float depth = texelFetch(gDepthTex, pixel, 0).r;
    // The background: nothing to occlude. llvmpipe runs both sides of an `if` (and past a
    // `return`) but leaves a loop once no pixel of its block is in it, so the work below is a
    // loop whose count is 0 for the background and where the radius is under a pixel.
    bool background = depth >= 1.0;
    vec3 P = viewPositionAt(pixel);
    // The horizons bound the visible share of the surface's own hemisphere: about the face's
    // normal where a material bends its shading normal (surfaceNormalAt), as XeGTAO takes its
    // normals from the depth; the lighting's geometric horizon and the material's occlusion
    // already take out the part of a bent normal's hemisphere below the face.
    vec3 nWorld = surfaceNormalAt(pixel, background ? -1 : readMaterialId(pixel), P,
                                  octDecodeUnorm16(texelFetch(gNormalTex, pixel, 0).rg));
    vec3 N = normalize(mat3(frame.viewMatrix) * nWorld);
    bool ortho = frame.cameraPosition.w > 0.5;
    vec3 V = ortho ? vec3(0.0, 0.0, 1.0) : normalize(-P);
    float radius = stage.occlusion.y;
    // The radius in full-resolution pixels: the projection's y scale over the depth.
    float pixelsPerMetre = 0.5 * frame.viewport.y * frame.projMatrix[1][1] / (ortho ? 1.0 : -P.z);
    float radiusPixels = radius * pixelsPerMetre;
    // Farther than the radius from the mesh's bounding sphere a point sees nothing but the flat
    // ground: open (the pass is scissored to the mesh's grown bounds, render/ao_pass.h; this
    // trims the rectangle's corners).
    vec3 meshCentre = (frame.viewMatrix * vec4(stage.meshSphere.xyz, 1.0)).xyz;
    bool nearMesh = distance(P, meshCentre) <= stage.meshSphere.w + radius;
    int slices = background || !nearMesh || radiusPixels < 1.0 ? 0 : SLICES;
    radiusPixels = min(radiusPixels, 0.25 * frame.viewport.y);
    // A 4x4 pattern of slice rotations and step offsets, which the blur averages away.
    int cell = (texel.x & 3) + 4 * (texel.y & 3);
    float rotation = (float((cell * 7) & 15) + 0.5) / 16.0 * PI / float(SLICES);
    float jitter = float((cell * 11 + 5) & 15) / 16.0;
    float falloffFrom = 0.6 * radius;
    float visibility = 0.0;
    for (int slice = 0; slice < slices; ++slice) {
        float phi = rotation + float(slice) * PI / float(SLICES);
        vec2 omega = vec2(cos(phi), sin(phi));
        vec3 direction = vec3(omega, 0.0);
        vec3 orthoDirection = direction - dot(direction, V) * V;
        vec3 axis = normalize(cross(orthoDirection, V));
        vec3 projectedNormal = N - axis * dot(N, axis);
        float projectedLength = length(projectedNormal);
        if (projectedLength < 1e-4)
            continue;
        float signN = sign(dot(orthoDirection, projectedNormal));
        float cosN = saturate(dot(projectedNormal, V) / projectedLength);
        float angleN = signN * acos(cosN);
        float horizon0 = cos(angleN + 0.5 * PI), horizon1 = cos(angleN - 0.5 * PI);
        float low0 = horizon0, low1 = horizon1;
        for (int k = 0; k < STEPS; ++k) {
            float t = (float(k) + jitter) / float(STEPS);
            vec2 offset = omega * max(t * t * radiusPixels, 1.0 + float(k));
            for (int side = 0; side < 2; ++side) {
                ivec2 q = pixel + ivec2(round(side == 0 ? offset : -offset));
                if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(frame.viewport.xy))))
                    continue;
                vec3 delta = viewPositionAt(q) - P;
                float dist = length(delta);
                float c = dot(delta / max(dist, 1e-6), V);
                // Samples beyond the radius fade back to the open horizon (XeGTAO's falloff).
                float weight = saturate((radius - dist) / (radius - falloffFrom));
                if (side == 0)
                    horizon0 = max(horizon0, mix(low0, c, weight));
                else
                    horizon1 = max(horizon1, mix(low1, c, weight));
            }
        }
        float h0 = -acos(clamp(horizon1, -1.0, 1.0));
        float h1 = acos(clamp(horizon0, -1.0, 1.0));
        h0 = angleN + max(h0 - angleN, -0.5 * PI);
        h1 = angleN + min(h1 - angleN, 0.5 * PI);
        float sinN = sin(angleN);
        float arc0 = (cosN + 2.0 * h0 * sinN - cos(2.0 * h0 - angleN)) * 0.25;
        float arc1 = (cosN + 2.0 * h1 * sinN - cos(2.0 * h1 - angleN)) * 0.25;
        visibility += projectedLength * (arc0 + arc1);
    }
    // Not clamped to 1 yet: one pixel's two slices over- or under-estimate a tilted plane, and
    // only the blur's average over the 4x4 rotations comes back to 1 (ao_blur.frag clamps).
    if (background)
        outOcclusion = vec2(1.0, 1e6);
    else if (slices == 0)
        outOcclusion = vec2(1.0, -P.z);
    else
        outOcclusion = vec2(clamp(visibility / float(SLICES), 0.0, 2.0), -P.z);
}
