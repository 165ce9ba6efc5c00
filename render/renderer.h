#pragma once
/// @file renderer.h
/// The deferred renderer: G-buffer pass, lighting (directional lights + HDRI ambient), background,
/// tone mapping to display. Owns every GL object; needs a current OpenGL 4.5 core context (a Qt one
/// in the editor, a bare EGL one in the CLI and tests) and no Qt.

#include <memory>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "core/image.h"
#include "core/scene.h"

namespace velvet::render {

/// What the final pass shows (the renderer issue adds every G-buffer and lighting view).
/// Debug views write raw values to the linear image (readLinear): Albedo linear base colour, Normal
/// world normal, Depth view-space distance along -Z in metres, Roughness, Metallic, Position world
/// position; the display image maps them for viewing.
enum class DebugView { Final, Albedo, Normal, Depth, Roughness, Metallic, Position };

/// Tone-mapping operators (the post-chain issue adds more and the OCIO display transform).
enum class ToneMapper { KhronosPbrNeutral, AcesFitted, Reinhard, Linear };

struct FrameSettings {
    int width = 256;
    int height = 256;
    float exposureEv = 0.0f; ///< exposure in stops applied before tone mapping
    ToneMapper toneMapper = ToneMapper::KhronosPbrNeutral;
    DebugView view = DebugView::Final;
};

/// GPU timings of the last frame (GL timer queries; 0 where unavailable). Logged, never asserted.
struct FrameTimings {
    double gbufferMs = 0, lightingMs = 0, postMs = 0, totalMs = 0;
};

class Renderer {
public:
    Renderer();
    /// Must run with the renderer's context current (frees GL objects).
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Loads and compiles shaders; needs a current GL 4.5 core context. False + message on failure
    /// (a compile error names file:line).
    bool initialize(std::string* error);

    /// Takes the scene to draw. Cheap for value edits (material numbers go to a uniform buffer, no
    /// shader is recompiled); mesh and HDRI are (re)loaded only when their source changes.
    /// Problems (a missing HDRI or texture) are reported and a fallback is used.
    void setScene(const Scene& scene, Problems* problems = nullptr);

    /// Renders one frame into framebuffer @p targetFbo (0: the default framebuffer) at
    /// settings.width x settings.height, display-encoded (sRGB). False + message on GL failure.
    bool render(const FrameSettings& settings, unsigned targetFbo, std::string* error = nullptr);

    /// The last frame's scene-linear HDR colour (before exposure and tone mapping), RGBA float.
    Image readLinear() const;
    /// The last frame's display-encoded colour as written to the target, RGBA in [0, 1].
    Image readDisplay() const;

    /// Number of shader programs compiled since construction (tests assert value edits add none).
    int shaderCompileCount() const;
    FrameTimings lastTimings() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace velvet::render
