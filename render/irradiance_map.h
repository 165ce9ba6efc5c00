#pragma once
/// @file irradiance_map.h
/// Render-private: the environment's diffuse irradiance as a small cube (issue 15).
///
/// Image-based light lit diffuse lobes (and the sheen, about its tilted direction) with the
/// environment's SH9 (Ramamoorthi & Hanrahan 2001). For a studio HDRI whose light comes from a few
/// small lamps the nine coefficients ring and smear: beside a bright soft lamp they are a tenth off
/// the integral (test_render_irradiance_map: 11 % mean relative error), and a white glazed ceramic
/// under the default HDRI read mean ΔE2000 1.90 against the reference path tracer at 48 × 48 with
/// them, 0.84 with this cube (BENCHMARKS.md, "The irradiance integrated, not its SH9").
/// This cube holds E(n) / pi integrated over a low mip of the equirect (at least 64 texels wide:
/// 2,048 source texels a direction for the shipped HDRIs, lamps keeping their energy in the mip's
/// means), 32 × 32 a face (the irradiance varies over tens of degrees), in the environment's own
/// frame (its rotation and intensity are applied by the lookup). It is integrated once per
/// environment in six dispatches, in the first frame that shows it, and read by every frame: a
/// 24 KB cube's fetch costs llvmpipe no more than the SH9's arithmetic (BENCHMARKS.md).

#include "render/environment_map.h"
#include "render/shader_program.h"

#include <string>

namespace velvet::render {

class IrradianceMap {
public:
    /// Face size of the cube, and the least width of the equirect mip it integrates.
    static constexpr int kFaceSize = 32;
    static constexpr int kSourceWidth = 64;

    ~IrradianceMap();
    /// Compiles the compute program. False + message.
    bool build(std::string* error);
    int compileCount() const { return m_compileCount; }
    /// Integrates @p environment's cube unless it already holds it (its key and texture). Needs a
    /// current context; leaves the image and texture units it used unbound.
    void update(const GpuEnvironment& environment);
    /// The cube (environment frame, no intensity), 0 before the first update().
    unsigned texture() const { return m_cube; }
    /// Environments integrated since construction (tests: once per environment).
    int integrations() const { return m_integrations; }
    /// The shaders changed: the next update() integrates again.
    void invalidate() { m_texture = 0; }

private:
    ComputeProgram m_program;
    unsigned m_cube = 0;
    std::string m_key;      ///< GpuEnvironment::key of the environment integrated
    unsigned m_texture = 0; ///< its texture (0: none yet, or invalidated)
    int m_compileCount = 0, m_integrations = 0;
};

} // namespace velvet::render
