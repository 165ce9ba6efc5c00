#include "render/renderer_impl.h"

#include <epoxy/gl.h>
#include <utility>

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
    reflectionSourceFrameBefore = std::exchange(reflectionSourceFrame, -2);
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
    // A split frame draws B into the right of the G-buffer: what it or the frame after it would
    // keep (the screen passes, the background) must not outlive the split.
    splitDrawnOrEnded = fs.splitMaterial.has_value() || lastFrameSplit;
    lastFrameSplit = fs.splitMaterial.has_value();
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
    // Without a material that bends its normal, the programs without the face normal's
    // reconstruction (the same image: gbuffer_read.glsl's geometricHorizon is 1 for them).
    if (isLightView(fs.view) && lights.lightCount() > 0)
        lights.draw(fs.lightPath, fs.width, fs.height, targets.gbuffer().framebuffer(),
                    targets.hdr().framebuffer(), targets.hdr().texture(), emptyVao,
                    frameFeatures(fs).geometricHorizon);
}

namespace {

/// The format of the default framebuffer's colour buffer when it is an 8-bit one (what a
/// window system gives), else 0.
GLenum defaultColorFormat() {
    if (glCheckNamedFramebufferStatus(0, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return 0; // none (a surfaceless context)
    GLint samples = 0, doubleBuffered = 0;
    glGetNamedFramebufferParameteriv(0, GL_SAMPLES, &samples);
    glGetNamedFramebufferParameteriv(0, GL_DOUBLEBUFFER, &doubleBuffered);
    const GLenum buffer = doubleBuffered ? GL_BACK_LEFT : GL_FRONT_LEFT;
    GLint size[4] = {}, type = 0, encoding = 0;
    const GLenum pnames[4] = {
        GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE, GL_FRAMEBUFFER_ATTACHMENT_GREEN_SIZE,
        GL_FRAMEBUFFER_ATTACHMENT_BLUE_SIZE, GL_FRAMEBUFFER_ATTACHMENT_ALPHA_SIZE};
    for (int i = 0; i < 4; ++i)
        glGetNamedFramebufferAttachmentParameteriv(0, buffer, pnames[i], &size[i]);
    glGetNamedFramebufferAttachmentParameteriv(0, buffer, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE,
                                               &type);
    glGetNamedFramebufferAttachmentParameteriv(0, buffer, GL_FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING,
                                               &encoding);
    if (samples > 0 || type != GL_UNSIGNED_NORMALIZED || size[0] != 8 || size[1] != 8 ||
        size[2] != 8 || (size[3] != 8 && size[3] != 0))
        return 0;
    const bool srgb = encoding == GL_SRGB;
    return size[3] ? (srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8) : (srgb ? GL_SRGB8 : GL_RGB8);
}

/// The internal format of @p fbo's first colour attachment; 0 for a multisampled or layered
/// one or one it cannot tell (the inline display step is then not taken).
GLenum targetColorFormat(GLuint fbo) {
    if (fbo == 0)
        return defaultColorFormat();
    GLint samples = 0, type = GL_NONE, name = 0, format = 0;
    glGetNamedFramebufferParameteriv(fbo, GL_SAMPLES, &samples);
    glGetNamedFramebufferAttachmentParameteriv(fbo, GL_COLOR_ATTACHMENT0,
                                               GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (samples > 0 || type == GL_NONE)
        return 0;
    glGetNamedFramebufferAttachmentParameteriv(fbo, GL_COLOR_ATTACHMENT0,
                                               GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
    if (type == GL_TEXTURE) {
        GLint level = 0;
        glGetNamedFramebufferAttachmentParameteriv(fbo, GL_COLOR_ATTACHMENT0,
                                                   GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL, &level);
        GLint layered = 0, target = 0;
        glGetNamedFramebufferAttachmentParameteriv(fbo, GL_COLOR_ATTACHMENT0,
                                                   GL_FRAMEBUFFER_ATTACHMENT_LAYERED, &layered);
        glGetTextureParameteriv(GLuint(name), GL_TEXTURE_TARGET, &target);
        if (layered || target != GL_TEXTURE_2D)
            return 0;
        glGetTextureLevelParameteriv(GLuint(name), level, GL_TEXTURE_INTERNAL_FORMAT, &format);
    } else if (type == GL_RENDERBUFFER) {
        glGetNamedRenderbufferParameteriv(GLuint(name), GL_RENDERBUFFER_INTERNAL_FORMAT, &format);
    }
    return GLenum(format);
}

} // namespace

bool Renderer::Impl::chooseInlineDisplay(const FrameSettings& fs, const FrameBlock& b,
                                         unsigned targetFbo, const DisplayChoice& choice,
                                         bool emission, InlineDisplay& out, bool& failed,
                                         std::string* error) {
    failed = false;
    // Emission, the ground and the local lights add to the scene-linear target after the
    // surfaces (or between them): those frames keep it.
    if (!fs.displayOnly || fs.view != DebugView::Final || !specialisedPrograms || emission ||
        scene.environment.ground != GroundMode::Off || lights.lightCount() != 0 ||
        wantsScreenSpaceReflections(fs)) // the second surfaces pass reads the first's linear image
        return false;
    const GLenum format = targetColorFormat(targetFbo);
    if (format == 0)
        return false;
    out.chain = PostChainRenderer::hasEnabledEffects(scene.post);
    if (out.chain) {
        out.inputs = postInputs(fs, b, targetFbo, choice);
        if (!post.inlineSource(scene.post, out.inputs, out.source))
            return false;
    } else if (!display.inlineSource(choice, out.source)) {
        return false;
    }
    if (!lighting.inlinePrograms(stageBackground(), ibl.specularReady(), frameFeatures(fs),
                                 out.source, mayBuildSpecialised(), out.background, out.surfaces))
        return false;
    // A picture without fine detail under a smooth display step: drawn smaller and upsampled.
    // A sharp HDRI's detail is its texels: screen pixels per texel at the frame's centre (an
    // orthographic camera sees one direction: one colour).
    const float pixelsPerRadian = 0.5f * float(fs.height) * b.projMatrix[1][1];
    const float texelsPerRadian =
        environment && environment->width > 0 ? float(environment->width) / 6.2831853f : 0.0f;
    const float pixelsPerTexel = b.cameraPosition.w > 0.5f ? 1e9f
                                 : texelsPerRadian > 0.0f  ? pixelsPerRadian / texelsPerRadian
                                                           : 0.0f;
    out.smallBackground = nullptr;
    out.downsample = backgroundDownsampleFactor(stageBackground(), ibl.specularReady(),
                                                out.chain ? &scene.post : nullptr, pixelsPerTexel);
    if (out.downsample > 1)
        out.smallBackground =
            lighting.downsampledBackground(stageBackground(), ibl.specularReady(), out.downsample,
                                           out.source, mayBuildSpecialised());
    // The HDRI's dome (render/background_dome.h): where the smaller picture would do, under a
    // perspective camera, with a display step of the colour alone and a cache of the HDRI's
    // size that the frame magnifies; and in a frame without time to spare: the view at rest
    // (sampled reflections) keeps the smaller picture, which is closer to the full-size pass.
    out.cacheBackground = nullptr;
    if (out.smallBackground && fs.reflectionSamples == 0 && b.cameraPosition.w < 0.5f &&
        pixelsPerTexel >= 1.0f &&
        backgroundDomeApplies(stageBackground(), out.chain ? &scene.post : nullptr) &&
        environment->width * BackgroundDome::kCacheScale <= 4096 &&
        environment->height * BackgroundDome::kCacheScale <= 2048 && environment->height > 0) {
        out.cacheBackground = lighting.equirectBackground(stageBackground(), ibl.specularReady(),
                                                          out.source, mayBuildSpecialised());
        out.cacheWidth = environment->width * BackgroundDome::kCacheScale;
        out.cacheHeight = environment->height * BackgroundDome::kCacheScale;
    }
    out.width = fs.width;
    out.height = fs.height;
    // The surfaces' pass shades only where the mesh is (its depth test), but llvmpipe still
    // tests every block of the frame: scissored to the mesh's rectangle it visits only those.
    out.scissored = stage.meshRectangle(b.viewProjMatrix, fs.width, fs.height, out.meshRect);
    out.framebuffer = targets.displayFramebuffer(format, error);
    failed = out.framebuffer == 0;
    return !failed;
}

bool Renderer::Impl::steadySince(std::uint64_t& uploadedAsOf) {
    const std::uint64_t uploaded = textures.uploadStats().bytes;
    const bool steady = !splitDrawnOrEnded && textures.progress().loading == 0 &&
                        uploaded == uploadedAsOf && !structureAdoptedThisFrame;
    uploadedAsOf = uploaded;
    return steady;
}

FrameKey Renderer::Impl::screenPassKey(const FrameSettings& fs, const FrameBlock& b) {
    if (!steadySince(screenPassUploadedBytes))
        stage.invalidateScreenPasses();
    FrameKey key;
    key.add(b.viewMatrix).add(b.projMatrix).add(fs.width).add(fs.height);
    // sheenWeightAnisotropy.w: the shading normal varies per pixel (a normal map, a graph's).
    if (packedA.sheenWeightAnisotropy.w > 0.5f)
        key.add(packedA);
    return key;
}

bool Renderer::Impl::drawStageScreenPasses(const FrameSettings& fs, const FrameBlock& block,
                                           std::string* error) {
    // Screen-space occlusion of the G-buffer, at the stage's downsample (off: nothing runs).
    targets.gbuffer().bindTextures();
    // One key for both screen-space passes: it also notes what no key sees (screenPassKey).
    const FrameKey screenKey = screenPassKey(fs, block);
    // Both passes take the face's normal, not the bent one, for the materials that bend theirs.
    const bool bentNormals = frameFeatures(fs).geometricHorizon;
    if (!stage.drawOcclusion(scene.environment, block.viewProjMatrix, fs.width, fs.height,
                             bentNormals, screenKey, emptyVao, error))
        return false;
    // The screen-space shadow mask: every shadowed light's visibility per pixel, which the
    // lighting passes read instead of filtering the maps themselves (render/shadow_mask.h).
    unsigned maskFbo = 0;
    if (stage.hasShadows() && !(maskFbo = targets.shadowMaskFramebuffer(stage.downsample(), error)))
        return false;
    stage.drawShadowMask(maskFbo, targets.shadowMask().texture(), targets.shadowKey().texture(),
                         targets.groundShadowMask().texture(), scene.environment,
                         block.viewProjMatrix, fs.width, fs.height, screenKey, emptyVao,
                         fs.settleShadows, bentNormals);
    return true;
}

bool Renderer::Impl::keepsGBuffer(const FrameSettings& fs, const FrameBlock& b,
                                  unsigned framebuffer, bool emission, bool lobeTargets) {
    const bool steady = steadySince(gbufferUploadedBytes);
    const bool valuesFromTable = (packedA.terms2.y & kRecordValuesPerMaterial) != 0 &&
                                 packedGraphFields.empty() && !hasLobeMap(packedA) &&
                                 packedA.sheenWeightAnisotropy.w < 0.5f;
    const bool alone = !fs.splitMaterial && scene.environment.ground == GroundMode::Off;
    // The specialised G-buffer program compiles the mesh's visibility out when it has none
    // (FIXED_MESH_VISIBILITY 0): the specular occlusion is then the material occlusion, 1.
    const bool eligible = fs.keepGBuffer && steady && valuesFromTable && alone && !emission &&
                          !lobeTargets && gbufferSpecialised && !mesh->gpu.hasVisibility();
    if (!eligible) {
        gbufferReuse.invalidate();
        return false;
    }
    FrameKey key;
    key.add(b.viewMatrix).add(b.projMatrix).add(fs.width).add(fs.height).add(framebuffer);
    key.add(packedA.terms2).add(mesh);
    return gbufferReuse.reuse(std::move(key));
}

bool Renderer::Impl::keepsBackground(const FrameSettings& fs, const FrameBlock& b,
                                     const IblBlock& ibl, const InlineDisplay& d,
                                     unsigned targetFbo) {
    // What the key cannot see (frame_reuse.h): a split frame's B, textures arriving (a
    // cut-out changes the coverage), the bake's slices, a graph structure adopted this frame.
    const bool steady = steadySince(uploadedBytes) && ibl.state.x > 0.5f;
    if (!steady)
        backgroundReuse.invalidate();
    IblBlock keyed = ibl;
    const bool readsTime = b.modes.w == 3 || // the procedural background moves with the time
                           (d.chain && postChainReadsTime(scene.post)); // grain, static
    if (!readsTime)
        keyed.background.y = 0.0f;
    keyed.reflection = glm::vec4(0.0f); // the background reads no reflection
    FrameKey key;
    key.add(b).add(keyed).add(d.framebuffer).add(targetFbo).add(fs.width).add(fs.height);
    key.add(fs.exposureEv).add(d.background->id()).add(d.chain).add(d.source.key);
    key.add(d.smallBackground ? d.smallBackground->id() : 0u);
    key.add(fs.display).add(fs.displayView).add(fs.look);
    return backgroundReuse.reuse(std::move(key)) && steady;
}

FrameKey Renderer::Impl::backgroundCacheKey(const FrameSettings& fs, const FrameBlock& b,
                                            const IblBlock& ibl, const InlineDisplay& d) {
    // keepsBackground()'s key without the camera's pose and the lights (the dome turns the
    // picture with the view), nor the time (no effect that reads it applies).
    FrameBlock keyedFrame = b;
    keyedFrame.viewMatrix = keyedFrame.projMatrix = keyedFrame.invProjMatrix =
        keyedFrame.invViewMatrix = keyedFrame.viewProjMatrix = glm::mat4(0.0f);
    keyedFrame.cameraPosition = keyedFrame.viewport = glm::vec4(0.0f);
    for (glm::vec4& v : keyedFrame.envSh)
        v = glm::vec4(0.0f);
    for (int i = 0; i < kMaxDirectionalLights; ++i)
        keyedFrame.lightDirection[i] = keyedFrame.lightRadiance[i] = glm::vec4(0.0f);
    keyedFrame.modes.x = 0;   // the directional lights' count
    keyedFrame.post.y = 0.0f; // the camera's distance
    IblBlock keyedIbl = ibl;
    keyedIbl.background.y = 0.0f;
    keyedIbl.reflection = glm::vec4(0.0f);
    FrameKey key;
    key.add(keyedFrame).add(keyedIbl).add(environment->texture).add(environment->key);
    key.add(fs.exposureEv).add(d.cacheBackground->id()).add(d.chain).add(d.source.key);
    key.add(fs.display).add(fs.displayView).add(fs.look);
    return key;
}

void Renderer::Impl::drawInlineDisplay(const InlineDisplay& d, bool keepBackground) {
    // The programs the display step's inputs are bound on (the smaller background's and the
    // dome cache's too).
    std::vector<unsigned> programs{d.background->id(), d.surfaces->id()};
    if (d.smallBackground)
        programs.push_back(d.smallBackground->id());
    if (d.cacheBackground)
        programs.push_back(d.cacheBackground->id());
    if (d.chain)
        post.bindInline(scene.post, d.inputs, programs);
    else
        display.bindInline(programs);
    if (!keepBackground) {
        // The dome where it applies; else the smaller picture upsampled; the full-size pass
        // where their targets cannot be made.
        std::string error;
        bool cacheDrawn = false;
        if (d.cacheBackground &&
            backgroundDome.draw(*d.cacheBackground, d.cacheWidth, d.cacheHeight, d.cacheKey,
                                d.framebuffer, d.width, d.height, &cacheDrawn, &error)) {
            passes.backgroundDome = true;
            passes.backgroundCacheDrawn = cacheDrawn;
            glBindVertexArray(emptyVao); // the surfaces' full-screen triangle
        } else if (!d.smallBackground ||
                   !backgroundDownsample.draw(*d.smallBackground, d.downsample, d.framebuffer,
                                              d.width, d.height, &error)) {
            lighting.drawBackground(*d.background);
        }
    }
    if (d.scissored) {
        glEnable(GL_SCISSOR_TEST);
        glScissor(d.meshRect[0], d.meshRect[1], d.meshRect[2], d.meshRect[3]);
    }
    lighting.drawSurfaces(*d.surfaces, /*emission=*/false, /*displayValues=*/true);
    glDisable(GL_SCISSOR_TEST);
    if (d.chain)
        post.unbindInline();
    else
        display.unbindInline();
}

bool Renderer::Impl::drawLitPasses(const FrameSettings& fs, const FrameBlock& block, bool emission,
                                   const ShaderProgram& surfaceProgram, std::string* error) {
    if (!emission) // nothing in the HDR target yet: start from black, opaque
        glClearBufferfv(GL_COLOR, 0, kNoEmission);
    if (fs.view == DebugView::Final) { // debug views: no background (the HDR target is black)
        lighting.drawBackground(scene.environment.background, ibl.specularReady());
        ++passes.fullScreen;
    }
    // With a shadow catcher only the mesh's rectangle needs the surface shading (render/stage.h).
    int meshRect[4];
    const bool scissored = scene.environment.ground == GroundMode::ShadowCatcher &&
                           stage.meshRectangle(block.viewProjMatrix, fs.width, fs.height, meshRect);
    if (scissored) {
        glEnable(GL_SCISSOR_TEST);
        glScissor(meshRect[0], meshRect[1], meshRect[2], meshRect[3]);
    }
    bool reflected = false;
    if (wantsScreenSpaceReflections(fs) &&
        !drawReflectingSurfaces(fs, emission, surfaceProgram, reflected, error))
        return false;
    if (reflected) {
        passes.fullScreen += 2;
        passes.screenSpaceReflections = true;
    } else {
        lighting.drawSurfaces(surfaceProgram, emission);
        ++passes.fullScreen;
    }
    glDisable(GL_SCISSOR_TEST);
    if (fs.view == DebugView::Final && scene.environment.ground == GroundMode::ShadowCatcher) {
        if (!lighting.drawCatcher(emission, stageBackground(), error, // its own variant
                                  frameFeatures(fs), mayBuildSpecialised()))
            return false;
        ++passes.fullScreen;
    }
    passes.linear = true;
    return true;
}

bool Renderer::Impl::drawReflectingSurfaces(const FrameSettings& fs, bool emission,
                                            const ShaderProgram& surfaceProgram, bool& drawn,
                                            std::string* error) {
    drawn = false;
    // The final image's surface program specialised to @p f, or null (a failure, in @p error);
    // @p specialised false when it is the generic one (not built yet, or its build failed).
    bool specialised = false;
    auto programFor = [&](const LightingFeatures& f) {
        const ShaderProgram* p = lighting.surfaceProgram(
            fs.view, error, scene.environment.ground, stageBackground(), f, mayBuildSpecialised());
        specialised = p && lighting.lastWasSpecialised();
        return p;
    };
    LightingFeatures features = frameFeatures(fs);
    features.screenSpaceReflections = true;
    const ShaderProgram* reflecting = programFor(features);
    if (!reflecting)
        return false;
    if (!specialised) // the plain surfaces this frame
        return true;
    // The first pass only lights what the rays meet: by the split sum, which costs a sixteenth of
    // the sampled lobe's lookups (the reflection the ray meets is seen from another angle anyway).
    features.screenSpaceReflections = false;
    features.sampledReflections = false;
    const ShaderProgram* source = programFor(features);
    if (!source)
        return false;
    if (!specialised)
        source = &surfaceProgram;
    const GLuint sourceFbo = targets.reflectionSourceFramebuffer(error);
    if (!sourceFbo)
        return false;
    const ColorTarget& hdr = targets.hdr();
    const ColorTarget& light = targets.reflectionSource();
    // A frame of the progressive mean after the first reads the frame before's light (the same
    // view but for a sub-pixel jitter): the frame's own light and one more bounce, for no first
    // pass.
    const bool reused =
        accumulationIndex >= 1 && reflectionSourceFrameBefore == accumulationIndex - 1;
    auto copyHdrToSource = [&] {
        glCopyImageSubData(hdr.texture(), GL_TEXTURE_2D, 0, 0, 0, 0, light.texture(), GL_TEXTURE_2D,
                           0, 0, 0, 0, hdr.width(), hdr.height(), 1);
    };
    if (!reused) {
        // The first pass over what the HDR target holds so far (the background, the emission),
        // so that its image is the frame's but for the traced light.
        copyHdrToSource();
        glBindFramebuffer(GL_FRAMEBUFFER, sourceFbo);
        lighting.drawSurfaces(*source, emission);
        glBindFramebuffer(GL_FRAMEBUFFER, targets.litFramebuffer());
    }
    glBindTextureUnit(binding::kHdrTex, light.texture());
    lighting.drawSurfaces(*reflecting, emission);
    glBindTextureUnit(binding::kHdrTex, 0);
    // This frame's light for the mean's next frame.
    if (accumulationIndex >= 0) {
        copyHdrToSource();
        reflectionSourceFrame = accumulationIndex;
    }
    passes.reflectionSourceReused = reused;
    drawn = true;
    return true;
}

PostRunInputs Renderer::Impl::postInputs(const FrameSettings& fs, const FrameBlock& b,
                                         unsigned targetFbo, const DisplayChoice& choice) {
    PostRunInputs in;
    in.hdrTexture = targets.hdr().texture();
    in.width = fs.width;
    in.height = fs.height;
    in.viewProj = b.viewProjMatrix;
    in.proj = b.projMatrix;
    // The last camera seen through this frame's jitter (both unjittered): the refinement's
    // sub-pixel offsets are no camera motion for the motion blur.
    const glm::mat4 jitter = jitterMatrix(fs.jitter, fs.width, fs.height);
    in.prevViewProj = fs.hasPreviousViewProj ? jitter * fs.previousViewProj
                      : haveLastViewProj     ? jitter * lastViewProj
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
    return in;
}

bool Renderer::Impl::runPost(const FrameSettings& fs, const FrameBlock& b, unsigned targetFbo,
                             const DisplayChoice& choice, unsigned& finalInput, bool& displayed,
                             std::string* error) {
    targets.gbuffer().bindTextures(); // depth and normals for motion blur, DoF, toon, vaporwave
    const PostRunInputs in = postInputs(fs, b, targetFbo, choice);
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
    inner.accumulation = -1; // a reduced frame is drawn alone (FrameSettings::accumulation)
    inner.jitter = glm::vec2(0.0f);
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

bool Renderer::Impl::renderAccumulated(Renderer& self, const FrameSettings& fs, unsigned targetFbo,
                                       std::string* error) {
    const auto start = std::chrono::steady_clock::now();
    FrameSettings inner = fs;
    inner.accumulation = -1;
    accumulationIndex = fs.accumulation;
    const bool drawn = accumulationFrame.resize(fs.width, fs.height, GL_RGBA8, error) &&
                       self.render(inner, accumulationFrame.framebuffer(), error);
    accumulationIndex = -1;
    if (!drawn || !accumulation.add(accumulationFrame, fs.accumulation == 0, emptyVao, error))
        return false;
    accumulation.present(targetFbo);
    finishFrame(targetFbo, fs, start);
    if (const std::string e = takeGlErrors(); !e.empty())
        return fail(error, "OpenGL error while averaging anti-aliasing frames: " + e);
    return true;
}

} // namespace velvet::render
