#pragma once
/// @file ao_pass.h
/// Render-private: screen-space ambient occlusion (GTAO, ao_gtao.frag) at half resolution after
/// the geometry pass, then a depth-aware 4x4 blur (ao_blur.frag); the lighting pass reads the
/// result at stage_binding::kOcclusionTex with a depth-aware upsample (stage_shading.glsl) and
/// multiplies the environment's light by it and the material's occlusion map.

#include "render/gbuffer.h"
#include "render/shader_program.h"

#include <string>

namespace velvet::render {

class OcclusionPass {
public:
    bool build(std::string* error);
    int compileCount() const { return m_compileCount; }
    /// The half-resolution size for a @p width x @p height frame.
    static int halfSize(int fullSize) { return (fullSize + 1) / 2; }
    /// Runs both passes for a @p width x @p height frame; expects the frame and stage blocks and
    /// the G-buffer's textures bound. Leaves the viewport at the half size.
    bool run(int width, int height, unsigned emptyVao, std::string* error);
    /// The blurred occlusion at stage_binding::kOcclusionTex.
    void bind() const;

private:
    ShaderProgram m_gtao, m_blur;
    ColorTarget m_raw, m_blurred;
    int m_compileCount = 0;
};

} // namespace velvet::render
