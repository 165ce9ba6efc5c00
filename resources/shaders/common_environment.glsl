// The environment: equirectangular radiance (mip-mapped) and its SH9 irradiance; the baked IBL
// (render/ibl_bake.h): the GGX-prefiltered specular cube and the DFG LUT, with the approximate
// path while a bake is incomplete; the background modes, the procedural FBM one included.
#include "common_math.glsl"
#include "common_frame.glsl"
#include "common_brdf.glsl"
#include "common_hash.glsl"

layout(binding = BINDING_ENVIRONMENT_TEX) uniform sampler2D uEnvironment;
layout(binding = BINDING_IBL_SPECULAR_TEX) uniform samplerCube uSpecularCube;
layout(binding = BINDING_IBL_DFG_TEX) uniform sampler2D uDfgLut;

// IblBlock (instance `ibl`) is generated into render_interface.glsl (common_frame.glsl).

// Direction of equirect coordinates (u, v), v = 0 at +Y, u = 0.5 looking down -Z.
// Must match velvet::equirectDirection() in core/spherical_harmonics.cpp.
vec3 equirectDirection(vec2 uv) {
    float phi = (uv.x - 0.5) * 2.0 * PI;
    float theta = uv.y * PI;
    return vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
}
vec2 equirectUv(vec3 d) {
    return vec2(0.5 + atan(d.x, -d.z) / (2.0 * PI), acos(clamp(d.y, -1.0, 1.0)) / PI);
}

