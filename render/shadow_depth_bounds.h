#pragma once
/// @file shadow_depth_bounds.h
/// Render-private: the shadow maps' depth bounds (docs/shadows.md, "Skipping what the filter
/// would not change"). For every layer of the depth array, a mip chain of RG32F texels holding
/// the least (r) and greatest (g) stored depth over the map texels each covers: level 0 reduces
/// kShadowBoundsBlock² texels, each further level 2x2 of the one above (a min-max shadow map,
/// Dmitriev and Uralsky 2007). The shadow mask's lookup reads four texels of the level where its
/// whole filter footprint fits and, where no texel can be a blocker or every one is, knows the
/// filter's result without running it (shadow_sampling.glsl, shadowVisibilityBound), so those
/// texels are skipped exactly. Rebuilt with the maps (ShadowMaps::draw), never per frame.

#include "render/shader_program.h"

#include <string>

namespace velvet::render {

/// Map texels per level-0 bounds texel, per side.
inline constexpr int kShadowBoundsBlock = 8;

/// Levels of a full mip chain whose level 0 is @p size texels wide (size, size / 2, ..., 1).
constexpr int shadowBoundsLevels(int size) {
    int levels = 1;
    while ((size >> levels) > 0)
        ++levels;
    return levels;
}

class ShadowDepthBounds {
public:
    ShadowDepthBounds() = default;
    /// Needs the renderer's context current.
    ~ShadowDepthBounds();
    ShadowDepthBounds(const ShadowDepthBounds&) = delete;
    ShadowDepthBounds& operator=(const ShadowDepthBounds&) = delete;

    bool build(std::string* error);
    int compileCount() const { return m_compileCount; }

    /// Rebuilds the bounds of @p layers layers of @p depthArray (a @p size² GL_TEXTURE_2D_ARRAY
    /// of depth, size a multiple of kShadowBoundsBlock): one compute dispatch per level and layer.
    void update(unsigned depthArray, int layers, int size);
    /// The RG32F array with its mip chain (0 before the first update()).
    unsigned texture() const { return m_texture; }
    int levels() const { return m_levels; }

private:
    void allocate(int layers, int size);

    ComputeProgram m_program;
    int m_compileCount = 0;
    unsigned m_texture = 0;
    int m_layers = 0, m_size = 0, m_levels = 0;
};

} // namespace velvet::render
