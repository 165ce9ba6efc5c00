// The mesh's light traced in screen space (docs/architecture.md, "Reflections of the mesh in
// itself"): where a glossy lobe's reflection meets the mesh itself (the shader ball's cap over its ring, the ring
// over its pedestal), the light it brings is the mesh's own, not the environment's that the mesh
// hides. The mesh's visibility (mesh_visibility.glsl) can only darken such a reflection; the path
// tracer shows the lit copper the ray meets. A frame at rest (FrameSettings::reflectionSamples)
// draws the surfaces twice: the first pass's lit image is the source this one reads back where
// a few rays a pixel, GGX visible-normal samples of the lobe, meet the depth buffer (a linear
// march in screen space with perspective-correct depth, as McGuire & Mara 2014, "Efficient GPU
// Screen-Space Ray Tracing", JCGT 3(4), then a bisection of the step that crossed the surface).
// The pixels of a progressive mean (or a supersampled still's samples) each trace another ray of
// one stratified set, so the mean holds the share of the lobe that meets the mesh. The diffuse
// light is gathered the same way (screenSpaceGather): a lit part of the mesh lights the parts
// that face it, which no occlusion can give back.
// Needs gbuffer_read.glsl, common_environment.glsl (reflectionSample, the visible normals) and
// stage_shading.glsl (the stage block: the mesh's bounding sphere).

// WITH_SCREEN_SPACE_REFLECTIONS 1 (render/lighting_features.h): the second surfaces pass.
#ifndef WITH_SCREEN_SPACE_REFLECTIONS
#define WITH_SCREEN_SPACE_REFLECTIONS 0

#endif

#if WITH_SCREEN_SPACE_REFLECTIONS
// The first surfaces pass's linear image (render/renderer_impl.cpp, drawLitPasses).
layout(binding = BINDING_HDR_TEX) uniform sampler2D uReflectionSource;

// Steps of the march over the ray's reach (the mesh's diameter, clipped to the frame), and
// bisections of the step that crossed a surface. 40 and 4 added about half as much again to a
// turntable of the copper ball on its stage as 24 and 3, for the shader ball's metals within 0.15
// mean ΔE2000 of them (velvet compare --table).
const int SSR_STEPS = 24;
const int SSR_REFINEMENTS = 3;
// The diffuse rays' steps: a wide lobe's light is a mean over many rays, each hit's place
// matters less than a mirror's.
const int SSR_GATHER_STEPS = 12;

// The view-space z (negative in front) of full-resolution pixel @p q, from its hardware depth
// through the projection's z row alone (a jitter moves x and y only): clip z = P22 z + P32 over
// clip w = -z (perspective) or 1 (orthographic). One division, where viewPositionAt multiplies
// by the whole inverse: the march asks for it at every step.
float ssrSceneZ(ivec2 q) {
    float ndcZ = texelFetch(gDepthTex, clamp(q, ivec2(0), ivec2(frame.viewport.xy) - 1), 0).r * 2.0 - 1.0;
    float p22 = frame.projMatrix[2][2], p32 = frame.projMatrix[3][2];
    return frame.cameraPosition.w > 0.5 ? (ndcZ - p32) / p22 : -p32 / (ndcZ + p22);
}

