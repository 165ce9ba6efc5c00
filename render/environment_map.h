#pragma once
/// @file environment_map.h
/// Render-private: equirectangular environments on the GPU (mip-mapped RGBA16F) with their SH9
/// radiance, cached by source so a value edit never reloads an HDRI.

#include "core/diagnostics.h"
#include "core/ibl_cache.h"
#include "core/image.h"
#include "core/scene.h"
#include "core/spherical_harmonics.h"

#include <filesystem>
#include <list>
#include <memory>
#include <string>

namespace velvet::render {

struct GpuEnvironment {
    std::string key; ///< HDRI path + '\n' + its modification stamp, or "uniform:r,g,b"
    unsigned texture = 0;
    int width = 0;
    int height = 0;
    int levels = 1;
    SH9 sh{};            ///< radiance SH9 (intensity not applied)
    std::string warning; ///< non-empty when a fallback replaced a missing or broken file
    /// The on-disk cache (core/ibl_cache.h): where this HDRI's bake is (or goes) and its key;
    /// empty for a uniform environment, a fallback, or with caching off.
    std::filesystem::path cacheFile;
    std::string cacheKey;
    /// The prefiltered cube read from the cache (its equirect already uploaded and dropped):
    /// IblBaker::request adopts it instead of baking. Null when the HDRI was decoded.
    std::shared_ptr<const IblCacheEntry> cached;
};

/// Uploads an equirectangular radiance image as EnvironmentCache does (RGBA16F, full mip chain,
/// its SH9); the caller owns the texture.
GpuEnvironment uploadEquirect(const Image& radiance, std::string key);

class EnvironmentCache {
public:
    EnvironmentCache() = default;
    ~EnvironmentCache();
    EnvironmentCache(const EnvironmentCache&) = delete;
    EnvironmentCache& operator=(const EnvironmentCache&) = delete;

    /// The environment for @p env (loading it if needed, and again when the file's modification
    /// time or size changed). A file that cannot be read gives a uniform grey fallback and a
    /// warning in @p problems naming the file. With a non-empty @p bakeSignature
    /// (IblBaker::cacheSignature) and a cache folder (core/cache_dir.h), an HDRI is first looked
    /// up in the on-disk cache by its content: a hit uploads the cached equirect and carries the
    /// prefiltered cube (GpuEnvironment::cached) without decoding the file; an entry that
    /// cannot be used is rebuilt, with a warning in @p problems.
    const GpuEnvironment& get(const Environment& env, Problems* problems,
                              const std::string& bakeSignature = {});

    /// HDRIs decoded and cache entries used since construction (tests, the bench).
    int decodes() const { return m_decodes; }
    int diskCacheHits() const { return m_diskCacheHits; }

    /// Radiance used when an HDRI cannot be read.
    static constexpr float kFallbackGrey = 0.5f;

private:
    std::list<GpuEnvironment> m_entries; ///< most recently used first
    /// A cache entry's problem, reported once to the next get() given a Problems.
    std::string m_cacheWarning;
    int m_decodes = 0, m_diskCacheHits = 0;
};

} // namespace velvet::render
