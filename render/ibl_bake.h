#pragma once
/// @file ibl_bake.h
/// Render-private: the image-based-lighting bake. An environment (render/environment_map.h) is
/// turned into a radiance cubemap and a GGX-prefiltered specular mip chain (Karis 2013, "Real
/// Shading in Unreal Engine 4", with the PDF-based source mip selection of Colbert & Krivanek
/// 2007), in slices of bounded time so that a window never freezes; diffuse irradiance is
/// render/irradiance_map.h's cube (the SH9 until it exists). Also owns
/// the lookup tables: the split-sum DFG LUT (made once on the GPU, in slices, then cached on disk
/// under $XDG_CACHE_HOME/velvet) and the sheen albedo tables of every sheen model (core/brdf.h).
///
/// While a bake is incomplete the previous complete one stays in use; with none, the lighting
/// pass takes the approximate path (mip-mapped equirect and Karis 2014's analytic DFG).

#include "core/image.h"
#include "render/environment_map.h"

#include <deque>
#include <filesystem>
#include <glm/vec2.hpp>
#include <string>
#include <vector>

namespace velvet::render {

/// Sizes and budgets of the bake.
struct IblBakeOptions {
    /// Cube face size of level 0; 0: from the source (a quarter of the equirect's width, a power
    /// of two clamped to 16..256).
    int faceSize = 0;
    /// Levels of the prefiltered chain (level k has roughness k / (levels - 1)); fewer when the
    /// face is too small.
    int specularLevels = 6;
    /// Importance samples per prefiltered texel (few suffice with PDF-based source mips).
    int samples = 64;
    /// Target GPU time of one slice (measured with glFinish); the bake adapts the rows per slice
    /// to it from the cost it measured on the previous slices.
    double sliceTargetMs = 8.0;
    /// Most work units (texels x samples per texel) one slice may do, whatever the cost model
    /// says: a slice's time stays bounded by this much work even when the model's estimate is
    /// off (its first slice, a machine that got busy). A slice still does at least one group of
    /// rows; no job's row group exceeds this (a 256-texel face at 64 samples: 8 rows = 2^17).
    double maxSliceUnits = 262144.0;
};

/// What the bake measured (reported by tests and the bench; never asserted as absolute times).
struct IblBakeStats {
    int slices = 0;             ///< slices run since construction
    double worstSliceMs = 0;    ///< longest slice (dispatch + glFinish, wall clock)
    double worstSliceUnits = 0; ///< most work units (texels x samples) one slice did
    double totalMs = 0;         ///< sum of the slices
    std::vector<double> sliceMs;
};

class IblBaker {
public:
    IblBaker();
    /// Must run with the context current (frees GL objects).
    ~IblBaker();
    IblBaker(const IblBaker&) = delete;
    IblBaker& operator=(const IblBaker&) = delete;

    /// Compiles the compute programs, uploads the sheen tables and the DFG LUT (from the disk
    /// cache when it holds a valid one; otherwise its slices are queued first). False + message.
    bool initialize(std::string* error);
    void setOptions(const IblBakeOptions& options) { m_options = options; }
    const IblBakeOptions& options() const { return m_options; }

    /// Starts baking @p env unless it is the one baked or being baked (a pending bake of another
    /// environment is dropped; the ready one stays in use until the new one completes).
    void request(const GpuEnvironment& env);
    /// Runs slices until about @p budgetMs has been spent or nothing is left; true when done.
    bool step(double budgetMs);
    /// Runs every remaining slice (headless rendering, tests).
    void finish();
    /// Completion of the queued work in [0, 1] (1 when nothing is pending).
    float progress() const;

    bool specularReady() const { return m_ready.specular != 0; }
    unsigned specularCube() const { return m_ready.specular; }
    int specularLevels() const { return m_ready.levels; }
    int faceSize() const { return m_ready.faceSize; }
    bool dfgReady() const { return m_dfgReady; }
    unsigned dfgLut() const { return m_dfgLut; }
    /// RGBA32F kSheenLutSize^2: the sheen, diffuse and specular albedo tables (render/sheen_lut.h).
    unsigned sheenLut() const { return m_sheenLut; }

    const IblBakeStats& stats() const { return m_stats; }
    /// Time the first sliced step()s spent on a tiny bake that makes llvmpipe compile the
    /// shaders' machine code (once per baker and per reload; otherwise charged to the first slice
    /// of each kind of job). Not a slice: it is shader compilation, itself spread over frames
    /// (about one program's compile per frame; a warm-up frame runs no bake slice).
    double warmUpMs() const { return m_warmUpMs; }
    /// Frames (step() calls) the warm-up took, and the longest of them (wall clock, ms).
    int warmUpFrames() const { return m_warmUpFrames; }
    double worstWarmUpFrameMs() const { return m_worstWarmUpFrameMs; }

