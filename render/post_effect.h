#pragma once
/// @file post_effect.h
/// Render-private: the pieces every post effect is built from. A pooled render target, the
/// per-run context (pool, frame constants, the shared blur and the OCIO hook) and the effect
/// interface. Each effect's parameters reach its shader as vec4 slots whose indices are generated
/// from the catalogue (core/post_effects.h) into the virtual include "post_params.glsl".

#include "core/post_effects.h"
#include "render/shader_program.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace velvet::render {

/// @name Bindings and uniform locations of the post shaders (emitted into post_params.glsl)
/// @{
inline constexpr int kPostInputUnit = 8; ///< the image an effect reads (linear sampler)
inline constexpr int kPostAuxUnit = 9;   ///< a second image (bloom level, blur, curl field)
inline constexpr int kPostAux2Unit = 10; ///< a third image, bound by the effect (DoF's wide blur)
inline constexpr int kPostFrameUbo = 7;  ///< PostFrame block
inline constexpr int kPostMaxSlots = 48; ///< vec4 parameter slots (uParams)
inline constexpr int kPostPassLocation = 50;
inline constexpr int kPostTexelLocation = 51;
inline constexpr int kPostWeightsLocation = 52;
inline constexpr int kPostMaxTaps = 65; ///< gaussian taps: centre + 64 each side
/// @}

/// The text of "post_params.glsl": the bindings above and, per effect and parameter, the slot
/// index (`#define VIGNETTE_INTENSITY 3`) and choice values (`#define TONEMAP_OPERATOR_ACES 1`).
std::string postParamsGlsl();

/// Normalised gaussian weights w[0..radius] for taps 0, ±1, …, ±radius:
/// G(x) = e^(−x²/2σ²)/√(2πσ²) (seed 001), scaled so that w[0] + 2 Σ w[i] = 1.
std::vector<float> gaussianWeights(float sigma, int radius);

/// A colour texture with its framebuffer (RGBA16F, bilinear, clamped).
struct PostTarget {
    unsigned texture = 0;
    unsigned fbo = 0;
    int width = 0, height = 0;
};

/// Render targets reused across passes and frames: acquire() returns a free target of the size
/// or allocates one; release() hands it back. Over a steady sequence of frames the number of
/// allocations stops growing (tests/render/test_render_post_effects.cpp).
class PostTargetPool {
public:
    PostTargetPool() = default;
    ~PostTargetPool();
    PostTargetPool(const PostTargetPool&) = delete;
    PostTargetPool& operator=(const PostTargetPool&) = delete;

    PostTarget acquire(int width, int height);
    void release(const PostTarget& target);
    /// Once per frame: frees targets idle for 8 frames (sizes no longer used after a resize).
    void trim();
    /// Textures allocated since construction.
    int allocationCount() const { return m_allocations; }
    /// Textures held now.
    int size() const { return int(m_entries.size()); }

private:
    struct Entry {
        PostTarget target;
        bool inUse = false;
        int idleFrames = 0;
    };
    std::vector<Entry> m_entries;
    int m_allocations = 0;
};

/// What a chain run gives every effect.
struct PostContext {
    PostTargetPool* pool = nullptr;
    int width = 0, height = 0; ///< full resolution
    unsigned vao = 0;          ///< an empty VAO for the fullscreen triangle
    /// Blurs @p input into @p output with a separable gaussian (sizes may differ: the blur runs
    /// at the output's size, reading @p input bilinearly when they differ).
    std::function<void(const PostTarget& input, const PostTarget& output, float sigma, int radius)>
        blur;
    /// Draws the OCIO display transform of @p input (scene-linear) into the bound framebuffer
    /// with @p exposureEv; empty when no display transform is available.
    std::function<void(unsigned input, float exposureEv)> displayTransform;
    /// Shader programs compiled (counted by the chain).
    int* compileCount = nullptr;
    /// During run() of an effect whose readsPreviousFrame() is true: last frame's copy of its
    /// input (same size), or a zero texture on the first frame and after a resize.
    PostTarget previousFrame;
};

/// Uploads @p effect's parameters into uParams[base …] of @p program (catalogue order).
void setEffectParams(unsigned program, const EffectMeta& meta, const EffectInstance& effect,
                     int base);
/// Binds @p output, sets the viewport, uPass and uTexel (from @p input's size) and draws the
/// fullscreen triangle with @p program; @p input on kPostInputUnit, @p aux on kPostAuxUnit.
void drawPostPass(const PostContext& ctx, unsigned program, const PostTarget& input,
                  const PostTarget& output, int pass, int level = 0, unsigned aux = 0);
/// Builds @p program from fullscreen.vert + @p fragment with the post includes.
/// @p pass >= 0 defines POST_PASS (one program per pass of a multi-pass effect). When @p extra
/// has no "display_encode.glsl", the hand-written sRGB fallback of render/display_encoding.h is
/// supplied.
bool buildPostProgram(ShaderProgram& program, const std::string& fragment,
                      const GeneratedSources& extra, std::string* error, int* compileCount,
                      int pass = -1);

/// One pass an effect draws, for the catalogue of renderer classes (tests, profiling).
struct PostPassInfo {
    std::string_view name;   ///< e.g. "bright pass"
    std::string_view shader; ///< fragment shader file in resources/shaders/
    int downscale = 1;       ///< 1 full resolution, 2 half, … (0: a chain of mip levels)
};

class FusableEffect;