// World direction -> environment direction (the environment is rotated about +Y).
vec3 toEnvironment(vec3 d) {
    float c = frame.envParams.x, s = frame.envParams.y;
    return vec3(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
}

// Radiance arriving from world direction d, blurred to mip level lod; intensity applied.
vec3 environmentRadiance(vec3 d, float lod) {
    vec2 uv = equirectUv(toEnvironment(d));
    return textureLod(uEnvironment, uv, lod).rgb * frame.envParams.z + frame.ambientRadiance.rgb;
}

// The irradiance integrated over the environment into a small cube (render/irradiance_map.h):
// the SH9 below rings and smears a studio HDRI's few small lamps (a tenth off beside a lamp).
// WITH_IRRADIANCE_MAP 0 (render/lighting_features.h: no cube yet) reads the SH9.
#ifndef WITH_IRRADIANCE_MAP
#define WITH_IRRADIANCE_MAP 1
#endif
layout(binding = BINDING_IBL_IRRADIANCE_TEX) uniform samplerCube uIrradianceCube;

// Ramamoorthi & Hanrahan 2001, "An Efficient Representation for Irradiance Environment Maps"
// E(n) / pi, so that a uniform radiance L gives L. Mirrors evalIrradianceOverPi() in
// core/spherical_harmonics.cpp; frame.envSh already carries the intensity.
vec3 irradianceOverPi(vec3 nWorld) {
    vec3 n = toEnvironment(nWorld);
#if WITH_IRRADIANCE_MAP
    return textureLod(uIrradianceCube, n, 0.0).rgb * frame.envParams.z +
               frame.ambientRadiance.rgb;
#endif
    vec3 e = frame.envSh[0].rgb * 0.282095;
    e += (2.0 / 3.0) * 0.488603 * (frame.envSh[1].rgb * n.y + frame.envSh[2].rgb * n.z +
                                   frame.envSh[3].rgb * n.x);
    e += 0.25 * (frame.envSh[4].rgb * (1.092548 * n.x * n.y) +
                 frame.envSh[5].rgb * (1.092548 * n.y * n.z) +
                 frame.envSh[6].rgb * (0.315392 * (3.0 * n.z * n.z - 1.0)) +
                 frame.envSh[7].rgb * (1.092548 * n.x * n.z) +
                 frame.envSh[8].rgb * (0.546274 * (n.x * n.x - n.y * n.y)));
    return max(e, vec3(0.0)) + frame.ambientRadiance.rgb;
}

// Mip level of the equirect whose texel footprint roughly matches a GGX lobe of width alpha (the
// approximate path, used only until the prefiltered cube is ready).
float specularLod(float perceptualRoughness) {
    float alpha = perceptualRoughness * perceptualRoughness;
    return clamp(log2(max(alpha * frame.post.z / PI, 1e-6)), 0.0, frame.envParams.w);
}

// Split-sum prefiltered radiance (Karis 2013, "Real Shading in Unreal Engine 4") at reflection
// direction r for a perceptual roughness: the GGX-prefiltered cube, level = r (levels - 1)
// (velvet::ibl::lodOfRoughness); intensity applied.
// FIXED_IBL_BAKED (render/lighting_features.h) compiles the approximate path out once the bake
// is ready, or the baked one out before.
vec3 specularRadiance(vec3 r, float perceptualRoughness) {
#ifdef FIXED_IBL_BAKED
    const bool baked = FIXED_IBL_BAKED == 1;
#else
    bool baked = ibl.state.x > 0.5;
#endif
    if (!baked)
        return environmentRadiance(r, specularLod(perceptualRoughness));
    return textureLod(uSpecularCube, toEnvironment(r), perceptualRoughness * ibl.state.y).rgb *
               frame.envParams.z +
           frame.ambientRadiance.rgb;
}

// The prefiltered radiance along the reflection r of an isotropic GGX lobe seen at n.v: the split
// sum's cube holds the lobe as n = v = r sees it, but away from normal incidence the reflection
// l = reflect(-v, h) moves by 2 cos(theta_v) times a half vector's tilt across the plane of
// incidence and by 2 times its tilt along it (the Jacobian of the reflection, Walter et al. 2007, "Microfacet Models for Refraction
// through Rough Surfaces", eq. 14), so the reflected lobe is only alpha n.v wide across the plane.
// One isotropic lookup cannot be narrow one way and wide the other: it takes the narrow width for
// glossy lobes and fades back to alpha as the lobe widens (weight alpha^2), where a narrow lookup
// would under-blur along the plane. Measured against the reference path tracer (BENCHMARKS.md,
// "The reflected lobe's narrowing at grazing angles"): copper on the sphere under the HDRI 4.55 ->
// 2.66 mean CIEDE2000, rubber unmoved; the same one cube lookup, so it costs the frame nothing
// (a sweep of several lookups along the plane was closer still but +30-55 % of the frame).
vec3 reflectedRadiance(vec3 r, float NdotV, float perceptualRoughness) {
    float alpha = perceptualRoughness * perceptualRoughness;
    float alphaLookup = mix(alpha * NdotV, alpha, alpha * alpha);
    return specularRadiance(r, sqrt(alphaLookup));
}

// (A, B) of the split-sum environment BRDF, E = f0 A + B: the DFG LUT (texel centres at
// (i + 0.5) / N, velvet::ibl::dfgTexelParams), or Karis 2014's fit until the LUT is made.
vec2 environmentDfg(float NdotV, float perceptualRoughness) {
#ifdef FIXED_IBL_BAKED
    const bool baked = FIXED_IBL_BAKED == 1;
#else
    bool baked = ibl.state.z > 0.5;
#endif
    if (!baked)
        return envBrdfApprox(perceptualRoughness, NdotV);
    return textureLod(uDfgLut, vec2(NdotV, perceptualRoughness), 0.0).rg;
}

// The factor by which multiple scattering raises a specular lobe's single-scattering reflection
// (Fdez-Aguera 2019, "A Multiple-Scattering Microfacet Model for Real-Time Image-based Lighting",
// eq. 16: 1 + E_ms F_avg / (1 - E_ms F_avg)), from its Fresnel f0 and (A, B); 1 when disabled.
vec3 multipleScatteringGain(vec3 f0, vec2 dfg) {
    if (!multipleScatteringOn()) // common_brdf.glsl
        return vec3(1.0);
    float ems = 1.0 - (dfg.x + dfg.y);
    vec3 favg = f0 + (1.0 - f0) / 21.0;
    return 1.0 + ems * favg / (1.0 - ems * favg);
}
// Directional albedo of a specular lobe of Fresnel f0 from (A, B), multiple scattering included.
// Mirrors velvet::ibl::specularAlbedo().
vec3 specularAlbedo(vec3 f0, vec2 dfg) {
    return (f0 * dfg.x + dfg.y) * multipleScatteringGain(f0, dfg);
}

// ---- Procedural background (seed 004: Perlin noise made smoky by FBM; in HSV a hue that turns
// with time, a fixed value, the saturation from the noise) ----

// A unit gradient per lattice point from pcg2d (common_hash.glsl): the same bits on every GPU,
// so a fixed time gives a fixed image.
vec2 gradientAt(ivec2 cell) {
    uvec2 h = pcg2d(uvec2(cell + 32768));
    float a = float(h.x & 0xffffu) / 65536.0 * 2.0 * PI;
    return vec2(cos(a), sin(a));
}
// Perlin 2002, "Improving Noise" (gradient noise with the quintic fade), in about [-1, 1].
float perlinNoise(vec2 p) {
    ivec2 i = ivec2(floor(p));
    vec2 f = fract(p);
    vec2 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    float a = dot(gradientAt(i), f);
    float b = dot(gradientAt(i + ivec2(1, 0)), f - vec2(1.0, 0.0));
    float c = dot(gradientAt(i + ivec2(0, 1)), f - vec2(0.0, 1.0));
    float d = dot(gradientAt(i + ivec2(1, 1)), f - vec2(1.0, 1.0));
    return mix(mix(a, b, u.x), mix(c, d, u.x), u.y) * 1.4142;
}
// Fractional Brownian motion: 5 octaves, lacunarity 2, gain 0.5; in [0, 1].
float fbm(vec2 p) {
    float sum = 0.0, amplitude = 0.5;
    for (int o = 0; o < 5; ++o) {
        sum += amplitude * perlinNoise(p);
        p = p * 2.0 + vec2(17.3, 9.1);
        amplitude *= 0.5;
    }
    return saturate(sum / 0.96875 * 0.5 + 0.5);
}
vec3 hsvToRgb(vec3 c) {
    vec3 p = abs(fract(c.xxx + vec3(0.0, 2.0, 1.0) / 3.0) * 6.0 - 3.0);
    return c.z * mix(vec3(1.0), clamp(p - 1.0, 0.0, 1.0), c.y);
}
// The background at screen position uv (height-normalised) and time t (seconds): display-referred
// colour decoded to scene-linear, so the tone mapper gives it back about as the seed showed it.
vec3 proceduralBackground(vec2 uv, float t) {
    float n = fbm(uv * 3.0 + vec2(0.05, 0.03) * t);
    float hue = fract(t * 0.02);
    return srgbDecode(hsvToRgb(vec3(hue, n, 0.55)));
}

// The background along world direction dir at screen position uv, for BackgroundMode (scene.h):
// Sharp the environment itself, Blurred a prefiltered level, SolidColor the colour exactly,
// ProceduralFbm the seed's noise.
// With BACKGROUND_MODE defined (lighting.frag's background variants) only that mode is compiled
// in, llvmpipe running every branch otherwise; the Blurred variant is used only once the cube is
// ready.
vec3 backgroundRadiance(vec3 dir, vec2 uv) {
#ifdef BACKGROUND_MODE
    const int mode = BACKGROUND_MODE;
    const bool cubeReady = BACKGROUND_MODE == 1;
#else
    int mode = frame.modes.w;
    bool cubeReady = ibl.state.x > 0.5;
#endif
    if (mode == 2)
        return frame.backgroundColor.rgb;
    if (mode == 3)
        return proceduralBackground(uv, ibl.background.y);
    if (mode == 1 && cubeReady)
        return textureLod(uSpecularCube, toEnvironment(dir), ibl.background.x).rgb *
                   frame.envParams.z +
               frame.ambientRadiance.rgb;
    return environmentRadiance(dir, frame.backgroundColor.w);
}

// The environment light an anisotropic base (KHR_materials_anisotropy) reflects, estimated along
// its stretch. In slope space the anisotropic GGX is the isotropic one stretched: its slopes along
// the stretch direction t follow GGX's marginal slope distribution of width alpha_t (Heitz 2014,
// "Understanding the Masking-Shadowing Function", P22 integrated over the other axis: a Student t
// of two degrees of freedom), whose inverse CDF is closed, x = alpha s / sqrt(1 - s^2) with
// s = 2u - 1. The sweep takes stratified u (every pixel the same smooth sweep, no noise) for the
// residual width alpha_r = sqrt(alpha_t^2 - alpha_b^2) and reads each half vector's reflection from
// the cube's level for the narrow width alpha_b (narrowed at grazing angles as reflectedRadiance
// narrows it), which stands for the slopes across t; a sample far from its neighbours reads a
// blurrier level (filtered importance sampling, Colbert & Krivanek 2007).
// Each sample is weighted as a microfacet estimator weights a half vector drawn from D (n.h):
// f n.l / pdf = F V 4 (n.l) (v.h) / (n.h), with the anisotropic Smith V, so the masking of the
// stretched lobe at grazing angles is its own (not the isotropic DFG's) and the sweep carries its
// energy itself. The Fresnel is Schlick's, kept as two moments so that the caller mixes the
// dielectric's and the metal's (sweptSpecular): radiance = sum w L, grazing = sum w L (1 - v.h)^5.
// Against the reference path tracer (BENCHMARKS.md, "Anisotropy under image-based light, weighted
// per sample"): brushed aluminium on the sphere under the HDRI, 128x128, mean CIEDE2000 9.4 with
// n.l weights normalised and the isotropic DFG (before), 4.35 with these weights; a brute-force
// 24x24 sampling of the whole lobe reads 3.7.
// As many samples as the sweep is wide against the narrow width (6 alpha_r / alpha_b, 4 to
// ANISOTROPY_IBL_SAMPLES: brushed aluminium 33, satin 28): 4 per width showed the studio lamp as
// a row of dots along the streak, 8 cost twice 4's lookups for 0.2 less mean error. Each is a
// cube lookup (`WITH_ANISOTROPY` compiles the sweep out of every other material's program).
#ifndef ANISOTROPY_IBL_SAMPLES
#define ANISOTROPY_IBL_SAMPLES 48
#endif
struct SweptReflection {
    vec3 radiance; // the lobe's reflected light for F = 1 (single scattering)
    vec3 grazing;  // the part of it that Schlick's Fresnel takes to f90: weighted by (1 - v.h)^5
};
SweptReflection anisotropicReflection(Surface s, vec3 n, vec3 v, float NdotV,
                                      float perceptualRoughness) {
    vec2 a = anisotropicAlphas(perceptualRoughness, s.anisotropyStrength); // (alpha_t, alpha_b)
    float alphaSweep = sqrt(max(a.x * a.x - a.y * a.y, 0.0));
    vec3 t = s.anisotropyDirection;
    vec3 b = cross(n, t);
    float TdotV = dot(t, v), BdotV = dot(b, v);
    float alphaNarrow = mix(a.y * NdotV, a.y, a.y * a.y); // reflectedRadiance's narrowing
    float count = clamp(ceil(6.0 * alphaSweep / a.y), 4.0, float(ANISOTROPY_IBL_SAMPLES));
    SweptReflection sum = SweptReflection(vec3(0.0), vec3(0.0));
    for (int i = 0; i < int(count); ++i) {
        float u = 2.0 * (float(i) + 0.5) / count - 1.0; // s in (-1, 1)
        float rest = 1.0 - u * u;
        float slope = alphaSweep * u * inversesqrt(rest);
        // The slope's distance to the next sample, dx/du / count: the blur that closes the gap.
        float gap = 2.0 * alphaSweep / (count * rest * sqrt(rest));
        vec3 h = normalize(n - slope * t);
        vec3 l = reflect(-v, h);
        float NdotL = dot(n, l);
        if (NdotL <= 0.0)
            continue;
        float VdotH = max(dot(v, h), 1e-4), NdotH = max(dot(n, h), 1e-4);
        float vis = visibilitySmithGGXCorrelatedAnisotropic(NdotL, NdotV, TdotV, BdotV, dot(t, l),
                                                            dot(b, l), a.x, a.y);
        float alphaLookup = max(alphaNarrow, 0.5 * gap);
        vec3 light = specularRadiance(l, sqrt(min(alphaLookup, 1.0))) *
                     (vis * 4.0 * NdotL * VdotH / NdotH);
        float c = 1.0 - VdotH, c2 = c * c;
        sum.radiance += light;
        sum.grazing += light * (c2 * c2 * c);
    }
    sum.radiance /= count;
    sum.grazing /= count;
    return sum;
}
// The swept reflection through Schlick's Fresnel from f0 to 1, with the multiple-scattering
// energy specularAlbedo gives the split sum (Fdez-Aguera 2019; @p dfg at the base roughness), so
// that an anisotropic base keeps the energy an isotropic one of its roughness has.
vec3 sweptSpecular(SweptReflection sw, vec3 f0, vec2 dfg) {
    return (f0 * (sw.radiance - sw.grazing) + sw.grazing) * multipleScatteringGain(f0, dfg);
}

// ---- The reflected environment light sampled (the viewport at rest and supersampled stills) ----
// The split sum's one lookup (reflectedRadiance) assumes n = v = r; at grazing angles the true lobe
// is narrow across the plane of incidence and shifted, which no single isotropic lookup can hold:
// glossy metals missed the reference path tracer by twice issue 15's goal, and a brute-force
// integral met it (BENCHMARKS.md, "What keeps the glossy metals from the goal"). Frames with time
// to spare (FrameSettings::reflectionSamples) estimate the integral instead: GGX half vectors
// drawn from the distribution of visible normals, each reflection read from the equirect's mip
// chain at its sample's footprint (filtered importance sampling), the frames of a progressive mean
// or the samples of a supersampled pixel each drawing the next block of one stratified sequence.

// Heitz 2018, "Sampling the GGX Distribution of Visible Normals" (JCGT 7(4)), listing 1, split
// in two: the view's hemisphere configuration (vh and the frame about it), the same for every
// sample of a pixel, then a half vector with density G1(v) max(0, v.h) D(h) / n.v for uniform
// numbers u, in the lobe's frame (x along the width alpha.x, y along alpha.y, z = n).
struct VisibleNormals {
    vec3 vh, t1, t2;
    vec2 alpha;
};
VisibleNormals visibleNormalsOf(vec3 vt, vec2 alpha) {
    vec3 vh = normalize(vec3(alpha * vt.xy, vt.z));
    float lensq = dot(vh.xy, vh.xy);
    vec3 t1 = lensq > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0);
    return VisibleNormals(vh, t1, cross(vh, t1), alpha);
}
vec3 sampleGgxVisibleNormal(VisibleNormals g, vec2 u) {
    float r = sqrt(u.x), phi = 2.0 * PI * u.y;
    float p1 = r * cos(phi), p2 = r * sin(phi);
    float blend = 0.5 * (1.0 + g.vh.z);
    p2 = (1.0 - blend) * sqrt(max(1.0 - p1 * p1, 0.0)) + blend * p2;
    vec3 nh = p1 * g.t1 + p2 * g.t2 + sqrt(max(1.0 - p1 * p1 - p2 * p2, 0.0)) * g.vh;
    return normalize(vec3(g.alpha * nh.xy, max(nh.z, 0.0)));
}

