#pragma once
/// @file background_dome.h
/// Render-private: the inline frame's HDRI background drawn as a dome of triangles around the
/// camera, textured with the background already display-encoded (issue 16).
///
/// A background at infinity is a function of the view direction alone, and where the display
/// step is a function of the colour alone (the tone curve, the OCIO encoding, colour grading: no
/// vignette, no grain) so is the display value of each of its pixels. The picture is therefore
/// drawn once into an equirectangular cache at the HDRI's own resolution — each texel the
/// background's display value in that texel's direction (lighting.frag's BACKGROUND_EQUIRECT) —
/// and each frame that moves the camera draws a latitude-longitude sphere whose vertices carry
/// the cache's coordinates: the rasteriser interpolates them, so a pixel pays one bilinear fetch
/// and none of the direction's arithmetic (normalise, atan, acos) nor the display step.
/// On llvmpipe the per-pixel direction and equirect lookup cost 18 ms at 1280×720 and a cube
/// lookup 15 ms, against 4.5 ms for a fetch at interpolated coordinates (BENCHMARKS.md, "The
/// background as a dome"). Linear interpolation of the coordinates across a flat facet of the
/// sphere is off the true equirect mapping by at most a fraction of a texel: a facet of angle a
/// bends a direction by about a^3 / 20 radians (0.0025 of a texel of the 1024-wide HDRIs at 64
/// segments).
/// The cache is drawn again only when what it shows changes (its key: the environment, its
/// rotation and intensity, the background mode, the exposure and the display step): a dragged
/// exposure draws it every frame (524k texels for the 1024-wide HDRIs, about twice the smaller
/// picture's, render/background_downsample.h), so that a frame's picture never depends on the
/// frames before it. The frames at rest keep the smaller picture (renderer_impl.cpp).

#include "core/post_chain.h"
#include "core/scene.h"
#include "render/frame_reuse.h"
#include "render/gbuffer.h"
#include "render/gpu_mesh.h"
#include "render/shader_program.h"

#include <string>

namespace velvet::render {

/// Whether a background of @p mode under the display step of @p chain (null: the built-in tone
/// curve alone) may be drawn as the dome: the HDRI, sharp or blurred, and a chain of effects of
/// the colour alone (the tone map, colour grading). The caller also requires a perspective
/// camera and a cache no larger than the frame's pixels need (background_dome.h).
bool backgroundDomeApplies(BackgroundMode mode, const PostChain* chain);

class BackgroundDome {
public:
    /// Cache texels per environment texel each way (background_dome.h).
    static constexpr int kCacheScale = 1;
    /// The dome's program and its mesh. False + message.
    bool build(std::string* error);
    int compileCount() const { return m_compileCount; }

    /// Draws the dome into @p displayFramebuffer (@p width x @p height), every pixel: the
    /// surfaces' pass draws the mesh's pixels over it. Draws the cache first, @p cacheWidth x
    /// @p cacheHeight texels of @p cacheProgram (the display step's inputs already bound), unless
    /// it already holds @p key. Expects the frame block bound; leaves the depth test off, the
    /// framebuffer and viewport at the display target's and the dome's vertex array bound. @p
    /// cacheDrawn: whether it drew the cache. False + message when the cache cannot be made
    /// (nothing drawn).
    bool draw(const ShaderProgram& cacheProgram, int cacheWidth, int cacheHeight,
              const FrameKey& key, unsigned displayFramebuffer, int width, int height,
              bool* cacheDrawn, std::string* error);
    /// Something the key cannot see changed (a post chain's values, the colour management, the
    /// shaders): the next draw draws the cache again.
    void invalidate() { m_cacheValid = false; }

private:
    ShaderProgram m_program;
    ColorTarget m_cache;
    unsigned m_cacheGeneration = 0;
    FrameKey m_cacheKey;
    bool m_cacheValid = false;
    GpuMesh m_mesh; ///< background_dome.cpp's domeMesh()
    int m_compileCount = 0;
};

} // namespace velvet::render
