#include "render/renderer.h"

#include "render/gbuffer_layout.h"
#include "render/renderer_impl.h"
#include "render/texture_storage_thread.h"

#include <epoxy/gl.h>

namespace velvet::render {

Renderer::Renderer() : m_impl(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

bool Renderer::initialize(std::string* error) {
    Impl& d = *m_impl;
    if (d.initialized)
        return true;
    if (epoxy_gl_version() < 45)
        return fail(error, "OpenGL 4.5 core is needed; the current context is " +
                               std::string(reinterpret_cast<const char*>(glGetString(GL_VERSION))));
    takeGlErrors();
    d.parallelShaderCompile = enableParallelShaderCompile();
    d.graph.start(d.scene.material);
    if (!d.buildPrograms(error))
        return false;
    // The default display's tone-map program too, so that the first frame and every value edit
    // after it compile nothing (the encoding comes from the config, loaded here if none is set).
    if (!d.display.initialize(error))
        return false;
    // The texture slots look their input colour spaces up in the same config, loaded once.
    if (!d.colorManagement)
        d.textures.setColorManagement(d.display.sharedConfig());
    d.uniforms.initialize();
    glCreateVertexArrays(1, &d.emptyVao);
    glCreateQueries(GL_TIMESTAMP, 4, d.queries);
    glCreateQueries(GL_TIMESTAMP, 1, &d.lightsQuery);
    if (!d.lights.initialize(error) || !d.stage.initialize(error))
        return false;
    d.packedGround = groundMaterial(d.scene.environment);
    if (d.haveScene)
        d.uploadLights(nullptr);
    if (!d.ibl.initialize(error))
        return false;
    d.selectMesh(nullptr);
    d.refreshTextureSlots(nullptr);
    d.uploadMaterial();
    d.graph.uploadValues();
    d.graph.refreshTextures(d.textures.sharedCache(), nullptr);
    if (const std::string e = takeGlErrors(); !e.empty())
        return fail(error, "OpenGL error while creating renderer resources: " + e);
    d.initialized = true;
    if (!d.haveScene)
        setScene(Scene{});
    return true;
}

bool Renderer::reloadShaders(std::string* error) {
    Impl& d = *m_impl;
    if (!d.initialized)
        return fail(error, "Renderer::reloadShaders called before initialize()");
    d.backgroundReuse.invalidate();
    d.gbufferReuse.invalidate();
    d.stage.invalidateScreenPasses();
    // Every program from disk; each failure keeps its last good program and adds its message.
    std::string errors;
    auto collect = [&](bool ok, const std::string& message) {
        if (!ok)
            errors += (errors.empty() ? "" : "\n") + message;
    };
    std::string message;
    collect(d.buildPrograms(&message, /*keepGoing=*/true), message);
    collect(d.lights.reload(&message), message);
    collect(d.stage.reload(&message), message);
    collect(d.ibl.reload(&message), message);
    collect(d.display.reload(&message), message);
    collect(d.post.reload(&message), message); // counted by shaderCompileCount() through post
    if (!errors.empty())
        return fail(error, errors);
    return true;
}

void Renderer::setColorManagement(std::shared_ptr<const ColorManagement> colorManagement) {
    Impl& d = *m_impl;
    d.backgroundReuse.invalidate();
    d.backgroundDome.invalidate();    // the display's config
    d.stage.invalidateScreenPasses(); // the textures are taken again
    d.colorManagement = std::move(colorManagement);
    d.display.setColorManagement(d.colorManagement);
    // Input colour space names are looked up in the new config too (without one, in the
    // display's default, loaded once by the display at initialize()).
    d.textures.setColorManagement(d.colorManagement || !d.initialized ? d.colorManagement
                                                                      : d.display.sharedConfig());
    d.texturesDropped();
}

void Renderer::setScene(const Scene& scene, Problems* problems) {
    update(scene, ScenePart::All, problems);
}

void Renderer::update(const Scene& scene, ScenePart parts, Problems* problems) {
    Impl& d = *m_impl;
    copyParts(d.scene, scene, parts);
    d.haveScene = true;
    // A value edit leaves the background and the coverage as they were; anything else may not
    // (a texture slot's cut-out, the mesh, the environment: render/frame_reuse.h).
    if (touches(parts, ~ScenePart::MaterialValues)) {
        d.backgroundReuse.invalidate();
        d.gbufferReuse.invalidate();
    }
    // The dome's cache keys the environment's and the display's values but not the post chain's
    // parameters (uniforms) nor an HDRI file replaced under the same name.
    if (touches(parts, ScenePart::Environment | ScenePart::PostChain))
        d.backgroundDome.invalidate();
    // The occlusion and the shadow mask read the depth and the normals: the mesh, the textures
    // and the graph move them without their keys seeing it (the camera, the ground, the lights
    // and the material's values they see).
    if (touches(parts, ScenePart::Mesh | ScenePart::MaterialStructure | ScenePart::Graph |
                           ScenePart::Atlases))
        d.stage.invalidateScreenPasses();
    if (!d.initialized)
        return; // uploaded by initialize()
    if (touches(parts, ScenePart::Mesh))
        d.selectMesh(problems);
    if (touches(parts, ScenePart::MaterialStructure))
        d.refreshTextureSlots(problems);
    // Numbers only: rewrite the material table (never a shader; the next frame builds no
    // lighting variant either: LightingPass::surfaceProgram).
    if (touches(parts, ScenePart::MaterialStructure | ScenePart::MaterialValues))
        d.uploadMaterial();
    if (touches(parts, ScenePart::MaterialValues) && !touches(parts, ScenePart::MaterialStructure))
        d.valueEditSinceFrame = true; // a structural change (setScene) may compile
    // The graph: values and textures now, a new structure at the next render().
    if (touches(parts, ScenePart::Graph))
        d.graph.setGraph(d.scene.material, d.textures.sharedCache(), problems);
    if (touches(parts, ScenePart::Lights))
        d.uploadLights(problems);
    if (touches(parts, ScenePart::Environment)) {
        d.requestEnvironment(problems);
        d.uploadGround(); // the ground's colour and roughness (no count: not the material)
    }
    // PostChain: PostChainRenderer::run reads scene.post at each frame, nothing to upload.
    // Camera: the stored camera is all (makeFrameBlock reads it when FrameSettings::camera is
    // unset). Atlases: nothing in the renderer today — atlas regions reach it as texture slots
    // (MaterialStructure), and scene.atlases only names the document the editor loads.
}

Problems Renderer::takeWarnings() {
    Problems p = m_impl->display.takeWarnings();
    for (Problem& w : std::exchange(m_impl->lobeWarnings, Problems{}).items)
        p.items.push_back(std::move(w));
    for (Problem& t : m_impl->textures.takeProblems().items)
        p.items.push_back(std::move(t));
    return p;
}

void Renderer::setCompactGBuffer(bool compact) {
    Impl& d = *m_impl;
    if (compact == d.compactGBuffer)
        return;
    d.compactGBuffer = compact;
    if (d.initialized)
        d.uploadMaterial(); // every lobe per material, or mapped again; targets follow next frame
}

bool Renderer::compactGBuffer() const {
    return m_impl->compactGBuffer;
}

void Renderer::setSpecialisedPrograms(bool on) {
    m_impl->specialisedPrograms = on;
    m_impl->post.setSpecialiseOperators(on);
}

bool Renderer::lastFrameSpecialised() const {
    return m_impl->lighting.lastWasSpecialised();
}

int Renderer::lightingSpecialisationFailures() const {
    return m_impl->lighting.specialisationFailures();
}

bool Renderer::specialisationPending() const {
    return m_impl->lighting.lastDeferred() || m_impl->geometryDeferred;
}

std::string Renderer::lightingSpecialisationError() const {
    return m_impl->lighting.lastSpecialisationError();
}

void Renderer::setAsyncMeshBake(bool async) {
    m_impl->meshes.setAsyncBake(async);
}

bool Renderer::meshBakePending() const {
    return m_impl->meshes.bakePending();
}

void Renderer::setAsyncTextures(bool async) {
    Impl& d = *m_impl;
    if (async == d.textures.async())
        return;
    d.textures.setAsync(async);
    d.texturesDropped();
}

void Renderer::setTextureStorageContext(std::unique_ptr<WorkerGlContext> context) {
    m_impl->textures.setStorageContext(std::move(context));
    m_impl->texturesDropped();
}

void Renderer::setTextureUploadBudget(std::uint64_t bytes) {
    m_impl->textures.setUploadBudget(bytes);
}

TextureLoadProgress Renderer::textureProgress() const {
    TextureLoadProgress p = m_impl->textures.progress();
    if (m_impl->texturesB) { // the A/B split's B loads its own files
        const TextureLoadProgress b = m_impl->texturesB->progress();
        p.loading += b.loading;
        p.total += b.total;
        p.fraction = std::min(p.fraction, b.fraction);
    }
    return p;
}

void Renderer::finishTextures() {
    Impl& d = *m_impl;
    if (!d.initialized)
        return;
    d.textures.finish();
    d.uploadMaterial();
}

const TextureUploadStats& Renderer::textureUploadStats() const {
    return m_impl->textures.uploadStats();
}

std::uint64_t Renderer::textureDecodes() const {
    return m_impl->textures.decodeCount();
}

std::uint64_t Renderer::textureCacheHits() const {
    return m_impl->textures.cacheHits();
}

UploadStats Renderer::uploadStats() const {
    UploadStats s = m_impl->uploads;
    s.graphCompiles = m_impl->graph.graphCompiles();
    s.graphValueUploads = m_impl->graph.valueUploads();
    return s;
}

bool Renderer::render(const FrameSettings& fs, unsigned targetFbo, std::string* error) {
    Impl& d = *m_impl;
    if (!d.initialized)
        return fail(error, "Renderer::render called before initialize()");
    d.meshes.adoptBakes(); // a mesh's visibility baked on a worker since the last frame
    if (fs.width <= 0 || fs.height <= 0 || fs.width > 16384 || fs.height > 16384)
        return fail(error, "invalid frame size " + std::to_string(fs.width) + "x" +
                               std::to_string(fs.height));
    if (fs.renderScale > 0.0f && fs.renderScale < 1.0f)
        return d.renderScaled(*this, fs, targetFbo, error);
    if (fs.accumulation >= 0)
        return d.renderAccumulated(*this, fs, targetFbo, error);
    const auto cpuStart = std::chrono::steady_clock::now();
    takeGlErrors(); // errors left by whoever owns the context are not ours
    DisplayChoice display;
    const ShaderProgram* surfaceProgram = nullptr;
    if (!d.prepareFrame(fs, targetFbo, display, surfaceProgram, error))
        return false;

    // The per-frame camera (an orbit) or the scene's.
    FrameBlock block =
        makeFrameBlock(d.scene, fs.camera ? *fs.camera : d.scene.camera, *d.environment, fs);
    d.stage.annotate(block, d.scene.lights); // which directional lights have shadow maps
    d.uniforms.bindFrame(block);
    // The environment's integrated irradiance (render/irradiance_map.h): once per environment,
    // before anything binds the units it borrows.
    d.irradiance.update(*d.environment);
    d.stage.beginFrame(d.scene, fs.width, fs.height,
                       fs.navigating ? kNavigatingStageDownsample : kStageDownsample,
                       fs.packOcclusion);
    d.materials.bind();

    // Known state: a host (Qt) may leave anything bound or enabled.
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_MULTISAMPLE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    // 0. The shadow maps, when the lights or the mesh changed (render/stage.h).
    d.stage.drawShadows(d.mesh->gpu);
    glViewport(0, 0, fs.width, fs.height);
    glQueryCounter(d.queries[0], GL_TIMESTAMP);

    // 1. Geometry: the G-buffer, and emission into the HDR target.
    const bool emission =
        materialEmits(d.scene.material) || (fs.splitMaterial && materialEmits(*fs.splitMaterial));
    GeometryPassInputs geometry;
    // The lobe-channel targets only when a drawn record has a lobe map (B's is packed below:
    // a split keeps them): every reader (gbuffer_read.glsl's readLobeChannels) skips them
    // otherwise.
    geometry.lobeTargets =
        hasLobeMap(d.packedA) || fs.splitMaterial.has_value() ||
        (d.scene.environment.ground != GroundMode::Off && hasLobeMap(d.packedGround));
    geometry.framebuffer = d.targets.geometryFramebuffer(emission, geometry.lobeTargets, error);
    if (!geometry.framebuffer)
        return false;
    geometry.width = fs.width;
    geometry.height = fs.height;
    geometry.emission = emission;
    geometry.split = fs.splitMaterial.has_value();
    geometry.splitPosition = fs.splitPosition;
    geometry.splitSwapped = fs.splitSwapped;
    if (fs.splitMaterial) {
        std::string splitError;
        geometry.splitGraph = d.splitGraphFor(*fs.splitMaterial, &splitError);
        if (!splitError.empty())
            return fail(error, "A/B split: B's material graph: " + splitError);
        // B's own texture slots, then B's record: its lobe map following the program B draws
        // with (A's without its own), its presence bits following B's files.
        geometry.texturesB = &d.splitTextures(*fs.splitMaterial);
        d.uploadSplitMaterial(*fs.splitMaterial, geometry.splitGraph);
    } else if (d.texturesB) {
        d.dropSplitTextures();
    }
    // The final image's lighting program specialised to what this frame draws (built at a frame
    // that follows no value edit; the generic one meanwhile).
    if (fs.view == DebugView::Final && d.specialisedPrograms) {
        surfaceProgram = d.lighting.surfaceProgram(fs.view, error, d.scene.environment.ground,
                                                   d.stageBackground(), d.frameFeatures(fs),
                                                   d.mayBuildSpecialised());
        if (!surfaceProgram)
            return false;
    }
    // The display step inside the lighting pass (FrameSettings::displayOnly), decided under the
    // same rule (its programs are specialised ones).
    Impl::InlineDisplay inlineDisplay;
    bool inlineFailed = false;
    const bool inlined = d.chooseInlineDisplay(fs, block, targetFbo, display, emission,
                                               inlineDisplay, inlineFailed, error);
    if (inlineFailed)
        return false;
    d.passes = {};
    for (int i = 0; i < gbufferColorAttachmentCount(); ++i)
        d.passes.gbufferTargets +=
            d.targets.gbuffer().texture(i) &&
            (geometry.lobeTargets || !gbufferAttachments()[size_t(i)].lobeChannels);
    // The G-buffer programs specialised to A's and B's records, under the same rule.
    geometry.recordA = d.packedA;
    geometry.recordB = fs.splitMaterial ? d.packedB : d.packedA;
    geometry.mayBuild = d.mayBuildSpecialised();
    geometry.specialise = d.specialisedPrograms;
    d.geometryDeferred = false;
    geometry.deferred = &d.geometryDeferred;
    d.valueEditSinceFrame = false;
    // After a value edit of a material whose G-buffer values are all per material, the G-buffer
    // is already right: its values come from the table (Renderer::Impl::keepsGBuffer).
    d.passes.gbufferKept =
        d.keepsGBuffer(fs, block, geometry.framebuffer, emission, geometry.lobeTargets);
    if (!d.passes.gbufferKept) {
        drawGeometryPass(geometry, *d.mesh, d.graph, d.textures);
        d.gbufferSpecialised = geometry.specialise && !d.geometryDeferred;
    }
    d.warnSpecialisationFailures();
    d.stage.drawGround(d.scene.environment); // into the same G-buffer, after the mesh
    glQueryCounter(d.queries[1], GL_TIMESTAMP);
    // The occlusion and the shadow masks of the G-buffer, at the stage's downsample.
    if (!d.drawStageScreenPasses(fs, block, error))
        return false;
    glViewport(0, 0, fs.width, fs.height);

    // 2. Background, then 3. lighting, into the HDR target with the G-buffer depth read-only
    // (or, inline, into the display target with the display step compiled in).
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glBindFramebuffer(GL_FRAMEBUFFER,
                      inlined ? inlineDisplay.framebuffer : d.targets.litFramebuffer());
    d.targets.gbuffer().bindTextures();
    glBindTextureUnit(binding::kEnvironmentTex, d.environment->texture);
    glBindTextureUnit(binding::kSheenLutTex, d.ibl.sheenLut());
    glBindTextureUnit(binding::kIblSpecularTex, d.ibl.specularCube());
    glBindTextureUnit(binding::kIblDfgTex, d.ibl.dfgLut());
    glBindTextureUnit(binding::kIblIrradianceTex, d.irradiance.texture());
    const IblBlock iblBlock = makeIblBlock(d.ibl, fs);
    d.uniforms.bindIbl(iblBlock);
    d.stage.bind();
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    glBindVertexArray(d.emptyVao);
    if (inlined) { // the background and the surfaces cover every pixel: no clear
        // After a value edit the background's pixels are already right (frame_reuse.h).
        const bool keep = d.keepsBackground(fs, block, iblBlock, inlineDisplay, targetFbo);
        if (inlineDisplay.cacheBackground && !keep) // only a drawn background reads it
            inlineDisplay.cacheKey = d.backgroundCacheKey(fs, block, iblBlock, inlineDisplay);
        d.drawInlineDisplay(inlineDisplay, keep);
        d.passes.fullScreen += keep ? 1 : 2;
        d.passes.backgroundKept = keep;
        d.passes.backgroundDownsample =
            !keep && inlineDisplay.smallBackground && !d.passes.backgroundDome
                ? inlineDisplay.downsample
                : 1;
    } else {
        d.backgroundReuse.invalidate(); // the display target is not drawn: nothing to keep
        if (!d.drawLitPasses(fs, block, emission, *surfaceProgram, error))
            return false;
    }
    glQueryCounter(d.lightsQuery, GL_TIMESTAMP);

    // 4. Local lights: point, spot and area.
    d.drawLocalLights(fs);
    glQueryCounter(d.queries[2], GL_TIMESTAMP);

    // 5. The scene's post chain. When it tone maps it writes the target itself; otherwise its
    // HDR result feeds the display pass below (an empty chain changes nothing).
    unsigned finalInput = d.targets.hdr().texture();
    bool chainDisplayed = false;
    if (!inlined && fs.view == DebugView::Final &&
        PostChainRenderer::hasEnabledEffects(d.scene.post)) {
        if (!d.runPost(fs, block, targetFbo, display, finalInput, chainDisplayed, error))
            return false;
        d.passes.fullScreen += d.post.lastStepCount();
        glViewport(0, 0, fs.width, fs.height);
        glBindVertexArray(d.emptyVao);
    }
    // Unjittered: a still camera's refinement frames move nothing (postInputs).
    d.lastViewProj = jitterMatrix(-fs.jitter, fs.width, fs.height) * block.viewProjMatrix;
    d.haveLastViewProj = true;

    // 6. Display, into the target (unless the chain's tone map and LDR effects did it, or the
    // lighting pass did: then a copy of the display target, same format, changes no value).
    glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);
    if (inlined) {
        glBlitNamedFramebuffer(inlineDisplay.framebuffer, targetFbo, 0, 0, fs.width, fs.height, 0,
                               0, fs.width, fs.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        d.passes.copies = 1;
        d.passes.inlineDisplay = true;
    } else if (!chainDisplayed) {
        d.display.draw(display, finalInput, fs.exposureEv);
        ++d.passes.fullScreen;
    }
    glQueryCounter(d.queries[3], GL_TIMESTAMP);
    d.queriesIssued = true;

    // Leave sane defaults for the host.
    d.stage.unbind();
    glUseProgram(0);
    glBindVertexArray(0);
    glDepthMask(GL_TRUE);
    for (GLuint unit :
         {0u, 1u, 2u, 3u, GLuint(binding::kEnvironmentTex), GLuint(binding::kSheenLutTex),
          GLuint(binding::kHdrTex), GLuint(binding::kIblSpecularTex), GLuint(binding::kIblDfgTex),
          GLuint(binding::kIblIrradianceTex)})
        glBindTextureUnit(unit, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);

    d.finishFrame(targetFbo, fs, cpuStart);
    if (const std::string e = takeGlErrors(); !e.empty())
        return fail(error, "OpenGL error while rendering: " + e);
    return true;
}

Image Renderer::readLinear() const {
    const Impl& d = *m_impl;
    const ColorTarget& hdr = d.targets.hdr();
    if (!d.initialized || !hdr.framebuffer() || !d.passes.linear)
        return {};
    return readFramebuffer(hdr.framebuffer(), hdr.width(), hdr.height());
}

Image Renderer::readDisplay() const {
    const Impl& d = *m_impl;
    if (!d.initialized || d.lastWidth == 0)
        return {};
    return readFramebuffer(d.lastTarget, d.lastWidth, d.lastHeight);
}

int Renderer::accumulatedSamples() const {
    return m_impl->accumulation.samples();
}

bool Renderer::showAccumulated(int width, int height, unsigned targetFbo) {
    Impl& d = *m_impl;
    if (!d.initialized || d.accumulation.samples() == 0 || d.accumulation.width() != width ||
        d.accumulation.height() != height)
        return false;
    const auto start = std::chrono::steady_clock::now();
    d.accumulation.present(targetFbo);
    FrameSettings fs;
    fs.width = width;
    fs.height = height;
    d.finishFrame(targetFbo, fs, start);
    return true;
}

FramePasses Renderer::lastFramePasses() const {
    return m_impl->passes;
}

float Renderer::meshRadius() const {
    return m_impl->mesh ? m_impl->mesh->radius : 1.0f;
}

const std::string& Renderer::graphError() const {
    return m_impl->graph.error();
}

bool Renderer::graphPending() const {
    return m_impl->graph.pending() || (m_impl->graphB && m_impl->graphB->pending());
}

TextureCache& Renderer::graphTextureCache() {
    return m_impl->textures.sharedCache();
}

void Renderer::finishGraph() {
    if (!m_impl->initialized)
        return;
    m_impl->graph.buildPending(m_impl->textures.sharedCache(), /*wait=*/true);
    if (m_impl->graphB)
        m_impl->graphB->buildPending(m_impl->textures.sharedCache(), /*wait=*/true);
}

bool Renderer::parallelShaderCompile() const {
    return m_impl->parallelShaderCompile;
}

int Renderer::irradianceIntegrations() const {
    return m_impl->irradiance.integrations();
}

int Renderer::shaderCompileCount() const {
    const Impl& d = *m_impl;
    return d.graph.compileCount() + (d.graphB ? d.graphB->compileCount() : 0) +
           d.lighting.compileCount() + d.lights.compileCount() + d.ibl.compileCount() +
           d.display.compileCount() + d.post.compileCount() + d.stage.compileCount();
}

PostChainRenderer& Renderer::postChain() {
    return m_impl->post;
}

FrameTimings Renderer::lastTimings() const {
    const Impl& d = *m_impl;
    if (d.queriesIssued) {
        GLuint64 t[4] = {};
        for (int i = 0; i < 4; ++i)
            glGetQueryObjectui64v(d.queries[i], GL_QUERY_RESULT, &t[i]);
        d.timings.gbufferMs = double(t[1] - t[0]) * 1e-6;
        d.timings.lightingMs = double(t[2] - t[1]) * 1e-6;
        d.timings.postMs = double(t[3] - t[2]) * 1e-6;
        d.timings.totalMs = double(t[3] - t[0]) * 1e-6;
        GLuint64 lightsStart = t[2];
        glGetQueryObjectui64v(d.lightsQuery, GL_QUERY_RESULT, &lightsStart);
        d.timings.localLightsMs = double(t[2] - lightsStart) * 1e-6;
        d.timings.shadowMapsMs = d.stage.lastShadowMs();
        d.timings.occlusionMs = d.stage.lastOcclusionMs();
        d.timings.shadowMaskMs = d.stage.lastShadowMaskMs();
        d.stage.lastShadowMaskTexels(&d.timings.shadowMaskTexels, &d.timings.shadowMaskFiltered);
    }
    d.timings.shadowMaskPasses = d.stage.lastShadowMaskPasses();
    d.timings.occlusionKept = d.stage.lastOcclusionKept();
    d.timings.occlusionInMask = d.stage.occlusionInMask();
    d.timings.shadowMaskKept = d.stage.lastShadowMaskKept();
    return d.timings;
}

float Renderer::environmentProgress() const {
    return m_impl->initialized ? m_impl->ibl.progress() : 0.0f;
}

void Renderer::finishEnvironment() {
    Impl& d = *m_impl;
    if (!d.initialized)
        return;
    if (!d.environment)
        d.environment = &d.environments.get(d.scene.environment, nullptr, d.ibl.cacheSignature());
    d.ibl.request(*d.environment);
    d.ibl.finish();
}

Renderer::EnvironmentBakeStats Renderer::environmentBakeStats() const {
    const IblBakeStats& s = m_impl->ibl.stats();
    return {s.slices,
            s.worstSliceMs,
            s.totalMs,
            m_impl->ibl.warmUpMs(),
            m_impl->ibl.warmUpFrames(),
            m_impl->ibl.worstWarmUpFrameMs()};
}

} // namespace velvet::render