// Smith's Lambda for the (anisotropic) GGX (Heitz 2014, eq. 72 and section 5.3) of the
// direction w in the lobe's frame.
float smithLambdaGgx(vec3 w, vec2 alpha) {
    float z2 = max(w.z * w.z, 1e-8);
    return 0.5 * (sqrt(1.0 + (alpha.x * alpha.x * w.x * w.x + alpha.y * alpha.y * w.y * w.y) / z2) -
                  1.0);
}

// The samples this frame draws per pixel (0: the split sum). WITH_SAMPLED_REFLECTIONS 0
// (render/lighting_features.h) compiles the sampling out of the frames that draw none.
#ifndef WITH_SAMPLED_REFLECTIONS
#define WITH_SAMPLED_REFLECTIONS 1
#endif
// Rougher lobes keep the split sum: their shape hardly narrows at grazing angles, and the cube's
// GGX prefilter is exact where the equirect's box-filtered mips, which a wide lobe's samples read
// at high levels, blur unevenly towards the poles (crimson velvet, roughness 0.8: mean ΔE2000
// 1.38 with the split sum, 1.45 sampled; BENCHMARKS.md, "Reflections sampled at rest"). A pixel
// past it runs none of the loop, so a rough material's refinement costs what it did
// (SAMPLED_REFLECTION_MAX_ROUGHNESS, render::kSampledReflectionMaxRoughness, generated into
// render_interface.glsl; a frame whose materials are all rougher compiles the sampling out).
int reflectionSamplesThisFrame() { return WITH_SAMPLED_REFLECTIONS != 0 ? int(ibl.reflection.x) : 0; }

