#pragma once
/// @file shader_program.h
/// Render-private: GLSL loading with a small `#include "file"` preprocessor and GL program
/// building. Virtual includes generated from C++ tables ("gbuffer_layout.glsl",
/// "render_bindings.glsl") keep one definition of the G-buffer and binding points. Compile errors
/// name file:line (mapped back through `#line`) with the driver's log.

#include "core/texture_ref.h"

#include <string>
#include <utility>
#include <vector>

namespace velvet::render {

/// Binding points shared by C++ and GLSL (emitted as "render_bindings.glsl").
namespace binding {
inline constexpr int kFrameUbo = 0;
inline constexpr int kMaterialSsbo = 1;
inline constexpr int kEnvironmentTex = 4; ///< units 0..3 are the G-buffer (gbuffer_layout.h)
inline constexpr int kSheenLutTex = 5;
inline constexpr int kHdrTex = 6;
/// Image-based lighting (render/ibl_bake.h): its uniform block, the prefiltered specular cube and
/// the DFG LUT.
inline constexpr int kIblUbo = 3;
inline constexpr int kIblSpecularTex = 8;
inline constexpr int kIblDfgTex = 9;
/// The irradiance cube of the frames at rest (render/irradiance_map.h): the unit below the
/// material textures', which the OCIO LUTs from kDisplayLutTexFirst must stay below.
inline constexpr int kIblIrradianceTex = 39;
/// Units kDisplayLutTexFirst.. hold the LUT textures of the OCIO display transform (as many as
/// OCIO asks for, display_transform.cpp checks them against GL_MAX_TEXTURE_IMAGE_UNITS).
inline constexpr int kDisplayLutTexFirst = 16;
/// Units kMaterialTexFirst + TextureSlot hold a material's textures in the G-buffer pass
/// (render/texture_set.h): kTextureSlotCount units, above the OCIO LUTs and within GL 4.5's minimum
/// of 80 combined units.
inline constexpr int kMaterialTexFirst = 40;
/// The G-buffer's two lobe-channel targets (render/gbuffer_layout.h); units 0..3 hold the
/// first G-buffer attachments and depth, 10..13 the stage's (render/stage_interface.h).
inline constexpr int kGBufferLobes0Tex = 14;
inline constexpr int kGBufferLobes1Tex = 15;
} // namespace binding

/// Uniform locations of common_material_textures.glsl's per-slot arrays: uTexRegion takes
/// 1 .. kTextureSlotCount, then uTexUvLinear, then uTexUvOffset (emitted as TEX_UV_*_LOCATION).
constexpr int textureUvLinearLocation() {
    return 1 + kTextureSlotCount;
}
constexpr int textureUvOffsetLocation() {
    return textureUvLinearLocation() + kTextureSlotCount;
}

/// Include files made at run time (name, GLSL text), e.g. OCIO's generated display transform.
/// They are looked up before resources/shaders/ and get their own `#line` index like any file.
using GeneratedSources = std::vector<std::pair<std::string, std::string>>;

/// Reads resources/shaders/@p file and resolves includes. `#version` stays first; @p defines
/// ("NAME" or "NAME VALUE") follow it. Each inserted file gets `#line n index`, where index is
/// its position in @p files. False + message naming the file on a missing or cyclic include.
bool preprocessShader(const std::string& file, const std::vector<std::string>& defines,
                      std::string& out, std::vector<std::string>& files, std::string* error,
                      const GeneratedSources& generated = {});

/// Rewrites driver log lines "index:line(col)" (Mesa) or "index(line)" (NVIDIA) as "file:line".
std::string mapShaderLog(const std::string& log, const std::vector<std::string>& files);

/// Asks the driver for its most shader compiler threads (GL_KHR_parallel_shader_compile) once
/// the context is current; false where the extension is missing, and ProgramBuild::ready() is
/// then always true (builds finish synchronously in ProgramBuild::finish, as before).
bool enableParallelShaderCompile();

class ShaderProgram;

/// A vertex + fragment program build in flight. start() hands the sources to the driver and asks
/// no status, so a driver with GL_KHR_parallel_shader_compile compiles and links on its own
/// threads; ready() polls GL_COMPLETION_STATUS_KHR (never blocks); finish() checks the result and
/// gives the program to a ShaderProgram. Destroying or restarting a build abandons it.
class ProgramBuild {
public:
    ProgramBuild() = default;
    ~ProgramBuild();
    ProgramBuild(const ProgramBuild&) = delete;
    ProgramBuild& operator=(const ProgramBuild&) = delete;

    /// Preprocesses both stages, compiles them and links (any build in flight is abandoned).
    /// False + message when a source cannot be read or included; nothing is then in flight.
    bool start(const std::string& vertexFile, const std::string& fragmentFile,
               const std::vector<std::string>& defines, const GeneratedSources& generated,
               std::string* error);
    /// A build started and not yet finished or abandoned.
    bool active() const { return m_program != 0; }
    /// The driver has finished compiling and linking (true without the extension: finish()
    /// then waits in its status queries).
    bool ready() const;
    /// Waits if not ready, then checks compile and link status. On success @p target takes the
    /// program (releasing its old one); on failure false + message (file:line and the driver
    /// log, as ShaderProgram::build) and @p target keeps its program. Inactive afterwards.
    bool finish(ShaderProgram& target, std::string* error);
    void abandon();

private:
    unsigned m_vertex = 0, m_fragment = 0, m_program = 0;
    bool m_parallel = false;
    std::string m_vertexFile, m_fragmentFile;
    std::vector<std::string> m_vertexFiles, m_fragmentFiles; ///< #line indices to names
};

/// A linked vertex + fragment program.
class ShaderProgram {
public:
    ShaderProgram() = default;
    ~ShaderProgram();
    ShaderProgram(const ShaderProgram&) = delete;
    ShaderProgram& operator=(const ShaderProgram&) = delete;

    /// Compiles and links now (a ProgramBuild finished at once); false + message (file:line and
    /// the driver log) on failure, the previous program kept.
    bool build(const std::string& vertexFile, const std::string& fragmentFile,
               const std::vector<std::string>& defines, std::string* error);
    /// As above, with include files made at run time (see GeneratedSources).
    bool build(const std::string& vertexFile, const std::string& fragmentFile,
               const std::vector<std::string>& defines, const GeneratedSources& generated,
               std::string* error);
    unsigned id() const { return m_program; }
    void release();

private:
    friend class ProgramBuild;
    unsigned m_program = 0;
};

/// A linked compute program. Like ShaderProgram, a failed build keeps the last good program, so
/// Renderer::reloadShaders() can rebuild it from disk without losing it on an error.
class ComputeProgram {
public:
    ComputeProgram() = default;
    ~ComputeProgram();
    ComputeProgram(const ComputeProgram&) = delete;
    ComputeProgram& operator=(const ComputeProgram&) = delete;

    /// Compiles and links resources/shaders/@p file; false + message (file:line and the driver
    /// log) on failure, the previous program kept.
    bool build(const std::string& file, const std::vector<std::string>& defines,
               const GeneratedSources& generated, std::string* error);
    unsigned id() const { return m_program; }
    void release();

private:
    unsigned m_program = 0;
};

} // namespace velvet::render
