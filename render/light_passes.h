#pragma once
/// @file light_passes.h
/// Render-private: the point, spot and area lights of a scene, drawn on top of the full-screen
/// lighting pass (which does directional lights, ambient and the environment) by one of three
/// paths that give the same image (tests/render/test_render_light_paths.cpp):
///  - Volumes: the seeds' light volumes, a proxy per light (a sphere; a cone for spot lights of
///    outer angle up to kConeProxyMaxOuterDeg), back faces depth-tested against the G-buffer and
///    added by blending, so only pixels in front of a light's far side pay;
///  - Tiled: a compute pass culls lights into small screen tiles by the tile's view-space box and a
///    per-tile depth bitmask (Harada et al. 2012 "Forward+"; Harada 2012's 2.5D culling) and
///    shades each pixel with its tile's list (Olsson & Assarsson 2011);
///  - Brute: one full-screen loop over every light, for comparison.
/// Light data lives in an SSBO (any number of lights; scenes hold 4,096 and more).

#include "core/scene.h"
#include "render/renderer.h"
#include "render/shader_program.h"

#include <string>
#include <vector>

namespace velvet::render {

/// Lights Auto sends down the brute-force path (one pass, nothing to cull); above, tiled.
inline constexpr int kAutoBruteMaxLights = 8;

/// Spot lights with a wider outer cone are drawn by the sphere proxy in the volumes path (a cone
/// of half-angle above ~63 degrees encloses more than the sphere).
inline constexpr float kConeProxyMaxOuterDeg = 60.0f;

/// The path Auto picks for @p localLightCount lights.
LightPath resolveLightPath(LightPath requested, int localLightCount);

class LightPasses {
public:
    LightPasses() = default;
    ~LightPasses();
    LightPasses(const LightPasses&) = delete;
    LightPasses& operator=(const LightPasses&) = delete;

    /// Compiles the three paths' programs and makes the proxy mesh. False + message (file:line).
    bool initialize(std::string* error);
    /// Programs compiled by initialize() and reload().
    int compileCount() const { return m_compileCount; }
    /// Recompiles the three paths' programs from disk; a program that fails keeps its last good
    /// build. False + every failure's message (file:line).
    bool reload(std::string* error);

    /// Packs the point, spot and area lights of @p lights into the light buffer (directional and
    /// ambient lights stay with the full-screen pass).
    /// @p shadowSlots, when given, holds each light's shadow slot + 1 (0: none; Stage).
    void upload(const std::vector<Light>& lights, const std::vector<int>* shadowSlots = nullptr);
    int lightCount() const { return m_count; }

    /// Adds the lights to @p hdrTexture (RGBA16F, bound in @p hdrFbo). Expects the frame UBO,
    /// the material table and the G-buffer textures bound, and the G-buffer of @p gbufferFbo
    /// filled. @p geometricHorizon: some drawn material bends its shading normal
    /// (LightingFeatures::geometricHorizon); without, the programs built without the face
    /// normal's reconstruction draw (llvmpipe would run it for every pixel and light).
    /// Leaves blending, culling and depth testing disabled.
    void draw(LightPath path, int width, int height, unsigned gbufferFbo, unsigned hdrFbo,
              unsigned hdrTexture, unsigned emptyVao, bool geometricHorizon = true);

private:
    void release();
    bool buildPrograms(std::string* error);
    /// Each shading path twice: [0] WITH_GEOMETRIC_HORIZON 0, [1] with it (gbuffer_read.glsl).
    ShaderProgram m_volumeProgram[2], m_bruteProgram[2];
    ComputeProgram m_tiledProgram[2], m_classifyProgram;
    unsigned m_lightSsbo = 0;
    unsigned m_tileSsbo = 0;    ///< indirect dispatch arguments, then the active tiles
    size_t m_tileSsboTiles = 0; ///< tiles m_tileSsbo has room for
    size_t m_ssboBytes = 0;
    int m_count = 0;
    int m_coneFirst = 0; ///< lights [m_coneFirst, m_count) use the cone proxy
    unsigned m_proxyVao = 0, m_proxyVbo = 0, m_proxyIbo = 0;
    int m_proxyIndexCount = 0; ///< the sphere's indices, first in m_proxyIbo
    int m_coneIndexCount = 0;  ///< the cone's, after them
    int m_coneBaseVertex = 0;  ///< the cone's first vertex in m_proxyVbo
    unsigned m_volumeFbo = 0;
    int m_compileCount = 0;
};

} // namespace velvet::render
