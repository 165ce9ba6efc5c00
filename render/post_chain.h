#pragma once
/// @file post_chain.h
/// Render-private: runs a scene's post chain (core/post_chain.h) after lighting, in chain order
/// (Filament's PostProcessManager style: each step takes an input texture and returns its output).
/// Which passes a run draws is the chain's plan (render/post_plan.h: consecutive pointwise effects
/// fused into one generated pass), computed without GL and kept until the chain changes;
/// blur-like effects run at half resolution; render targets come from a pool and are reused
/// across frames. Effects that need depth or normals read the G-buffer textures bound at their
/// layout units (gbuffer_layout.h). Each effect type's renderer is built from the catalogue or is
/// a class of its own (render/post_effect.h, makePostEffect); an effect instance that reads the
/// previous frame (motion blur with frame blending) gets last frame's copy of its input, kept in
/// a pooled target only while such an instance is in the chain. Tests run a chain on synthetic
/// images through tests/render/post_test_harness.h.
/// Needs a current OpenGL 4.5 core context from the first run to destruction.

#include "core/post_chain.h"
#include "render/inline_post.h"

#include <functional>
#include <glm/mat4x4.hpp>
#include <memory>
#include <string>
#include <vector>

namespace velvet::render {

class DisplayEncoding;

/// Inputs of one chain run.
struct PostRunInputs {
    unsigned hdrTexture = 0; ///< scene-linear colour (GL texture name), width x height
    int width = 0, height = 0;
    glm::mat4 viewProj{1.0f};
    glm::mat4 prevViewProj{1.0f}; ///< last frame's (equal to viewProj: a still camera)
    glm::mat4 proj{1.0f};
    float time = 0.0f;       ///< seconds (grain, static, paintbrush)
    float exposureEv = 0.0f; ///< the frame settings' exposure, added to the tone map's own
    /// The tone curve an implicit tone map uses when the chain has LDR effects but no "tonemap"
    /// (an index of the tonemap effect's "operator" choice).
    int implicitToneMapper = 0;
    /// Draws the OCIO display transform of a scene-linear texture into the bound framebuffer with
    /// extra exposure (EV); returns false + message on failure. When set (the frame settings
    /// chose a display/view/look) every tone map of the chain uses it; otherwise only the
    /// "display" operator does, and fails without it.
    std::function<bool(unsigned texture, float exposureEv, std::string* error)> displayTransform;
    /// True when the frame's OCIO view tone maps itself (ACES, AgX, Raw, or a look is chosen):
    /// every tone map of the chain is then the full display transform above.
    bool forceDisplayTransform = false;
    /// The display encoding composed after a built-in curve in fused tone-map passes (OCIO's
    /// shader, render/display_encoding.h). Null: the hand-written sRGB fallback (test inputs).
    const DisplayEncoding* encoding = nullptr;
    unsigned finalFbo = 0; ///< display-encoded output goes here (when the chain tone maps)
};

/// What a run produced.
struct PostRunResult {
    /// True: the chain tone mapped and wrote display-encoded colour to finalFbo. False: the chain
    /// has HDR effects only; hdrTexture holds the result for the renderer's own final pass.
    bool displayEncoded = false;
    unsigned hdrTexture = 0;
};

/// Per-step GPU time (glFinish around each step; profiling only).
struct PostStepTiming {
    std::string name; ///< effect type, or "tonemap+vignette" for a fused step
    double ms = 0.0;
};

class PostChainRenderer {
public:
    PostChainRenderer();
    ~PostChainRenderer();
    PostChainRenderer(const PostChainRenderer&) = delete;
    PostChainRenderer& operator=(const PostChainRenderer&) = delete;

    /// Whether @p chain has an enabled effect (else the renderer skips the chain entirely).
    static bool hasEnabledEffects(const PostChain& chain);

    /// Tone-map passes built per operator (on, the default: an operator switch compiles once, as
    /// a BRDF term switch does) or with the operator chosen at run time (the generic reference,
    /// Renderer::setSpecialisedPrograms(false)).
    void setSpecialiseOperators(bool on);

    /// Runs the enabled effects of @p chain. Programs are compiled on first use (a parameter
    /// change never compiles; a tone-map operator switch compiles once, see above). False + message
    /// on a compile error or a failing display transform. The result's hdrTexture stays valid until
    /// endFrame().
    bool run(const PostChain& chain, const PostRunInputs& inputs, PostRunResult& result,
             std::string* error);
    /// Hands the run's targets back to the pool and trims targets unused for a while.
    void endFrame();

    /// The chain as the lighting pass's display step (issue 16): when its plan is one fused pass
    /// that tone maps with a built-in curve — every enabled effect pointwise, so each pixel needs
    /// only its own lit colour — that pass as lighting.frag's generated include
    /// "inline_post.glsl" into @p out (its key names effects, encoding and operator); false
    /// otherwise (the chain then runs on the HDR target). Builds the effects' classes it needs.
    bool inlineSource(const PostChain& chain, const PostRunInputs& inputs, InlinePost& out);
    /// Before drawing with programs built from inlineSource()'s sources for the same chain and
    /// inputs: their parameters, the frame block and the encoding's LUTs (unbindInline() after).
    void bindInline(const PostChain& chain, const PostRunInputs& inputs,
                    const std::vector<unsigned>& programs);
    void unbindInline();

    /// Recompiles from disk every program built so far (each effect's, the fused passes'): the
    /// renderer's shader reload (the editor's T). A program that fails to compile keeps its last
    /// good build, so the chain goes on drawing; false + every message (file:line and the driver
    /// log), joined by newlines. Programs not built yet are compiled on first use as before.
    bool reload(std::string* error);

    int compileCount() const;
    /// Render-target textures allocated since construction / held now.
    int textureAllocations() const;
    int pooledTextures() const;
    /// Passes drawn by the last run (fusion lowers it).
    int lastStepCount() const;

    /// With profiling on, run() waits for the GPU around each step and records its time.
    void setProfiling(bool on);
    const std::vector<PostStepTiming>& lastTimings() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace velvet::render
