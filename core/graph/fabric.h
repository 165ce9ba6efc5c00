#pragma once
/// @file fabric.h
/// The C++ twins of the fabric nodes of the material graph (Weave, Knit, Fibre fuzz, Pile and the
/// leather Grain): the same statements as the GLSL the graph compiler emits for them, compiled for
/// the CPU, for bakes and for tests. Both are built from one source, core/graph/fabric_source.inl
/// and grain_source.inl; the node table is core/graph/fabric_nodes.cpp, the patterns' definitions
/// docs/fabric-nodes.md.
///
/// Coordinates: warp ends run along +V and are counted along U (warp density: ends per UV unit),
/// weft picks run along +U and are counted along V. Heights are in [0, 1]; normals are unit
/// tangent-space vectors (+Z out, OpenGL +Y up), the gradient of crossingHeight × height in units
/// of the mean thread spacing.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <string_view>

namespace velvet::graph::fabric {

/// The Weave node's `pattern` input (a whole number, so a pattern change is a value edit).
enum class WeavePattern : int { Plain = 0, Twill = 1, Satin = 2, Basket = 3, Herringbone = 4 };

/// The Weave node's inputs; the defaults are the node's defaults (a 2/1 twill in undyed cotton).
struct WeaveParams {
    float pattern = float(WeavePattern::Twill);
    float over = 2.0f;    ///< twill, herringbone: picks an end floats over
    float under = 1.0f;   ///< twill, herringbone: picks it then passes under
    float harness = 5.0f; ///< satin: N of the N-harness satin (floats over N - 1)
    float step = 1.0f;    ///< picks the interlacing moves per end (twill line; satin counter)
    float group = 2.0f;   ///< basket: ends and picks woven as one; herringbone: ends per stripe
    glm::vec2 density{16.0f, 16.0f}; ///< warp ends per UV unit (along U), weft picks (along V)
    float width = 0.85f;             ///< yarn width as a fraction of the thread spacing
    float roundness = 1.0f;          ///< 0 flat tape, 1 elliptical, 2 parabolic cross-section
    glm::vec3 warpColor{0.62f, 0.58f, 0.5f};
    glm::vec3 weftColor{0.75f, 0.72f, 0.64f};
    float crossingHeight = 0.4f; ///< crown height in thread spacings (normal strength)
    float roughness = 0.8f;
    /// Not a node input: the UV extent of one pixel along u and v, what the GPU takes from
    /// fwidth(uv). Where a pixel spans more than a quarter of a thread the outputs but the normal
    /// and the thread id fade to the pattern's mean (weaveMean), reached at three quarters; (0, 0):
    /// unfiltered.
    glm::vec2 footprint{0.0f, 0.0f};
};

/// The Weave node's outputs at one point.
struct WeaveSample {
    glm::vec3 color{0.0f};
    float height = 0.0f;
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    float roughness = 0.0f;
    float sheen = 0.0f;
    glm::vec2 direction{0.0f, 1.0f}; ///< of the visible yarn: warp (0, 1), weft (1, 0)
    float thread = 0.0f;             ///< per-thread value in [0, 1)
    float warp = 0.0f;               ///< 1 where a warp end is seen
    float occlusion = 1.0f;
};

/// The Weave's colour, height, sheen and warp outputs averaged over its repeat, as the model of
/// fabric_source.inl (velvetWeaveMean) estimates them: what a pixel spanning many threads shows.
struct WeaveMean {
    glm::vec3 color{0.0f};
    float height = 0.0f;
    float sheen = 0.0f;
    float warp = 0.0f;
};
WeaveMean weaveMean(const WeaveParams& p);

/// 1 where warp end @p i passes over weft pick @p j (whole numbers), 0 where under.
float warpUp(float i, float j, const WeaveParams& p);
WeaveSample weave(glm::vec2 uv, const WeaveParams& p);

struct KnitParams {
    glm::vec2 density{10.0f, 14.0f}; ///< wales per UV unit (along U), courses (along V)
    float width = 0.9f;              ///< yarn width as a fraction of half a wale
    float roundness = 1.0f;
    float lean = 0.6f;         ///< how far the legs lean in (0: upright ribs, 1: closed V)
    float stitchHeight = 0.5f; ///< crown height in stitch spacings (normal strength)
    glm::vec3 color{0.55f, 0.1f, 0.1f};
};
struct KnitSample {
    glm::vec3 color{0.0f};
    float height = 0.0f;
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    glm::vec2 direction{0.0f, 1.0f};
    float occlusion = 1.0f;
};
KnitSample knit(glm::vec2 uv, const KnitParams& p);

struct FuzzParams {
    glm::vec2 direction{0.0f, 1.0f}; ///< the yarn's direction (a Weave node's `direction`)
    glm::vec3 baseColor{0.5f};
    float roughness = 0.8f;
    glm::vec3 fuzzColor{0.85f, 0.83f, 0.8f};
    float density = 200.0f; ///< fibres per UV unit across the yarn
    float stretch = 8.0f;   ///< how many times longer than wide a streak is
    float amount = 0.5f;
};
struct FuzzSample {
    glm::vec3 color{0.0f};
    float roughness = 0.0f;
    float sheen = 0.0f;
    float mask = 0.0f;
};
FuzzSample fuzz(glm::vec2 uv, const FuzzParams& p);

struct PileParams {
    float angle = 90.0f; ///< lay direction, degrees counter-clockwise from +U (90: along +V)
    float lean = 0.35f;  ///< tangent of the fibres' tilt towards it
    float crush = 0.0f;  ///< 0 plain velvet, 1 fully crushed velvet
    float scale = 3.0f;  ///< crushed patches per UV unit
};
struct PileSample {
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    float sheen = 0.0f;
    float roughness = 0.0f;
    float crush = 0.0f;
};
PileSample pile(glm::vec2 uv, const PileParams& p);

/// The Grain node's inputs (pebbled leather, grain_source.inl); the defaults are the node's.
struct GrainParams {
    float scale = 12.0f;        ///< cells per UV unit along u and v (a cell spacing of 1 / scale)
    float irregularity = 0.85f; ///< jitter of the cells' points: 0 a square grid, 1 random
    float creaseWidth = 0.2f;   ///< width of a crease's shoulder, in cell spacings
    float dome = 0.8f;          ///< how domed the cells' tops are (0: flat with rounded edges)
    float depth = 0.12f;        ///< relief in cell spacings (normal strength)
    glm::vec3 color{0.2f, 0.075f, 0.03f};        ///< the cells' tops (linear)
    glm::vec3 creaseColor{0.08f, 0.03f, 0.013f}; ///< the creases (linear)
    float roughness = 0.45f;                     ///< the cells' tops (polished by wear)
    float creaseRoughness = 0.75f;               ///< the creases
    /// Not a node input: a pixel's UV extent (fwidth(uv) on the GPU). Where a pixel spans more
    /// than a quarter of a cell the outputs fade to the cells' means (grainMean), reached at
    /// three quarters, the normal to flat and its slopes into the roughness; (0, 0): unfiltered.
    glm::vec2 footprint{0.0f, 0.0f};
};
struct GrainSample {
    glm::vec3 color{0.0f};
    float height = 0.0f;
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    float roughness = 0.0f;
    float cavity = 0.0f; ///< 1 at the bottom of a crease, 0 past its shoulder
    float occlusion = 1.0f;
    float cell = 0.0f; ///< per-cell value in [0, 1)
};
GrainSample grain(glm::vec2 uv, const GrainParams& p);
/// The means over the cells that the filtered Grain fades to (velvetGrainMean's model): the
/// height, the crease profile (1 - cavity) and the squared slope of the height per unit depth.
struct GrainMean {
    float height = 0.0f;
    float crease = 0.0f;
    float slope2 = 0.0f;
};
GrainMean grainMean(const GrainParams& p);

/// @name The graph compiler's noise helpers on the CPU (velvetGraphPerlin01, velvetGraphFbm)
/// @{
float perlin01(glm::vec2 p);
float fbm(glm::vec2 p, float octaves, float lacunarity, float gain);
/// @}

/// The GLSL of the fabric functions (the HelperFabric group of node_catalogue.h); it calls the
/// noise helpers, which the compiler emits before it.
std::string_view fabricGlsl();

} // namespace velvet::graph::fabric
