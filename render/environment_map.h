#pragma once
/// @file environment_map.h
/// Render-private: equirectangular environments on the GPU (mip-mapped RGBA16F) with their SH9
/// radiance, cached by source so a value edit never reloads an HDRI.

#include "core/diagnostics.h"
#include "core/image.h"
#include "core/scene.h"
#include "core/spherical_harmonics.h"

#include <list>
#include <string>

namespace velvet::render {

struct GpuEnvironment {
    std::string key; ///< HDRI path + '\n' + its modification stamp, or "uniform:r,g,b"
    unsigned texture = 0;
    int width = 0;
    int levels = 1;
    SH9 sh{};            ///< radiance SH9 (intensity not applied)
    std::string warning; ///< non-empty when a fallback replaced a missing or broken file
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
    /// warning in @p problems naming the file.
    const GpuEnvironment& get(const Environment& env, Problems* problems);

    /// Radiance used when an HDRI cannot be read.
    static constexpr float kFallbackGrey = 0.5f;

private:
    std::list<GpuEnvironment> m_entries; ///< most recently used first
};

} // namespace velvet::render
