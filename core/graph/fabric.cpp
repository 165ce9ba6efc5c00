// The C++ twin of the fabric nodes: core/graph/fabric_source.inl compiled as C++ with GLM standing
// in for GLSL's types and built-in functions, so the CPU runs the GPU's statements.
#include "core/graph/fabric.h"

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace velvet::graph::fabric {
namespace twin {

using namespace glm;

// ---- The graph compiler's noise helpers (graph_compiler.cpp, kNoiseGlsl), line for line --------

// pcg2d (resources/shaders/common_hash.glsl): Jarzynski & Olano 2020, "Hash Functions for GPU
// Rendering", JCGT 9(3), 21-38.
uvec2 pcg2d(uvec2 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v = v ^ (v >> 16u);
    v.x += v.y * 1664525u;
    v.y += v.x * 1664525u;
    v = v ^ (v >> 16u);
    return v;
}

vec2 velvetGraphGradient(ivec2 cell) {
    uvec2 h = pcg2d(uvec2(cell));
    float a = float(h.x >> 8u) * (6.28318530718f / 16777216.0f);
    return vec2(cos(a), sin(a));
}

// Perlin 2002, "Improving Noise" (quintic fade), 2D with hashed gradients.
float velvetGraphPerlin(vec2 p) {
    vec2 i = floor(p);
    vec2 f = p - i;
    vec2 u = f * f * f * (f * (f * 6.0f - 15.0f) + 10.0f);
    ivec2 c = ivec2(i);
    float n00 = dot(velvetGraphGradient(c), f);
    float n10 = dot(velvetGraphGradient(c + ivec2(1, 0)), f - vec2(1.0f, 0.0f));
    float n01 = dot(velvetGraphGradient(c + ivec2(0, 1)), f - vec2(0.0f, 1.0f));
    float n11 = dot(velvetGraphGradient(c + ivec2(1, 1)), f - vec2(1.0f, 1.0f));
    return mix(mix(n00, n10, u.x), mix(n01, n11, u.x), u.y);
}

float velvetGraphPerlin01(vec2 p) {
    return clamp(0.5f + 0.70710678f * velvetGraphPerlin(p), 0.0f, 1.0f);
}

float velvetGraphFbm(vec2 p, float octaves, float lacunarity, float gain) {
    int count = clamp(int(octaves + 0.5f), 1, 8);
    float sum = 0.0f;
    float norm = 0.0f;
    float amplitude = 1.0f;
    for (int i = 0; i < 8; ++i) {
        if (i >= count)
            break;
        sum += amplitude * velvetGraphPerlin(p);
        norm += amplitude;
        amplitude *= gain;
        p = p * lacunarity + vec2(17.31f, 9.73f);
    }
    return clamp(0.5f + 0.70710678f * sum / max(norm, 1e-6f), 0.0f, 1.0f);
}

// ---- The fabric functions -------------------------------------------------------------------

#define VELVET_OUT(T) T&
#define VELVET_FABRIC_SOURCE(...) __VA_ARGS__
#include "core/graph/fabric_source.inl"
#include "core/graph/grain_source.inl"
#undef VELVET_FABRIC_SOURCE
#undef VELVET_OUT

} // namespace twin

float warpUp(float i, float j, const WeaveParams& p) {
    return twin::velvetWeaveWarpUp(i, j, p.pattern, p.over, p.under, p.harness, p.step, p.group);
}

WeaveSample weave(glm::vec2 uv, const WeaveParams& p) {
    const twin::VelvetWeave w = twin::velvetWeave(
        uv, p.pattern, p.over, p.under, p.harness, p.step, p.group, p.density, p.width, p.roundness,
        p.warpColor, p.weftColor, p.crossingHeight, p.roughness, p.footprint);
    return {w.color,     w.height, w.normal, w.roughness, w.sheen,
            w.direction, w.thread, w.warp,   w.occlusion};
}

WeaveMean weaveMean(const WeaveParams& p) {
    const twin::VelvetWeaveMean m =
        twin::velvetWeaveMean(p.pattern, p.over, p.under, p.harness, p.group, p.width, p.roundness,
                              p.warpColor, p.weftColor);
    return {m.color, m.height, m.sheen, m.warp};
}

KnitSample knit(glm::vec2 uv, const KnitParams& p) {
    const twin::VelvetKnit k =
        twin::velvetKnit(uv, p.density, p.width, p.roundness, p.lean, p.stitchHeight, p.color);
    return {k.color, k.height, k.normal, k.direction, k.occlusion};
}

FuzzSample fuzz(glm::vec2 uv, const FuzzParams& p) {
    const twin::VelvetFuzz f = twin::velvetFuzz(uv, p.direction, p.baseColor, p.roughness,
                                                p.fuzzColor, p.density, p.stretch, p.amount);
    return {f.color, f.roughness, f.sheen, f.mask};
}

PileSample pile(glm::vec2 uv, const PileParams& p) {
    const twin::VelvetPile s = twin::velvetPile(uv, p.angle, p.lean, p.crush, p.scale);
    return {s.normal, s.sheen, s.roughness, s.crush};
}

GrainSample grain(glm::vec2 uv, const GrainParams& p) {
    const twin::VelvetGrain g =
        twin::velvetGrain(uv, p.scale, p.irregularity, p.creaseWidth, p.dome, p.depth, p.color,
                          p.creaseColor, p.roughness, p.creaseRoughness, p.footprint);
    return {g.color, g.height, g.normal, g.roughness, g.cavity, g.occlusion, g.cell};
}

GrainMean grainMean(const GrainParams& p) {
    const twin::VelvetGrainMean m = twin::velvetGrainMean(p.irregularity, p.creaseWidth, p.dome);
    return {m.height, m.crease, m.slope2};
}

float perlin01(glm::vec2 p) {
    return twin::velvetGraphPerlin01(p);
}

float fbm(glm::vec2 p, float octaves, float lacunarity, float gain) {
    return twin::velvetGraphFbm(p, octaves, lacunarity, gain);
}

} // namespace velvet::graph::fabric
