#pragma once
/// @file display_transform.h
/// The viewport's OpenColorIO display transform on the GPU: OCIO's own shader (not a hand-written
/// copy) placed at the tone-mapping stage of the post chain. Takes the plain data of
/// ColorManagement::gpuDisplayTransform (GLSL text, LUT textures, uniforms; no OCIO types),
/// injects the GLSL into resources/shaders/display_transform.frag and uploads the LUTs and
/// uniforms. Programs are cached by OCIO's cache id: choosing a display/view/look compiles once,
/// choosing it again later compiles nothing, and exposure is a uniform (never a recompile). GL
/// objects stay private; needs a current OpenGL 4.5 core context from construction to destruction.

#include "core/color_management.h"
#include "core/image.h"

#include <memory>
#include <string>

namespace velvet::render {

class DisplayTransform {
public:
    DisplayTransform();
    /// Must run with the context current (frees programs and LUT textures).
    ~DisplayTransform();
    DisplayTransform(const DisplayTransform&) = delete;
    DisplayTransform& operator=(const DisplayTransform&) = delete;

    /// Makes @p transform the current one. The first time its cacheId is seen this compiles
    /// display_transform.frag with the transform's GLSL and uploads its LUT textures and uniforms;
    /// later calls with a known cacheId only switch. False + message (file:line of the generated
    /// "ocio_display.glsl" on a compile error); the previous selection stays on failure.
    bool select(const GpuDisplayTransform& transform, std::string* error);
    /// Switches to an already built program; false (nothing changes) when @p cacheId is unknown.
    bool selectCached(const std::string& cacheId);
    bool hasSelection() const;

    /// Draws the final pass into the bound framebuffer over the current viewport: texel (x, y) of
    /// the scene-linear texture @p hdrTexture (a GL texture name, RGBA, read with texelFetch)
    /// through the selected transform with @p exposureEv stops of exposure, clamped to [0, 1],
    /// alpha 1. Leaves the program, VAO and its texture units unbound. Nothing happens when
    /// nothing is selected.
    void draw(unsigned hdrTexture, float exposureEv);

    /// Testable entry point: runs the selected transform over @p linear (1 to 4 channels, grey as
    /// RRR; uploaded as RGBA32F) into an RGBA32F target and reads back @p display (RGBA, row 0 at
    /// the top, values as draw() writes them). Saves and restores the framebuffer binding and
    /// viewport. False + message when nothing is selected or GL fails.
    bool apply(const Image& linear, float exposureEv, Image& display, std::string* error);

    /// Recompiles every cached program from disk (display_transform.frag and its includes, with the
    /// OCIO GLSL it was built with; the editor's shader reload). A program that fails keeps its
    /// last good build. False + every failure's message (file:line).
    bool reload(std::string* error);

    /// Programs compiled since construction (each new cache id compiles one).
    int compileCount() const;
    /// Programs held in the cache.
    int cachedProgramCount() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace velvet::render
