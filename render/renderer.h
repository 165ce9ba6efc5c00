#pragma once
/// @file renderer.h
/// The deferred renderer: G-buffer pass, lighting (directional lights + HDRI ambient), background,
/// tone mapping to display. Owns every GL object; needs a current OpenGL 4.5 core context (a Qt one
/// in the editor, a bare EGL one in the CLI and tests) and no Qt.

#include "core/diagnostics.h"
#include "core/image.h"
#include "core/scene.h"

#include <memory>
#include <string>
#include <vector>

namespace velvet {
class ColorManagement;
}

namespace velvet::render {

/// What the final pass shows (the renderer issue adds every G-buffer and lighting view).
/// Debug views write raw values to the linear image (readLinear): Albedo linear base colour, Normal
/// world normal, Depth view-space distance along -Z in metres, Roughness, Metallic, Position world
/// position; the display image maps them for viewing.
enum class DebugView { Final, Albedo, Normal, Depth, Roughness, Metallic, Position };

/// Built-in tone-mapping operators, used when no OCIO display/view is chosen (FrameSettings).
enum class ToneMapper { KhronosPbrNeutral, AcesFitted, Reinhard, Linear };

struct FrameSettings {
    int width = 256;
    int height = 256;
    /// Exposure in stops (scene-linear x 2^EV) before the tone mapper, or fed to the OCIO display
    /// transform's dynamic exposure uniform when an OCIO display/view is chosen.
    float exposureEv = 0.0f;
    ToneMapper toneMapper = ToneMapper::KhronosPbrNeutral;
    DebugView view = DebugView::Final;
    /// @name OpenColorIO display transform (docs/color-management.md)
    /// All three empty (the default): the built-in toneMapper and the sRGB OETF. Any of them set:
    /// the final view goes through OCIO's own GPU shader for display / displayView / look, where
    /// an empty display is the config's default display and an empty displayView that display's
    /// default view. Debug views ignore these.
    /// @{
    std::string display;
    std::string displayView;
    std::string look; ///< one look name, or OCIO's comma-separated list
    /// @}
    bool usesColorManagement() const {
        return !display.empty() || !displayView.empty() || !look.empty();
    }
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

    /// The OpenColorIO config the display transform comes from. Without one, the first frame that
    /// asks for a display/view loads ColorManagement::defaultConfigPath() ($OCIO or the shipped
    /// config).
    void setColorManagement(std::shared_ptr<const ColorManagement> colorManagement);

    /// Renders one frame into framebuffer @p targetFbo (0: the default framebuffer) at
    /// settings.width x settings.height, display-encoded (the built-in tone mapper + sRGB, or the
    /// chosen OCIO display/view). False + message on GL failure, or, before anything is drawn, on
    /// an unknown display, view or look (the message names it and the config).
    bool render(const FrameSettings& settings, unsigned targetFbo, std::string* error = nullptr);

    /// The last frame's scene-linear HDR colour (before exposure and tone mapping), RGBA float.
    Image readLinear() const;
    /// The last frame's display-encoded colour as written to the target, RGBA in [0, 1].
    Image readDisplay() const;

    /// Number of shader programs compiled since construction (tests assert value edits add none;
    /// a new OCIO display/view/look adds one, exposure none).
    int shaderCompileCount() const;
    FrameTimings lastTimings() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace velvet::render