// The block of samples pixel @p pixel draws within its output pixel's mean (a frame of the
// progressive mean, or one of a still's ss x ss samples of a pixel: consecutive blocks of one
// scrambled sequence, reflectionSample), and that output pixel, whose hash scrambles it.
uint reflectionSampleSetOf(vec2 pixel, out uvec2 outputPixel) {
    uint block = uint(max(ibl.reflection.w, 1.0));
    outputPixel = uvec2(pixel) / block;
    uvec2 sub = uvec2(pixel) % block;
    return uint(ibl.reflection.z) * block * block + sub.y * block + sub.x;
}

// The equirect's mip level for a sample along @p l of density @p pdf, one of @p total in the
// mean: where a texel covers its share 1 / (total pdf) of the sphere (Colbert & Krivanek 2007,
// "GPU-Based Importance Sampling", GPU Gems 3 ch. 20, eq. 13; an equirect texel spans
// (2 pi / W)(pi / H) sin(theta) steradians), half a level blurrier (sampledReflection says why).
float environmentSampleLod(vec3 l, float pdf, float total) {
    float width = frame.post.z;
    float texelSolidAngle = 4.0 * PI * PI / (width * width); // (2 pi / W)(pi / (W / 2))
    float sinTheta = sqrt(max(1.0 - l.y * l.y, 1e-4));      // the equirect's pole is world +Y
    float lod = 0.5 * log2(1.0 / (total * pdf * texelSolidAngle * sinTheta)) + 0.5;
    return clamp(lod, 0.0, frame.envParams.w);
}

