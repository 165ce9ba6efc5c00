// The mesh's visibility from itself (render/mesh_visibility.h: per vertex a bent normal and the
// open share of the hemisphere, ray traced once per mesh) turned into the occlusion of
// image-based light's reflections.
#include "common_math.glsl"

// Oat & Sander 2007, "Ambient Aperture Lighting" (section 3.2): the solid angle shared by two
// spherical caps of apertures acos(cosA1), acos(cosA2) whose axes are acos(cosD) apart, over
// 2 pi; one cap inside the other gives the smaller cap, a partial overlap their smoothstep
// approximation.
float sphericalCapsIntersection(float cosA1, float cosA2, float cosD) {
    float r1 = acos(clamp(cosA1, -1.0, 1.0));
    float r2 = acos(clamp(cosA2, -1.0, 1.0));
    float d = acos(clamp(cosD, -1.0, 1.0));
    if (min(r1, r2) <= max(r1, r2) - d)
        return 1.0 - max(cosA1, cosA2);
    if (r1 + r2 <= d)
        return 0.0;
    float delta = abs(r1 - r2);
    float x = 1.0 - saturate((d - delta) / max(r1 + r2 - delta, 1e-4));
    return (1.0 - max(cosA1, cosA2)) * x * x * (3.0 - 2.0 * x);
}

// Jimenez et al. 2016 (section 6), with the cone of the open directions: about the bent normal,
// its solid angle the open share of the hemisphere's (cos of its aperture 1 - open share), the
// specular lobe as a cone about the reflection direction r (its aperture where GGX of width
// alpha falls to a tenth: cos = 2^(-log2(10) alpha^2)). The specular occlusion is the share of
// the lobe's cone above the horizon of n (a cap of 90 degrees about it) that the open cone
// covers: the part of a wide or grazing lobe below the horizon is not occlusion (the split sum
// already leaves it out), so a vertex that sees its whole sky (the open cone the hemisphere
// about n) occludes no lobe at all.
float specularVisibility(vec4 visibility, vec3 n, vec3 r, float alpha) {
    if (dot(visibility.xyz, visibility.xyz) < 1e-6) // no visibility: all open
        return 1.0;
    float cosOpen = 1.0 - saturate(visibility.w);
    float cosLobe = min(exp2(-3.321928 * alpha * alpha), 0.9999);
    float open = sphericalCapsIntersection(cosOpen, cosLobe, dot(normalize(visibility.xyz), r));
    float aboveHorizon = sphericalCapsIntersection(0.0, cosLobe, dot(n, r));
    return saturate(open / max(aboveHorizon, 1e-6));
}