// The ray from view-space @p origin along view-space direction @p dir: the pixel it first passes
// behind the depth buffer, within a thickness that grows with the step's own depth span (a ray
// passing behind a thin part does not stop there), or (-1, -1). @p jitter in [0, 1) offsets the
// steps per pixel, so neighbours sample between each other's.
ivec2 ssrMarch(vec3 origin, vec3 dir, float reach, float jitter, int steps) {
    vec3 end = origin + dir * reach;
    // Keep the end in front of the camera (a ray towards it leaves the frustum there).
    if (frame.cameraPosition.w < 0.5 && end.z > -0.01) {
        float t = (origin.z + 0.01) / max(origin.z - end.z, 1e-6);
        end = origin + (end - origin) * clamp(t, 0.0, 1.0);
    }
    vec4 h0 = frame.projMatrix * vec4(origin, 1.0), h1 = frame.projMatrix * vec4(end, 1.0);
    float k0 = 1.0 / h0.w, k1 = 1.0 / h1.w;
    vec2 size = frame.viewport.xy;
    vec2 s0 = (h0.xy * k0 * 0.5 + 0.5) * size, s1 = (h1.xy * k1 * 0.5 + 0.5) * size;
    // Clip the screen segment to the frame: the share tMax of it inside.
    vec2 d = s1 - s0;
    float tMax = 1.0;
    for (int a = 0; a < 2; ++a) {
        if (d[a] > 1e-6)
            tMax = min(tMax, (size[a] - 0.5 - s0[a]) / d[a]);
        else if (d[a] < -1e-6)
            tMax = min(tMax, (0.5 - s0[a]) / d[a]);
    }
    if (tMax <= 0.0 || dot(d, d) * tMax * tMax < 4.0) // leaves at once, or within two pixels
        return ivec2(-1);
    // Perspective-correct: q = p / w and k = 1 / w vary linearly across the screen.
    vec3 q0 = origin * k0, q1 = end * k1;
    float stepZ = abs(q1.z / k1 - q0.z / k0) / float(steps);
    float thickness = max(2.0 * stepZ, 0.02 * reach);
    float before = 0.0;
    for (int i = 1; i <= steps; ++i) {
        float t = tMax * (float(i) - jitter) / float(steps);
        ivec2 px = ivec2(mix(s0, s1, t));
        float rayZ = mix(q0.z, q1.z, t) / mix(k0, k1, t);
        float behind = ssrSceneZ(px) - rayZ; // > 0: the ray is farther than the surface
        if (behind > 0.0) {
            if (behind > thickness) // behind a near part: the ray may come out again
                return ivec2(-1);
            // Bisect between the last step in front and this one.
            float lo = before, hi = t;
            for (int b = 0; b < SSR_REFINEMENTS; ++b) {
                float m = 0.5 * (lo + hi);
                float z = mix(q0.z, q1.z, m) / mix(k0, k1, m);
                if (ssrSceneZ(ivec2(mix(s0, s1, m))) - z > 0.0)
                    hi = m;
                else
                    lo = m;
            }
            return ivec2(mix(s0, s1, hi));
        }
        before = t;
    }
    return ivec2(-1);
}

// Rays a pixel traces of each kind: SSR_RAYS_PER_OUTPUT_PIXEL over the samples its output
// pixel's mean holds (ibl.reflection.y / .x: 16 for the viewport's refinement and the table's
// 4 x 4, 4 for a still supersampled 2 x 2, whose one ray a sample left the reflections grainy).
const int SSR_RAYS_PER_OUTPUT_PIXEL = 16;
int screenSpaceReflectionRays() {
    float samplesInMean = max(ibl.reflection.y / max(ibl.reflection.x, 1.0), 1.0);
    return clamp(int(float(SSR_RAYS_PER_OUTPUT_PIXEL) / samplesInMean + 0.5), 1,
                 SSR_RAYS_PER_OUTPUT_PIXEL);
}

// Ray @p ray of pixel @p pixel's screenSpaceReflectionRays() of one kind: its index in the
// output pixel's stratified set (x), and the set's per-pixel scramble for the kind (yz), so the
// reflection's and the diffuse light's rays are not the lobe samples of sampledReflection.
uvec3 ssrRayIndex(ivec2 pixel, int ray, uvec2 kind) {
    uvec2 outputPixel;
    uint set = reflectionSampleSetOf(vec2(pixel), outputPixel);
    return uvec3(set * uint(screenSpaceReflectionRays()) + uint(ray), pcg2d(outputPixel ^ kind));
}