// Some unit vector perpendicular to @p n (a frame's tangent where no direction is preferred).
vec3 anyTangent(vec3 n) {
    return normalize(abs(n.y) < 0.999 ? cross(vec3(0.0, 1.0, 0.0), n) : vec3(1.0, 0.0, 0.0));
}

// Point j of the two-dimensional Sobol sequence (van der Corput and Sobol's second dimension,
// Kollig & Keller 2002, "Efficient Multidimensional Sampling", section 3), scrambled by XOR with
// a per-pixel word (a random digit scramble, which keeps the nets). Every aligned block of 2^m
// points is a (0, m, 2)-net, so each frame's block is stratified on its own and the mean's
// blocks together form one finer net: the mean converges as one large stratified set, where
// blocks of independently rotated points converge only as fast as their count.
vec2 reflectionSample(uint j, uvec2 scramble) {
    uint y = 0u;
    for (uint v = 1u << 31u, k = j; k != 0u; k >>= 1u, v ^= v >> 1u)
        if ((k & 1u) != 0u)
            y ^= v;
    return vec2(bitfieldReverse(j) ^ scramble.x, y ^ scramble.y) * 2.3283064365386963e-10;
}

// The GGX lobe's reflected environment light by ibl.reflection.x samples per pixel, in the frame
// (t, n x t, n) whose widths are alpha (equal for an isotropic lobe; alpha_t, alpha_b for a
// KHR_materials_anisotropy one, which the sweep, anisotropicReflection, draws otherwise).
// With visible normals the estimator f n.l / pdf is F G2(v, l) / G1(v), G2 from the material's
// chosen visibility term (glTF's separable Smith by default, as the reference's BRDF and the
// split sum's DFG table have it), kept as the two Schlick moments of SweptReflection so the
// caller mixes the dielectric's and the metal's Fresnel and adds the split sum's
// multiple-scattering energy (sweptSpecular). Each sample reads the mip
// level where a texel covers its share 1 / (N pdf) of the sphere, N the samples of the whole
// mean (Colbert & Krivanek 2007, "GPU-Based Importance Sampling", GPU Gems 3 ch. 20, eq. 13;
// an equirect texel spans (2 pi / W)(pi / H) sin(theta) steradians), half a level blurrier: their
// +1 blurred copper's highlights more than the stratified samples need, +0 let the lamp's noise
// through (48x48 table: copper under the HDRI 1.50 / 1.24 / 1.28 mean ΔE2000 at +1 / +0.5 / +0).
// A sample below the face's plane (@p ng; n where nothing bends the normal) brings no light, as
// in the path tracer: exact where the split sum fades its one reflection by the horizon.
SweptReflection sampledReflection(vec3 n, vec3 ng, vec3 t, vec3 v, float NdotV, vec2 alpha,
                                  int visibilityTerm, vec2 pixel) {
    int count = reflectionSamplesThisFrame();
    float total = max(ibl.reflection.y, float(count));
    vec3 b = cross(n, t);
    vec3 vt = vec3(dot(v, t), dot(v, b), NdotV);
    uvec2 outputPixel;
    uint set = reflectionSampleSetOf(pixel, outputPixel);
    uvec2 scramble = pcg2d(outputPixel);
    float lambdaV = smithLambdaGgx(vt, alpha);
    VisibleNormals visible = visibleNormalsOf(vt, alpha);
    SweptReflection sum = SweptReflection(vec3(0.0), vec3(0.0));
    for (int i = 0; i < count; ++i) {
        vec2 u = reflectionSample(set * uint(count) + uint(i), scramble);
        vec3 ht = sampleGgxVisibleNormal(visible, u);
        vec3 h = t * ht.x + b * ht.y + n * ht.z;
        vec3 l = reflect(-v, h);
        float NdotL = dot(n, l);
        if (NdotL <= 0.0 || dot(ng, l) <= 0.0)
            continue;
        float VdotH = max(dot(v, h), 1e-4);
        float D = distributionGGXAnisotropic(ht.z, ht.x, ht.y, alpha.x, alpha.y); // GGX when equal
        float pdf = D / (4.0 * NdotV * (1.0 + lambdaV)); // G1(v) D / (4 n.v)
        // G2 / G1(v) = V 4 (n.l)(n.v) (1 + Lambda(v)): V the material's chosen visibility, or for
        // a stretched lobe the anisotropic Smith term (the extension's, as direct light has it).
        float V = alpha.x != alpha.y
                      ? visibilitySmithGGXCorrelatedAnisotropic(NdotL, NdotV, vt.x, vt.y, dot(t, l),
                                                                dot(b, l), alpha.x, alpha.y)
                      : visibility(visibilityTerm, NdotL, NdotV, ht.z, VdotH, alpha.x);
        float masking = V * 4.0 * NdotL * NdotV * (1.0 + lambdaV);
        vec3 light = environmentRadiance(l, environmentSampleLod(l, pdf, total)) * masking;
        float c = 1.0 - VdotH, c2 = c * c;
        sum.radiance += light;
        sum.grazing += light * (c2 * c2 * c);
    }
    sum.radiance /= float(max(count, 1));
    sum.grazing /= float(max(count, 1));
    return sum;
}

