#pragma once
/// @file ocio_gpu.h
/// Render-private helpers shared by the two places OCIO's GPU shaders run: the full display
/// transform (render/display_transform.h) and the display encoding composed into the tone-mapping
/// programs (render/display_encoding.h). Need a current OpenGL 4.5 context.

#include "core/color_management.h"

namespace velvet::render {

/// Uploads one OCIO LUT as OCIO's own OpenGL helper does; returns the GL texture name.
unsigned uploadOcioLut(const GpuLutTexture& lut);
/// Sets @p u's extraction-time value on @p program (nothing when the uniform was optimised out).
void setOcioUniform(unsigned program, const GpuUniform& u);

} // namespace velvet::render
