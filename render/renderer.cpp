#include "render/renderer.h"

#include "core/color_management.h"
#include "core/post_effects.h"
#include "core/texture_cache.h"
#include "render/display_output.h"
#include "render/environment_map.h"
#include "render/frame_targets.h"
#include "render/frame_uniforms.h"
#include "render/geometry_pass.h"
#include "render/gl_util.h"
#include "render/ibl_bake.h"
#include "render/light_passes.h"
#include "render/lighting_pass.h"
#include "render/lobe_channels.h"
#include "render/material_graph_program.h"
#include "render/material_table.h"
#include "render/mesh_cache.h"
#include "render/post_chain.h"
#include "render/shader_program.h"
#include "render/stage.h"
#include "render/texture_set.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <epoxy/gl.h>
#include <utility>

namespace velvet::render {
namespace {

/// IBL bake time allowed at the start of a frame (render/ibl_bake.h adapts its slices to
/// IblBakeOptions::sliceTargetMs; a frame may run one slice past this).
constexpr double kIblFrameBudgetMs = 12.0;

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

} // namespace

struct Renderer::Impl {
    bool initialized = false;
    bool parallelShaderCompile = false; ///< GL_KHR_parallel_shader_compile (shader_program.h)

    /// @name The passes, in pipeline order
    /// @{
    MaterialGraphProgram graph; ///< geometry: the G-buffer program with the material graph
    /// The A/B split's B when its graph is not A's: its own G-buffer program (made on first use)
    /// and the graph it was given.
    std::unique_ptr<MaterialGraphProgram> graphB;
    SharedGraph graphBSource;
    LightingPass lighting;  ///< background, then directional + image-based lighting
    LightPasses lights;     ///< point, spot and area lights
    PostChainRenderer post; ///< the scene's post chain, run after lighting
    DisplayOutput display;  ///< tone mapping / OCIO into the caller's framebuffer
    Stage stage;            ///< shadow maps, the ground, screen-space occlusion
    /// @}

    FrameTargets targets; ///< G-buffer, HDR colour, the framebuffers over them
    ColorTarget scaled;   ///< FrameSettings::renderScale < 1: the reduced display-encoded frame
    FrameUniforms uniforms;
    MeshCache meshes;
    const MeshCache::Entry* mesh = nullptr;
    TextureSet textures;
    MaterialTable materials;
    GpuMaterial packedA{}; ///< the scene's material as last packed (material id 0)
    /// The drawn graph's written fields packedA's lobe-channel map follows (re-packed when the
    /// program that draws changes: render/lobe_channels.h).
    std::vector<std::string> packedGraphFields;
    bool compactGBuffer = false;    ///< the 16-byte layout (Renderer::setCompactGBuffer)
    std::uint32_t lobeOverflow = 0; ///< lobe values last warned about as kept per material
    Problems lobeWarnings;
    GpuMaterial packedGround{}; ///< the ground's record (ids 2 and 3, render/stage_interface.h)
    EnvironmentCache environments;
    IblBaker ibl; ///< prefiltered cube, DFG LUT, sheen tables
    GLuint emptyVao = 0;
    GLuint queries[4] = {};
    GLuint lightsQuery = 0; ///< between the full-screen lighting pass and the local lights
    bool queriesIssued = false;
    glm::mat4 lastViewProj{1.0f};
    bool haveLastViewProj = false;
    /// The host's config (setColorManagement), also handed to the texture slots.
    std::shared_ptr<const ColorManagement> colorManagement;

    Scene scene;
    bool haveScene = false;
    const GpuEnvironment* environment = nullptr;

    unsigned lastTarget = 0;
    int lastWidth = 0, lastHeight = 0;
    mutable FrameTimings timings;
    double cpuMs = 0;
    /// Uploads since construction; graphCompiles and graphValueUploads come from graph.
    UploadStats uploads;

    ~Impl() {
        if (emptyVao)
            glDeleteVertexArrays(1, &emptyVao);
        if (queries[0])
            glDeleteQueries(4, queries);
        if (lightsQuery)
            glDeleteQueries(1, &lightsQuery);
    }

