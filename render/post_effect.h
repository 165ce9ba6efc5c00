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
};

/// Uploads @p effect's parameters into uParams[base …] of @p program (catalogue order).
void setEffectParams(unsigned program, const EffectMeta& meta, const EffectInstance& effect,
                     int base);
/// Binds @p output, sets the viewport, uPass and uTexel (from @p input's size) and draws the
/// fullscreen triangle with @p program; @p input on kPostInputUnit, @p aux on kPostAuxUnit.
void drawPostPass(const PostContext& ctx, unsigned program, const PostTarget& input,
                  const PostTarget& output, int pass, int level = 0, unsigned aux = 0);
/// Builds @p program from fullscreen.vert + @p fragment with the post includes.
/// @p pass >= 0 defines POST_PASS (one program per pass of a multi-pass effect).
bool buildPostProgram(ShaderProgram& program, const std::string& fragment,
                      const GeneratedSources& extra, std::string* error, int* compileCount,
                      int pass = -1);

/// One effect type. run() reads @p input and writes @p output (a pooled target or the final
/// framebuffer, same size as the input); temporaries come from ctx.pool.
class PostEffect {
public:
    virtual ~PostEffect() = default;
    /// Compiles the programs; called once, before the first run.
    virtual bool build(PostContext& ctx, std::string* error) = 0;
    virtual void run(PostContext& ctx, const EffectInstance& effect, const PostTarget& input,
                     const PostTarget& output) = 0;
};

/// @name The effects with their own class (render/post_<type>.cpp). Pointwise effects (tone map,
/// colour grading, toon, vignette, night vision, film grain) are shader functions fused into
/// one pass by render/post_chain.cpp.
/// @{
std::unique_ptr<PostEffect> makeBloomEffect();
std::unique_ptr<PostEffect> makeGaussianBlurEffect();
std::unique_ptr<PostEffect> makeDepthOfFieldEffect();
std::unique_ptr<PostEffect> makePaintbrushEffect();
/// Single-pass effects: pixelate, motion_blur, pointillism, vaporwave, chromatic_aberration,
/// sharpen, fxaa (render/post_single_pass.cpp).
std::unique_ptr<PostEffect> makeSinglePassEffect(std::string_view type);
/// @}

} // namespace velvet::render