// The light the ray from @p p along world direction @p l brings from the mesh itself: rgb the
// first pass's radiance where it meets the surface, a 1 there; a 0 where it leaves the frame,
// meets nothing, meets a surface from behind or the shadow catcher (which stands for the
// background, not for an object in it). @p index: ssrRayIndex's x (the march's jitter).
vec4 ssrTrace(ShadingPoint p, vec3 l, ivec2 pixel, uint index, int steps) {
    if (dot(p.n, l) <= 0.0 || dot(p.ng, l) <= 0.0)
        return vec4(0.0);
    vec3 dirView = normalize(mat3(frame.viewMatrix) * l);
    vec3 nView = normalize(mat3(frame.viewMatrix) * p.ng);
    // Off the surface by a little of its depth, so the march does not meet its own pixel.
    vec3 origin = p.posView + nView * (0.002 * -p.posView.z);
    float jitter = float(pcg2d(uvec2(pixel) + uvec2(index * 7919u, index)).x) * 2.3283064365386963e-10;
    ivec2 hit = ssrMarch(origin, dirView, 2.0 * stage.meshSphere.w, jitter, steps);
    if (hit.x < 0 || hit == pixel)
        return vec4(0.0);
    if (readMaterialId(hit) == GROUND_CATCHER_MATERIAL_ID)
        return vec4(0.0);
    // Met from behind (the ray slipped under a silhouette): no light of the surface's face.
    if (dot(octDecodeUnorm16(texelFetch(gNormalTex, hit, 0).rg), l) > 0.0)
        return vec4(0.0);
    return vec4(texelFetch(uReflectionSource, hit, 0).rgb, 1.0);
}

// Ray @p ray of screenSpaceReflectionRays(): a GGX visible-normal sample of the base lobe (alpha
// along t and n x t), as ssrTrace.
vec4 screenSpaceReflection(ShadingPoint p, vec3 t, vec2 alpha, float NdotV, ivec2 pixel, int ray) {
    uvec3 index = ssrRayIndex(pixel, ray, uvec2(0x9E3779B9u, 0x85EBCA6Bu));
    vec2 u = reflectionSample(index.x, index.yz);
    vec3 b = cross(p.n, t);
    vec3 ht = sampleGgxVisibleNormal(visibleNormalsOf(vec3(dot(p.v, t), dot(p.v, b), NdotV), alpha), u);
    vec3 l = reflect(-p.v, t * ht.x + b * ht.y + p.n * ht.z);
    return ssrTrace(p, l, pixel, index.x, SSR_STEPS);
}

// The mean of @p rays of screenSpaceReflection's rays of a lobe (alpha along t and n x t about
// p.n): @p albedo times the mesh's light where a ray meets it, @p missed where it does not (the
// lobe's environment light, occluded). @p rays 0: a loop run no times, which llvmpipe skips for
// a whole block; the caller keeps its own estimate then.
vec3 tracedReflection(ShadingPoint p, vec3 t, vec2 alpha, float NdotV, ivec2 pixel, int rays,
                      vec3 albedo, vec3 missed) {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < rays; ++i) {
        vec4 hit = screenSpaceReflection(p, t, alpha, NdotV, pixel, i);
        sum += hit.a > 0.0 ? albedo * hit.rgb : missed;
    }
    return rays > 0 ? sum / float(rays) : missed;
}

// Ray @p ray of screenSpaceReflectionRays(): a sample of the cosine lobe about the face (the
// diffuse light's directions), as ssrTrace.
vec4 screenSpaceGather(ShadingPoint p, ivec2 pixel, int ray) {
    uvec3 index = ssrRayIndex(pixel, ray, uvec2(0x68E31DA4u, 0xB5297A4Du));
    vec2 u = reflectionSample(index.x, index.yz);
    vec3 n = p.ng;
    vec3 t = anyTangent(n);
    vec3 b = cross(n, t);
    float r = sqrt(u.x), phi = 2.0 * PI * u.y;
    vec3 l = t * (r * cos(phi)) + b * (r * sin(phi)) + n * sqrt(max(1.0 - u.x, 0.0));
    return ssrTrace(p, l, pixel, index.x + 977u, SSR_GATHER_STEPS);
}
#endif