    /// Recompiles the compute programs from disk (the editor's shader reload); a program that
    /// fails keeps its last good build, and the warm-up runs again. False + every failure's
    /// message (file:line); @p compiled counts the programs rebuilt.
    bool reload(std::string* error, int* compiled = nullptr);
    /// Compute programs built since construction: initialize() builds the four (equirect to
    /// cube, downsample, prefilter, DFG), each reload() the ones it rebuilt.
    int compileCount() const { return m_compileCount; }

    /// @name Read-backs for tests
    /// @{
    /// Face @p face (GL order +X, -X, +Y, -Y, +Z, -Z) of level @p level of the prefiltered cube.
    Image readSpecularFace(int level, int face) const;
    /// The DFG LUT, row-major (row = roughness), ibl::kDfgLutSize^2 (A, B) pairs.
    std::vector<glm::vec2> readDfgLut() const;
    /// @}

    /// Where the DFG LUT is cached (core/cache_dir.h: $VELVET_CACHE_DIR, else
    /// $XDG_CACHE_HOME/velvet, else ~/.cache/velvet); empty when caching is off or has no place.
    /// The name carries the format version, size and sample count.
    static std::filesystem::path dfgCacheFile();

    /// What a prefiltered environment in the disk cache (core/ibl_cache.h) must have been baked
    /// with to be used as this baker's: the cache format's version, the options that shape the
    /// cube (face size, levels, samples) and a hash of the bake shaders' preprocessed sources
    /// (a shader edit makes old entries misses). Empty before initialize() or after a reload
    /// that failed: nothing is cached then.
    std::string cacheSignature() const;
    /// Environments adopted from the disk cache and entries written since construction.
    int cacheAdoptions() const { return m_cacheAdoptions; }
    int cacheWrites() const { return m_cacheWrites; }

private:
    struct Bake {
        std::string key;
        unsigned radiance = 0; ///< mip-mapped cube, the prefilter's source (freed when done)
        unsigned specular = 0; ///< the prefiltered chain
        int faceSize = 0;
        int levels = 0;
        /// Where the finished bake is written (GpuEnvironment::cacheFile; empty: nowhere).
        std::filesystem::path cacheFile;
        std::string cacheKey;
        SH9 sh{};
    };
    enum class JobKind { Dfg, EquirectToCube, RadianceMips, CopyLevel0, Prefilter };
    struct Job {
        JobKind kind;
        int face = 0, level = 0;
        int size = 0;    ///< rows (and columns) of the image (level) the job writes
        int samples = 1; ///< work per texel, for the cost model
        int row = 0;     ///< next row to do
    };

    void release(Bake& bake);
    /// One frame of the sliced warm-up; true once it is complete.
    bool warmUpStep();
    void abandonWarmUp();
    double runSlice(Job& job);
    void completeDfg();
    /// Writes @p bake (just completed from m_source) to its disk cache entry.
    void writeDiskCache(const Bake& bake);
    double jobUnits(const Job& job) const { return double(job.size) * job.size * job.samples; }

    IblBakeOptions m_options;
    unsigned m_equirectProgram = 0, m_downsampleProgram = 0, m_prefilterProgram = 0,
             m_dfgProgram = 0;
    unsigned m_dfgLut = 0, m_sheenLut = 0;
    bool m_dfgReady = false;
    Bake m_ready, m_pending;
    unsigned m_source = 0; ///< the pending bake's equirect (owned by EnvironmentCache)
    int m_sourceWidth = 0;
    std::deque<Job> m_jobs;
    double m_unitsTotal = 0, m_unitsDone = 0;
    double m_msPerUnit[5] = {}; ///< measured cost per JobKind; 0 until its first slice
    IblBakeStats m_stats;
    double m_warmUpMs = 0;
    int m_warmUpFrames = 0;
    double m_worstWarmUpFrameMs = 0;
    bool m_warmedUp = false;
    int m_compileCount = 0;
    std::string m_shaderHash; ///< of the bake programs' sources (cacheSignature)
    int m_cacheAdoptions = 0, m_cacheWrites = 0;
    /// The warm-up's own tiny bake, carried from frame to frame.
    struct WarmUp {
        bool started = false, jobsDone = false;
        GpuEnvironment source;
        Bake bake;
        std::deque<Job> jobs;
        unsigned sourceTexture = 0;
        int sourceWidth = 0;
    };
    WarmUp m_warm;
};

} // namespace velvet::render
