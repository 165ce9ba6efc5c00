#include "render/renderer_impl.h"

#include <epoxy/gl.h>

namespace velvet::render {
namespace {

/// IBL bake time allowed at the start of a frame (render/ibl_bake.h adapts its slices to
/// IblBakeOptions::sliceTargetMs; a frame may run one slice past this).
constexpr double kIblFrameBudgetMs = 12.0;

} // namespace

Renderer::Impl::~Impl() {
    if (emptyVao)
        glDeleteVertexArrays(1, &emptyVao);
    if (queries[0])
        glDeleteQueries(4, queries);
    if (lightsQuery)
        glDeleteQueries(1, &lightsQuery);
}

TextureSet& Renderer::Impl::splitTextures(const Material& b) {
    Problems problems;
    if (!texturesB) {
        texturesB = std::make_unique<TextureSet>();
        texturesB->setColorManagement(colorManagement ? colorManagement : display.sharedConfig());
        texturesB->setAsync(textures.async());
        texturesB->setUploadBudget(textures.uploadBudget());
    }
    std::array<TextureRef, kTextureSlotCount> refs;
    for (int i = 0; i < kTextureSlotCount; ++i)
        refs[size_t(i)] = b.texture(TextureSlot(i));
    if (refs != texturesBRefs) {
        texturesB->setMaterial(b, &problems);
        texturesBRefs = std::move(refs);
    }
    texturesB->poll();
    for (Problem& p : problems.items)
        lobeWarnings.items.push_back(std::move(p));
    for (Problem& p : texturesB->takeProblems().items)
        lobeWarnings.items.push_back(std::move(p));
    return *texturesB;
}

bool Renderer::Impl::prepareFrame(const FrameSettings& fs, unsigned targetFbo,
                                  DisplayChoice& choice, const ShaderProgram*& surfaceProgram,
                                  std::string* error) {
    // A texture file changed on disk (edited in another program): re-upload, re-pack the record.
    if (textures.poll()) {
        ++uploads.textureSlotRefreshes;
        uploadMaterial();
    }
    // A structural graph edit: start the new G-buffer program, or adopt it once the driver's
    // compiler threads have finished (GL_KHR_parallel_shader_compile); meanwhile this frame
    // draws the old program, so the window never waits for a compile. Without the extension the
    // build completes here (the frame waits, as before). A failure keeps the old program
    // (graphError()).
    const int graphBuilds = graph.compileCount();
    graph.buildPending(textures.sharedCache());
    structureAdoptedThisFrame = graph.compileCount() != graphBuilds;
    if (graph.writtenFields() != packedGraphFields)
        uploadMaterial(); // the program now drawing writes other fields: a new lobe map
    graph.refreshTextures(textures.sharedCache(), nullptr); // files changed on disk re-upload
    // lighting.frag's variant for this view (built the first time a debug family is shown).
    // The ground's variants look the background up with its mode compiled in (Blurred only once
    // the prefiltered cube is ready, as the background pass does).
    surfaceProgram =
        lighting.surfaceProgram(fs.view, error, scene.environment.ground, stageBackground());
    if (!surfaceProgram)
        return false;
    // An unknown display, view or look fails here, before anything is drawn. A tone-mapping view
    // (or a look) is OCIO's alone; otherwise the built-in curve runs and OCIO's shader for the
    // display's un-tone-mapped view encodes (debug views use that encoding too).
    if (!display.choose(fs, choice, error))
        return false;
    // Every frame (a stat of the HDRI): an HDRI edited on disk is read and prefiltered again.
    const GpuEnvironment* current =
        &environments.get(scene.environment, nullptr, ibl.cacheSignature());
    if (current != environment)
        ++uploads.environmentRequests; // read again: a new entry
    environment = current;
    // Environment prefiltering: a few slices per frame (render/ibl_bake.h).
    ibl.request(*environment);
    const auto iblStart = std::chrono::steady_clock::now();
    ibl.step(kIblFrameBudgetMs);
    timings.iblMs = msSince(iblStart);
    if (!targets.resize(fs.width, fs.height, compactGBuffer, error))
        return false;
    if (targetFbo != 0) {
        const GLenum status = glCheckNamedFramebufferStatus(targetFbo, GL_DRAW_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            return fail(error, "target framebuffer " + std::to_string(targetFbo) +
                                   " is incomplete: " + framebufferStatusName(status));
    }
    return true;
}

void Renderer::Impl::uploadLights(Problems* problems) {
    ++uploads.lightUploads;
    planStage(problems);
    if (!problems)
        return;
    // The full-screen pass has a fixed array of directional lights (MAX_LIGHTS in
    // render_interface.glsl); makeFrameBlock() draws the first kMaxDirectionalLights and drops the
    // rest.
    int directional = 0;
    for (size_t i = 0; i < scene.lights.size(); ++i)
        if (scene.lights[i].type == LightType::Directional && ++directional > kMaxDirectionalLights)
            problems->warning("", "lights[" + std::to_string(i) + "]",
                              "directional light " + std::to_string(directional) +
                                  " is not drawn: the renderer draws the first " +
                                  std::to_string(kMaxDirectionalLights) +
                                  " directional lights only");
}

void Renderer::Impl::drawLocalLights(const FrameSettings& fs) {
    if (isLightView(fs.view))
        lights.draw(fs.lightPath, fs.width, fs.height, targets.gbuffer().framebuffer(),
                    targets.hdr().framebuffer(), targets.hdr().texture(), emptyVao);
}

bool Renderer::Impl::runPost(const FrameSettings& fs, const FrameBlock& b, unsigned targetFbo,
                             const DisplayChoice& choice, unsigned& finalInput, bool& displayed,
                             std::string* error) {
    targets.gbuffer().bindTextures(); // depth and normals for motion blur, DoF, toon, vaporwave
    PostRunInputs in;
    in.hdrTexture = targets.hdr().texture();
    in.width = fs.width;
    in.height = fs.height;
    in.viewProj = b.viewProjMatrix;
    in.proj = b.projMatrix;
    in.prevViewProj = fs.hasPreviousViewProj ? fs.previousViewProj
                      : haveLastViewProj     ? lastViewProj
                                             : b.viewProjMatrix;
    in.time = fs.time;
    in.exposureEv = fs.exposureEv;
    // The built-in curve as the tonemap effect's operator, looked up by name in the catalogue.
    in.implicitToneMapper =
        std::max(0, toneMapOperatorIndex(fs.toneMapper == ToneMapper::AcesFitted ? "aces"
                                         : fs.toneMapper == ToneMapper::Reinhard ? "reinhard"
                                         : fs.toneMapper == ToneMapper::Linear   ? "linear"
                                                                                 : "pbr-neutral"));
    const bool ocioAll = choice.ocioToneMaps;
    in.forceDisplayTransform = ocioAll;
    in.encoding = &display.encoding();
    in.displayTransform = [this, &fs, ocioAll](unsigned texture, float ev, std::string* err) {
        // The "display" operator with an encoding-only view: the full transform of fs.
        if (!ocioAll && !display.selectDisplayTransform(fs, err))
            return false;
        display.transform().draw(texture, fs.exposureEv + ev);
        return true;
    };
    in.finalFbo = targetFbo;
    PostRunResult r;
    if (!post.run(scene.post, in, r, error))
        return false;
    displayed = r.displayEncoded;
    if (!displayed)
        finalInput = r.hdrTexture;
    return true;
}

bool Renderer::Impl::renderScaled(Renderer& self, const FrameSettings& fs, unsigned targetFbo,
                                  std::string* error) {
    const auto start = std::chrono::steady_clock::now();
    FrameSettings inner = fs;
    inner.renderScale = 1.0f;
    inner.width = std::max(1, int(std::lround(float(fs.width) * fs.renderScale)));
    inner.height = std::max(1, int(std::lround(float(fs.height) * fs.renderScale)));
    if (!scaled.resize(inner.width, inner.height, GL_RGBA8, error) ||
        !self.render(inner, scaled.framebuffer(), error))
        return false;
    glBlitNamedFramebuffer(scaled.framebuffer(), targetFbo, 0, 0, inner.width, inner.height, 0, 0,
                           fs.width, fs.height, GL_COLOR_BUFFER_BIT, GL_LINEAR);
    glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);
    finishFrame(targetFbo, fs, start);
    if (const std::string e = takeGlErrors(); !e.empty())
        return fail(error, "OpenGL error while stretching a reduced frame: " + e);
    return true;
}

} // namespace velvet::render