    /// Builds the G-buffer and lighting programs from disk. With @p keepGoing (shader reload) a
    /// failed program keeps its last good build, the others are still rebuilt and the errors
    /// are joined.
    bool buildPrograms(std::string* error, bool keepGoing = false) {
        std::string errors;
        if (!graph.build(&errors) && !keepGoing)
            return fail(error, errors);
        if (graphB) {
            std::string messageB;
            if (!graphB->build(&messageB))
                errors += (errors.empty() ? "" : "\n") + messageB;
        }
        std::string message;
        if (!lighting.build(&message, keepGoing))
            errors += (errors.empty() ? "" : "\n") + message;
        return errors.empty() || fail(error, errors);
    }

    /// The material record: parameters, then texture presence bits and the means of the slots
    /// the G-buffer cannot carry (render/texture_set.h). Never a shader.
    void uploadMaterial() {
        ++uploads.materialUploads;
        packedGraphFields = graph.writtenFields();
        std::uint32_t overflow = 0;
        packedA = packMaterialRecord(scene.material, textures, packedGraphFields, compactGBuffer,
                                     &overflow);
        warnLobeOverflow(scene.material, overflow);
        writeMaterialTable(nullptr);
    }
    /// Once per change of what does not fit: the values a material varies beyond the eight
    /// lobe channels are drawn with their texture's mean (render/lobe_channels.h).
    void warnLobeOverflow(const Material& m, std::uint32_t overflow) {
        if (overflow && overflow != lobeOverflow)
            lobeWarnings.warning(
                "", "lobes",
                "material '" + m.name + "' varies more lobe values per pixel than the G-buffer's " +
                    std::to_string(kLobeChannelCount) + " lobe channels hold; the viewport draws " +
                    lobeValueNames(overflow) +
                    " with their texture's mean (exports keep the maps)");
        lobeOverflow = overflow;
    }
    /// The table: A, B (A again without a split), the plain ground and the catcher.
    void writeMaterialTable(const GpuMaterial* b) {
        materials.upload({packedA, b ? *b : packedA, packedGround, packedGround});
    }
    void uploadGround() {
        packedGround = groundMaterial(scene.environment);
        writeMaterialTable(nullptr);
    }

    /// A/B split: material id 1 is FrameSettings::splitMaterial with A's textures.
    void uploadSplitMaterial(const Material& b, const MaterialGraphProgram* program) {
        const GpuMaterial g = packMaterialRecord(
            b, textures, (program ? *program : graph).writtenFields(), compactGBuffer);
        writeMaterialTable(&g);
    }

    void selectMesh(Problems* problems) {
        ++uploads.meshSelections;
        mesh = &meshes.select(scene.mesh, problems);
        planStage(nullptr); // the shadow maps fit the new mesh
    }
    /// The shadow slots for the lights and the mesh, and the local lights with their slots.
    void planStage(Problems* problems) {
        stage.plan(scene.lights, mesh ? mesh->bounds : MeshBounds{}, problems);
        const std::vector<int> slots = stage.slotOfLight(scene.lights.size());
        lights.upload(scene.lights, &slots);
    }
    void refreshTextureSlots(Problems* problems) {
        ++uploads.textureSlotRefreshes;
        textures.setMaterial(scene.material, problems);
    }
    /// The lights; @p problems hears of each directional light past kMaxDirectionalLights.
    void uploadLights(Problems* problems);
    void requestEnvironment(Problems* problems) {
        ++uploads.environmentRequests;
        environment = &environments.get(scene.environment, problems);
        ibl.request(*environment);
    }

    /// The program B draws with: null when B's graph is A's (A's program, B's values in the
    /// material table); otherwise B's own, started and built the first time (synchronously, like
    /// the first build of A's), given B's graph when it changed, polled like A's.
    MaterialGraphProgram* splitGraphFor(const Material& b, std::string* error) {
        if (b.graph == scene.material.graph)
            return nullptr;
        if (!graphB) {
            auto program = std::make_unique<MaterialGraphProgram>();
            program->start(b);
            if (!program->build(error))
                return nullptr;
            graphB = std::move(program);
            graphBSource = b.graph;
            graphB->uploadValues();
            graphB->refreshTextures(textures.sharedCache(), nullptr);
        } else if (!(graphBSource == b.graph)) {
            graphB->setGraph(b, textures.sharedCache(), nullptr);
            graphBSource = b.graph;
        }
        graphB->buildPending(textures.sharedCache());
        graphB->refreshTextures(textures.sharedCache(), nullptr);
        return graphB.get();
    }

