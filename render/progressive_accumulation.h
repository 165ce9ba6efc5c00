#pragma once
/// @file progressive_accumulation.h
/// Progressive anti-aliasing of a still view (the editor's viewport at rest).
///
/// The viewport draws one sample per pixel at the pixel's centre, so silhouettes, thin threads
/// of a weave and a sharp highlight stair-step. Once nothing changes, the editor draws the same
/// view again with the projection offset by a sub-pixel jitter (progressiveJitter) and keeps the
/// running mean of those frames (ProgressiveAccumulation): after n frames each pixel is the box
/// filter of n samples spread over its area, the image `velvet render --supersample` gives a
/// still (render/render_job.h), with nothing added to a frame while the artist drags or orbits.
/// As offline renderers' progressive viewports do (Marmoset Toolbag's and Substance's at rest),
/// the frames are averaged after the display step: each one is the picture the artist sees.

#include "render/gbuffer.h"
#include "render/shader_program.h"

#include <glm/vec2.hpp>
#include <string>

namespace velvet::render {

/// The sub-pixel offset, in pixels within (-0.5, 0.5), of the @p index-th frame of a progressive
/// mean: (0, 0) for index 0 (the pixel's centre, so the mean starts from the frame the view
/// already shows), then the Halton sequence in bases 2 and 3 from its point 1 (a low-discrepancy
/// sequence; the centre stands in for its point 0, the pixel's corner, so x = 0 comes twice).
glm::vec2 progressiveJitter(int index);

/// The running mean of display-encoded frames of one size, kept in half floats so that 16 8-bit
/// frames average without rounding each step.
class ProgressiveAccumulation {
public:
    bool build(std::string* error);
    int compileCount() const { return m_compileCount; }

    /// Adds @p frame (an RGBA8 display target) to the mean with weight 1 / (samples + 1); with
    /// @p restart, or when the frame's size is not the mean's, the mean starts again from it.
    /// @p emptyVao is bound for the full-screen triangle. False + message when the history
    /// target cannot be made.
    bool add(const ColorTarget& frame, bool restart, unsigned emptyVao, std::string* error);
    /// Copies the mean into the framebuffer @p targetFbo (the frame's size).
    void present(unsigned targetFbo) const;
    /// The frames in the mean (0 before the first add).
    int samples() const { return m_samples; }
    int width() const { return m_history.width(); }
    int height() const { return m_history.height(); }

private:
    ShaderProgram m_copy;
    ColorTarget m_history;
    int m_samples = 0;
    int m_compileCount = 0;
};

} // namespace velvet::render