/// The renderer of one effect type: a SinglePassEffect or FusableEffect built from the catalogue,
/// or a class of its own (render/post_effects/post_<type>.cpp) for effects with several passes
/// or extra inputs (makePostEffect). run()
/// reads @p input and writes @p output (a pooled target or the final framebuffer, same size as
/// the input); temporaries come from ctx.pool.
class PostEffect {
public:
    /// @p type must be in the catalogue (core/post_effects.h).
    explicit PostEffect(std::string_view type);
    virtual ~PostEffect() = default;
    PostEffect(const PostEffect&) = delete;
    PostEffect& operator=(const PostEffect&) = delete;

    const EffectMeta& meta() const { return *m_meta; }
    /// The passes run() draws, in order.
    virtual std::vector<PostPassInfo> passes() const = 0;
    /// Effects whose build() must have run before this one's (depth of field borrows the blur).
    virtual std::vector<std::string_view> dependencies() const { return {}; }
    /// Non-null for pointwise effects: the chain folds consecutive ones into one fused pass.
    virtual const FusableEffect* fusable() const { return nullptr; }
    /// Whether this instance needs last frame's copy of its input (PostContext::previousFrame);
    /// the chain then keeps one pooled target per such effect across frames.
    virtual bool readsPreviousFrame(const EffectInstance& /*effect*/) const { return false; }

    /// Compiles the programs: once before the first run, and again from disk by
    /// PostChainRenderer::reload() (the editor's T). A program that fails keeps its last good
    /// build (ShaderProgram::build), so the effect still draws; false + message (file:line).
    virtual bool build(PostContext& ctx, std::string* error) = 0;
    virtual void run(PostContext& ctx, const EffectInstance& effect, const PostTarget& input,
                     const PostTarget& output) = 0;

private:
    const EffectMeta* m_meta;
};

/// An effect that is one fullscreen pass of resources/shaders/post_<type>.frag with its
/// parameters in uParams[0 …] (catalogue order): every effect that is not pointwise and has no
/// class of its own (pixelation, pointillism, vaporwave, chromatic aberration, sharpen, FXAA) is
/// one, built from its catalogue entry; motion blur derives from it to bind the previous frame.
/// These read neighbouring pixels, so they cannot be fused with their neighbours.
class SinglePassEffect : public PostEffect {
public:
    explicit SinglePassEffect(std::string_view type);
    std::vector<PostPassInfo> passes() const override;
    bool build(PostContext& ctx, std::string* error) override;
    void run(PostContext& ctx, const EffectInstance& effect, const PostTarget& input,
             const PostTarget& output) override;

protected:
    /// Before the draw: binds extra inputs; returns the aux texture (kPostAuxUnit) and sets
    /// @p level (uPass.y). Default: none.
    virtual unsigned bindInputs(PostContext& ctx, const EffectInstance& effect, int& level);
    const std::string& shaderFile() const { return m_shader; }
    ShaderProgram m_program;

private:
    std::string m_shader;
};

/// A pointwise effect (EffectMeta::pointwise: toon, colour grading, vignette, night vision, film
/// grain from the catalogue alone; tone mapping derives from it): its include-only file
/// post_<type>.glsl defines `vec4 post_<type>(vec4 colour, ivec2 px, int base)`
/// reading parameters from uParams[base …]. Consecutive fusable effects are one pass whose main
/// (fusedPassSource) calls each function in chain order; each effect uploads its own uniforms at
/// its base slot. Run alone, the effect is a fused pass of one.
class FusableEffect : public PostEffect {
public:
    explicit FusableEffect(std::string_view type, std::string glslFile = {});
    const FusableEffect* fusable() const override { return this; }
    std::vector<PostPassInfo> passes() const override;

    /// The include-only file defining the function (default "post_<type>.glsl").
    const std::string& glslFile() const { return m_glslFile; }
    /// "post_<type>"
    std::string glslFunction() const;
    /// vec4 slots the effect's uniforms take (one per parameter).
    int slotCount() const { return int(meta().params.size()); }
    /// Whether the function calls displayEncode() (the generated include
    /// "display_encode.glsl", render/display_encoding.h): a fused pass containing it is built
    /// per display encoding.
    virtual bool displayEncodes() const { return false; }
    /// Uploads @p effect's parameters at uParams[base …] of @p program.
    virtual void upload(unsigned program, const EffectInstance& effect, int base) const;

    /// The chain compiles the fused passes (fusedPassSource); this compiles nothing the first
    /// time and, on a reload, rebuilds the effect-alone program if run() built it.
    bool build(PostContext& ctx, std::string* error) override;
    /// The effect alone, as a fused pass of one (compiled on first use).
    void run(PostContext& ctx, const EffectInstance& effect, const PostTarget& input,
             const PostTarget& output) override;

private:
    std::string m_glslFile;
    ShaderProgram m_program; ///< the effect alone
};

/// The generated main of a fused pass: includes each effect's file once and calls the functions
/// in order, effect i reading its parameters from the sum of the slot counts before it.
std::string fusedPassSource(const std::vector<const FusableEffect*>& effects);

/// A new renderer for catalogue type @p type (nullptr for a type not in the catalogue): the
/// effect's class when it has one, else a FusableEffect for a pointwise type and a
/// SinglePassEffect for any other.
std::unique_ptr<PostEffect> makePostEffect(std::string_view type);

/// @name The effects with classes of their own (render/post_effects/post_<type>.cpp): several
/// passes, a shared blur, the previous frame or the OCIO display transform. makePostEffect builds
/// every other catalogue type from its metadata alone.
/// @{
std::unique_ptr<PostEffect> makeBloomEffect();
std::unique_ptr<PostEffect> makeMotionBlurEffect();
std::unique_ptr<PostEffect> makeDepthOfFieldEffect();
std::unique_ptr<PostEffect> makePaintbrushEffect();
std::unique_ptr<PostEffect> makeToneMapEffect();
std::unique_ptr<PostEffect> makeGaussianBlurEffect();
/// @}

} // namespace velvet::render