    /// Per-frame work before drawing: texture files changed on disk, a structural graph edit
    /// being built, the lighting variant and display path for @p fs, the environment bake's
    /// slices, the targets' size. False + message before anything is drawn.
    bool prepareFrame(const FrameSettings& fs, unsigned targetFbo, DisplayChoice& choice,
                      const ShaderProgram*& surfaceProgram, std::string* error);
    /// The point, spot and area lights, added on top by the path the frame asks for.
    void drawLocalLights(const FrameSettings& fs);
    /// Runs scene.post on the lit HDR target (render/post_chain.h); @p finalInput becomes its
    /// HDR result, or @p displayed is set when the chain wrote the target itself.
    bool runPost(const FrameSettings& fs, const FrameBlock& b, unsigned targetFbo,
                 const DisplayChoice& choice, unsigned& finalInput, bool& displayed,
                 std::string* error);
    /// FrameSettings::renderScale in (0, 1): the frame at the smaller size into our own target,
    /// stretched over the caller's (one linear blit).
    bool renderScaled(Renderer& self, const FrameSettings& fs, unsigned targetFbo,
                      std::string* error);
    BackgroundMode stageBackground() const {
        const BackgroundMode mode = scene.environment.background;
        return mode == BackgroundMode::Blurred && !ibl.specularReady() ? BackgroundMode::Sharp
                                                                       : mode;
    }
    void finishFrame(unsigned targetFbo, const FrameSettings& fs,
                     std::chrono::steady_clock::time_point start) {
        lastTarget = targetFbo;
        lastWidth = fs.width;
        lastHeight = fs.height;
        cpuMs = msSince(start);
    }
};

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
    graph.buildPending(textures.sharedCache());
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
    const GpuEnvironment* current = &environments.get(scene.environment, nullptr);
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
    d.colorManagement = std::move(colorManagement);
    d.display.setColorManagement(d.colorManagement);
    // Input colour space names are looked up in the new config too (without one, in the
    // display's default, loaded once by the display at initialize()).
    d.textures.setColorManagement(d.colorManagement || !d.initialized ? d.colorManagement
                                                                      : d.display.sharedConfig());
    if (d.initialized) {
        d.refreshTextureSlots(nullptr);
        d.uploadMaterial();
    }
}

void Renderer::setScene(const Scene& scene, Problems* problems) {
    update(scene, ScenePart::All, problems);
}