// The sheen lobe's reflected environment light at rest, by ibl.reflection.x samples per pixel
// (the frames of sampledReflection; lighting.frag): directions drawn uniformly over the
// hemisphere about the shading normal, each weighted by f n.l / pdf = 2 pi D V n.l (the Charlie
// distribution and the material's sheen visibility, Estevez & Kulla 2017): the lobe's light for
// a white sheen, in place of the sheen's albedo times the irradiance about the lobe's mean
// direction (sheenLightDirection). That one
// direction misplaces the lobe where the light is not smooth about it: satin and crushed velvet
// under the studio HDRI's lamp read half the mean ΔE2000 against the path tracer sampled
// (BENCHMARKS.md, "The table as the editor shows it at rest; the sheen sampled at rest").
// Uniform rather than cosine directions, as the lobe peaks towards grazing light: under the
// lamp of test_render_sampled_reflections 2.1 % off the lobe's integral against 4.9 %, and a
// velvet's rim visibly less grainy in a 2 x 2 supersampled still. A sample below the face's
// plane (@p ng) brings no light, as in the path tracer, which also clips the lobe by a bent
// normal's horizon. Each sample reads the mip where a texel covers its share of the sphere, as
// sampledReflection's (a level blurrier brought wool on the sphere under the HDRI from 2.27 to
// 1.87 mean ΔE2000 but read that lamp 13 % off the lobe's integral, with cosine directions).
vec3 sampledSheenLight(vec3 n, vec3 ng, vec3 v, float NdotV, float sheenRoughness, int model,
                       vec2 pixel) {
    int count = reflectionSamplesThisFrame();
    float total = max(ibl.reflection.y, float(count));
    uvec2 outputPixel; // scrambled apart from the base lobe's samples
    uint set = reflectionSampleSetOf(pixel, outputPixel);
    uvec2 scramble = pcg2d(outputPixel ^ uvec2(0x27D4EB2Du, 0x165667B1u));
    vec3 t = anyTangent(n);
    vec3 b = cross(n, t);
    const float pdf = 1.0 / (2.0 * PI); // uniform over the hemisphere
    vec3 sum = vec3(0.0);
    for (int i = 0; i < count; ++i) {
        vec2 u = reflectionSample(set * uint(count) + uint(i), scramble);
        float z = u.x, r = sqrt(max(1.0 - z * z, 0.0)), phi = 2.0 * PI * u.y;
        vec3 l = t * (r * cos(phi)) + b * (r * sin(phi)) + n * z;
        float NdotL = dot(n, l);
        if (NdotL <= 1e-4 || dot(ng, l) <= 0.0)
            continue;
        float NdotH = dot(n, normalize(l + v));
        float D = distributionCharlie(NdotH, max(1.0 - NdotH * NdotH, 0.0), sheenRoughness);
        float V = visibilitySheen(model, NdotL, NdotV, sheenRoughness);
        sum += NdotL * D * V / pdf * environmentRadiance(l, environmentSampleLod(l, pdf, total));
    }
    return sum / float(max(count, 1));
}

