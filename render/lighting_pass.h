#pragma once
/// @file lighting_pass.h
/// Render-private: the full-screen passes over the G-buffer into the HDR target (lighting.frag in
/// variants): the background where no geometry was drawn, then the surfaces lit by the
/// directional and ambient lights and the environment (image-based light). Both draw a triangle
/// at the far plane against the G-buffer's depth, read-only: GL_EQUAL passes where nothing was
/// drawn (the background), GL_GREATER where there is geometry (the surfaces), so neither pays
/// for the other.

#include "core/scene.h"
#include "render/inline_post.h"
#include "render/lighting_features.h"
#include "render/render_interface.h"
#include "render/renderer.h"
#include "render/shader_program.h"

#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace velvet::render {

class LightingPass {
public:
    /// Builds the variants every frame may need (Final and the backgrounds: a scene edit never
    /// compiles); the debug families again only when built before. With @p keepGoing (shader
    /// reload) a failure keeps that variant's last good build and the others are still built.
    /// False + every message.
    bool build(std::string* error, bool keepGoing = false);
    /// The surface variant for @p view, built the first time a debug family is shown (a
    /// debug-view switch may compile once); null + message on failure.
    /// In the final image a ground adds its own code (docs/shadows.md): the shadow catcher's
    /// pixels are discarded (drawCatcher() shades them), the plain ground fades into the
    /// @p background (built per mode, as llvmpipe runs every branch of a runtime switch).
    /// The final image's program is specialised to @p features (render/lighting_features.h):
    /// built now when @p mayBuild, otherwise (a value edit this frame: it must not compile) the
    /// generic program draws until a frame may build it. A specialised build that fails (a bug,
    /// the generic one being good) keeps the generic program for those features and is counted
    /// in specialisationFailures() with its message.
    const ShaderProgram*
    surfaceProgram(DebugView view, std::string* error, GroundMode ground = GroundMode::Off,
                   BackgroundMode background = BackgroundMode::Sharp,
                   const LightingFeatures& features = LightingFeatures::generic(),
                   bool mayBuild = true);

    /// The background (FrameSettings::view Final only: debug views leave the HDR target black).
    /// Blurred falls back to Sharp (the same lookup) until the prefiltered cube is ready.
    void drawBackground(BackgroundMode mode, bool prefilteredReady);
    /// The background from @p program (inlinePrograms()).
    void drawBackground(const ShaderProgram& program);

    /// The final image's background and surface programs with @p inlinePost compiled in, the
    /// surfaces specialised to @p features (no ground: GroundMode::Off), so that the pass writes
    /// display values straight into the display target (issue 16). Built when @p mayBuild
    /// (the rule of surfaceProgram()); false when either is not available (not built, a failed
    /// build, generic features): the frame then goes through the HDR target as before.
    bool inlinePrograms(BackgroundMode background, bool prefilteredReady,
                        const LightingFeatures& features, const InlinePost& inlinePost,
                        bool mayBuild, const ShaderProgram*& backgroundProgram,
                        const ShaderProgram*& surfaces);
    /// The background of inlinePrograms() built to draw into a target @p factor times smaller
    /// each way (lighting.frag's BACKGROUND_DOWNSAMPLE; render/background_downsample.h), under
    /// the same rules; null when not available.
    const ShaderProgram* downsampledBackground(BackgroundMode background, bool prefilteredReady,
                                               int factor, const InlinePost& inlinePost,
                                               bool mayBuild);
    /// The background of inlinePrograms() built to draw its dome's equirect cache
    /// (lighting.frag's BACKGROUND_EQUIRECT; render/background_dome.h), under the same rules;
    /// null when not available.
    const ShaderProgram* equirectBackground(BackgroundMode background, bool prefilteredReady,
                                            const InlinePost& inlinePost, bool mayBuild);
    /// The surfaces, from @p program (surfaceProgram()). With @p emission the geometry pass's
    /// emission is kept: result = surface + emission x alpha (lighting.frag's header), the
    /// target's alpha staying 1; without it the surfaces replace the black (no blend to pay).
    /// @p displayValues: the program writes display values (inlinePrograms()), alpha 1 included.
    void drawSurfaces(const ShaderProgram& program, bool emission, bool displayValues = false);
    /// The shadow-catching ground's pixels (GroundMode::ShadowCatcher, the final image only):
    /// the background times the light it receives (lighting.frag's LIGHTING_CATCHER). The
    /// surface variants discard those pixels.
    /// Built the first time for each background mode (null + message on failure); specialised
    /// to @p features like the surfaces (no shadowed light: no shadow lookup; occlusion off: no
    /// occlusion fetch), under the same @p mayBuild rule.
    bool drawCatcher(bool emission, BackgroundMode background, std::string* error,
                     const LightingFeatures& features = LightingFeatures::generic(),
                     bool mayBuild = true);

    /// Programs built since construction.
    int compileCount() const { return m_compileCount; }
    /// Whether the last surfaceProgram() call returned a specialised program.
    bool lastWasSpecialised() const { return m_lastSpecialised; }
    /// Whether it wanted one it was not allowed to build (a value edit that frame).
    bool lastDeferred() const { return m_lastDeferred; }
    /// Specialised builds that failed, and the last one's message.
    int specialisationFailures() const { return m_specialisationFailures; }
    const std::string& lastSpecialisationError() const { return m_specialisationError; }

private:
    /// lighting.frag's variants (its header): the surfaces per debug-view family, and the
    /// background per BackgroundMode.
    enum Variant {
        kFinal,
        kLobeViews,
        kGBufferViews,
        kFinalCatcherGround,
        kFinalPlainGround,                ///< + int(BackgroundMode)
        kCatcher = kFinalPlainGround + 4, ///< + int(BackgroundMode)
        kBackground = kCatcher + 4,       ///< + int(BackgroundMode)
        kCount = kBackground + 4
    };
    static Variant variantFor(DebugView view);
    static std::vector<std::string> variantDefines(Variant v);
    bool buildVariant(Variant v, std::string* error);
    const ShaderProgram* variant(Variant v, std::string* error);

    /// The specialised program of @p v for @p features, built when @p mayBuild; null: use the
    /// generic one.
    const ShaderProgram* specialised(Variant v, const LightingFeatures& features, bool mayBuild,
                                     const InlinePost* inlinePost = nullptr);
    /// The same by the features' defines.
    const ShaderProgram* specialised(Variant v, std::vector<std::string> featureDefines,
                                     bool mayBuild, const InlinePost* inlinePost);

    ShaderProgram m_programs[kCount];
    /// Specialised surface programs by (variant, defines, InlinePost::key); null after a failed
    /// build. At most kMaxSpecialised are kept, the least recently used evicted.
    struct Specialised {
        std::unique_ptr<ShaderProgram> program;
        long lastUse = 0;
    };
    static constexpr size_t kMaxSpecialised = 14;
    std::map<std::tuple<int, std::vector<std::string>, std::string>, Specialised> m_specialised;
    long m_useClock = 0;
    bool m_lastSpecialised = false, m_lastDeferred = false;
    int m_specialisationFailures = 0;
    std::string m_specialisationError;
    int m_compileCount = 0;
};

} // namespace velvet::render