void Renderer::update(const Scene& scene, ScenePart parts, Problems* problems) {
    Impl& d = *m_impl;
    copyParts(d.scene, scene, parts);
    d.haveScene = true;
    if (!d.initialized)
        return; // uploaded by initialize()
    if (touches(parts, ScenePart::Mesh))
        d.selectMesh(problems);
    if (touches(parts, ScenePart::MaterialStructure))
        d.refreshTextureSlots(problems);
    // Numbers only: rewrite the material table (never a shader).
    if (touches(parts, ScenePart::MaterialStructure | ScenePart::MaterialValues))
        d.uploadMaterial();
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

void Renderer::setAsyncTextures(bool async) {
    Impl& d = *m_impl;
    if (async == d.textures.async())
        return;
    d.textures.setAsync(async);
    if (d.initialized) {
        d.refreshTextureSlots(nullptr);
        d.uploadMaterial();
    }
}

void Renderer::setTextureUploadBudget(std::uint64_t bytes) {
    m_impl->textures.setUploadBudget(bytes);
}

TextureLoadProgress Renderer::textureProgress() const {
    return m_impl->textures.progress();
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
    if (fs.width <= 0 || fs.height <= 0 || fs.width > 16384 || fs.height > 16384)
        return fail(error, "invalid frame size " + std::to_string(fs.width) + "x" +
                               std::to_string(fs.height));
    if (fs.renderScale > 0.0f && fs.renderScale < 1.0f)
        return d.renderScaled(*this, fs, targetFbo, error);
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
    d.stage.beginFrame(d.scene, fs.width, fs.height);
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
    geometry.framebuffer = d.targets.geometryFramebuffer(emission, error);
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
        // B's record, its lobe map following the program B draws with (A's without its own).
        d.uploadSplitMaterial(*fs.splitMaterial, geometry.splitGraph);
    }
    drawGeometryPass(geometry, *d.mesh, d.graph, d.textures);
    d.stage.drawGround(d.scene.environment); // into the same G-buffer, after the mesh
    glQueryCounter(d.queries[1], GL_TIMESTAMP);
    // Screen-space occlusion of the G-buffer, at half resolution (off: nothing runs).
    d.targets.gbuffer().bindTextures();
    if (!d.stage.drawOcclusion(d.scene.environment, fs.width, fs.height, d.emptyVao, error))
        return false;
    glViewport(0, 0, fs.width, fs.height);

    // 2. Background, then 3. lighting, into the HDR target with the G-buffer depth read-only.
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glBindFramebuffer(GL_FRAMEBUFFER, d.targets.litFramebuffer());
    d.targets.gbuffer().bindTextures();
    glBindTextureUnit(binding::kEnvironmentTex, d.environment->texture);
    glBindTextureUnit(binding::kSheenLutTex, d.ibl.sheenLut());
    glBindTextureUnit(binding::kIblSpecularTex, d.ibl.specularCube());
    glBindTextureUnit(binding::kIblDfgTex, d.ibl.dfgLut());
    d.uniforms.bindIbl(makeIblBlock(d.ibl, fs));
    d.stage.bind();
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    glBindVertexArray(d.emptyVao);
    if (!emission) // nothing in the HDR target yet: start from black, opaque
        glClearBufferfv(GL_COLOR, 0, kNoEmission);
    if (fs.view == DebugView::Final) // debug views: no background (the HDR target is black)
        d.lighting.drawBackground(d.scene.environment.background, d.ibl.specularReady());
    // With a shadow catcher only the mesh's rectangle needs the surface shading (render/stage.h).
    int meshRect[4];
    const bool scissored =
        d.scene.environment.ground == GroundMode::ShadowCatcher &&
        d.stage.meshRectangle(block.viewProjMatrix, fs.width, fs.height, meshRect);
    if (scissored) {
        glEnable(GL_SCISSOR_TEST);
        glScissor(meshRect[0], meshRect[1], meshRect[2], meshRect[3]);
    }
    d.lighting.drawSurfaces(*surfaceProgram, emission);
    glDisable(GL_SCISSOR_TEST);
    if (fs.view == DebugView::Final && d.scene.environment.ground == GroundMode::ShadowCatcher &&
        !d.lighting.drawCatcher(emission, d.stageBackground(), error)) // its own variant
        return false;
    glQueryCounter(d.lightsQuery, GL_TIMESTAMP);

    // 4. Local lights: point, spot and area.
    d.drawLocalLights(fs);
    glQueryCounter(d.queries[2], GL_TIMESTAMP);

    // 5. The scene's post chain. When it tone maps it writes the target itself; otherwise its
    // HDR result feeds the display pass below (an empty chain changes nothing).
    unsigned finalInput = d.targets.hdr().texture();
    bool chainDisplayed = false;
    if (fs.view == DebugView::Final && PostChainRenderer::hasEnabledEffects(d.scene.post)) {
        if (!d.runPost(fs, block, targetFbo, display, finalInput, chainDisplayed, error))
            return false;
        glViewport(0, 0, fs.width, fs.height);
        glBindVertexArray(d.emptyVao);
    }
    d.lastViewProj = block.viewProjMatrix;
    d.haveLastViewProj = true;

    // 6. Display, into the target (unless the chain's tone map and LDR effects did it).
    glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);
    if (!chainDisplayed)
        d.display.draw(display, finalInput, fs.exposureEv);
    glQueryCounter(d.queries[3], GL_TIMESTAMP);
    d.queriesIssued = true;

    // Leave sane defaults for the host.
    d.stage.unbind();
    glUseProgram(0);
    glBindVertexArray(0);
    glDepthMask(GL_TRUE);
    for (GLuint unit :
         {0u, 1u, 2u, 3u, GLuint(binding::kEnvironmentTex), GLuint(binding::kSheenLutTex),
          GLuint(binding::kHdrTex), GLuint(binding::kIblSpecularTex), GLuint(binding::kIblDfgTex)})
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
    if (!d.initialized || !hdr.framebuffer())
        return {};
    return readFramebuffer(hdr.framebuffer(), hdr.width(), hdr.height());
}

Image Renderer::readDisplay() const {
    const Impl& d = *m_impl;
    if (!d.initialized || d.lastWidth == 0)
        return {};
    return readFramebuffer(d.lastTarget, d.lastWidth, d.lastHeight);
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
    }
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
        d.environment = &d.environments.get(d.scene.environment, nullptr);
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