// The isotropic lobe's frame: x along the plane of incidence (any azimuth would do).
vec3 incidencePlaneTangent(vec3 n, vec3 v, float NdotV) {
    vec3 across = v - n * NdotV;
    float len = length(across);
    return len > 1e-4 ? across / len : anyTangent(n);
}

// Where image-based light's sheen looks the environment up (lighting.frag). The Charlie lobe
// (Estevez & Kulla 2017) with the Neubelt-Pettineo visibility is not centred on the reflection
// direction: its n.l-weighted mean direction lies on the viewer's side of n, tilted towards v by
// an angle that depends on the sheen roughness and hardly on n.v (numerical moments over
// n.v in [0.05, 0.97]: about 70 degrees at roughness 0.2, 55 at 0.3, 33 at 0.5, 17 at 0.8, 12
// at 1; fitted by 100 exp(-2.1 roughness) degrees), and it is as broad as a cosine lobe (mean
// resultant length 0.53-0.70 against the cosine's 2/3). So its light is the irradiance (the
// radiance convolved with a cosine lobe: the SH9 of irradianceOverPi) about that tilt, the same
// before and after the bake. At normal incidence the lobe is a ring about n and the tilt fades
// to n. Measured against the reference path tracer in BENCHMARKS.md ("Sheen and
// anisotropy under image-based light").
vec3 sheenLightDirection(vec3 n, vec3 v, float NdotV, float sheenRoughness) {
    vec3 across = v - n * NdotV;
    float len = length(across);
    if (len < 1e-4)
        return n;
    float tilt = min(1.745 * exp(-2.1 * sheenRoughness), 1.48) * smoothstep(0.0, 0.25, len);
    return n * cos(tilt) + across / len * sin(tilt);
}
