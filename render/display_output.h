#pragma once
/// @file display_output.h
/// Render-private: the frame's last step, into the caller's framebuffer — OpenColorIO's display
/// transform (exposure, look, display/view in one generated function: a tone-mapping view such as
/// ACES or AgX, a view without a view transform such as Raw, or a look), or the built-in exposure
/// and tone-mapping curve followed by OCIO's display encoding for the display's un-tone-mapped
/// view (one pass: OCIO's function is composed into display_output.frag). Owns the OCIO config
/// (loaded once, here, when the host gives none), the cached display transforms and encodings,
/// and the tone-map programs, one per encoding.

#include "core/color_management.h"
#include "core/diagnostics.h"
#include "render/display_encoding.h"
#include "render/display_transform.h"
#include "render/inline_post.h"
#include "render/renderer.h"
#include "render/shader_program.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace velvet::render {

/// How a frame's display is done, chosen before anything is drawn (DisplayOutput::choose).
struct DisplayChoice {
    /// OCIO's transform replaces the built-in curve (a tone-mapping view, Raw, or a look).
    bool ocioToneMaps = false;
    /// The final pass is OCIO's display transform (ocioToneMaps and the Final view; debug views
    /// use the display's encoding).
    bool ocioDisplay = false;
    /// display_output.frag for the selected encoding (the final pass otherwise).
    ShaderProgram* tonemap = nullptr;
};

class DisplayOutput {
public:
    DisplayOutput() = default;
    DisplayOutput(const DisplayOutput&) = delete;
    DisplayOutput& operator=(const DisplayOutput&) = delete;

    /// The host's config (null: ColorManagement::defaultConfigPath(), loaded at first use).
    /// Names may mean other transforms in another config: the name-to-id maps are dropped
    /// (compiled programs stay valid: same cache id, same shader).
    void setColorManagement(std::shared_ptr<const ColorManagement> colorManagement);
    /// The config, loading the default the first time; null when it cannot be loaded (frames
    /// then use the hand-written sRGB OETF; warned once, through takeWarnings()).
    const ColorManagement* config();
    /// The same config for the renderer's other users (the texture slots' input colour spaces),
    /// so the file is loaded once: config(), or when it failed an unloaded ColorManagement
    /// (each texture then reports its colour space problem) rather than a second attempt.
    std::shared_ptr<const ColorManagement> sharedConfig();
    /// Warnings found since the last call (no config could be loaded; the config has no
    /// encoding view for a display), each reported once.
    Problems takeWarnings();

    /// Selects the default display's encoding and builds its tone-map program, so that the
    /// first frame and every value edit after it compile nothing. Needs a current context.
    bool initialize(std::string* error);
    /// Chooses the path for @p fs, selecting (and building, the first time) what it needs.
    /// False + message on an unknown display, view or look (naming it and the config).
    bool choose(const FrameSettings& fs, DisplayChoice& choice, std::string* error);
    /// Selects the display transform @p fs names, building it the first time (the post chain's
    /// "display" operator uses it too). Exposure is not part of it: a uniform at every draw.
    bool selectDisplayTransform(const FrameSettings& fs, std::string* error);
    /// The final pass into the bound framebuffer, from scene-linear @p hdrTexture.
    void draw(const DisplayChoice& choice, unsigned hdrTexture, float exposureEv);
    /// The final image's display step (display_output.frag's, the built-in curve and the
    /// encoding) as lighting.frag's generated include "inline_post.glsl" (issue 16); false when
    /// OCIO's transform draws (@p choice.ocioDisplay).
    bool inlineSource(const DisplayChoice& choice, InlinePost& out) const;
    /// Before drawing with programs built from inlineSource(): the encoding's uniforms and LUTs
    /// (unbindInline() after).
    void bindInline(const std::vector<unsigned>& programs) const;
    void unbindInline() const { m_encoding.unbindLuts(); }

    DisplayTransform& transform() { return m_transform; }
    const DisplayEncoding& encoding() const { return m_encoding; }

    /// Rebuilds the display transforms and the tone-map programs from disk; false + messages.
    bool reload(std::string* error);
    /// Programs compiled since construction (tone maps and display transforms).
    int compileCount() const { return m_compileCount + m_transform.compileCount(); }

private:
    bool ocioToneMaps(const FrameSettings& fs, bool& toneMaps, std::string* error);
    bool selectEncoding(const std::string& display, std::string* error);
    ShaderProgram* tonemapProgram(std::string* error);
    bool buildTonemap(ShaderProgram& program, const std::string& encodingId, std::string* error);

    std::shared_ptr<const ColorManagement> m_config;
    bool m_configFailed = false;
    std::shared_ptr<const ColorManagement> m_unloaded; ///< sharedConfig() after a failure
    Problems m_warnings;
    // The display transforms (programs cached by OCIO cache id inside DisplayTransform) and
    // which (display, view, look) maps to which cache id, so that switching back to a view asks
    // OCIO for nothing.
    DisplayTransform m_transform;
    std::map<std::string, std::string> m_transformIds;
    std::string m_transformKey;
    // The encoding after a built-in curve: which display maps to which encoding.
    DisplayEncoding m_encoding;
    std::map<std::string, std::string> m_encodingIds;
    /// display_output.frag, one per display encoding (keyed by its OCIO cache id; "" is the
    /// hand-written fallback).
    std::map<std::string, std::unique_ptr<ShaderProgram>> m_tonemaps;
    int m_compileCount = 0;
};

} // namespace velvet::render
