#pragma once
/// @file renderer_impl.h
/// Render-private: the state behind render::Renderer (render/renderer.h) — the passes in pipeline
/// order, the targets, the scene as last uploaded and the per-frame steps. renderer.cpp holds the
/// public API; renderer_impl.cpp the per-frame steps (prepare, local lights, post, reduced
/// resolution). Split from renderer.cpp (795 lines) by job.

#include "core/color_management.h"
#include "core/post_effects.h"
#include "core/texture_cache.h"
#include "render/background_dome.h"
#include "render/background_downsample.h"
#include "render/display_output.h"
#include "render/environment_map.h"
#include "render/frame_reuse.h"
#include "render/frame_targets.h"
#include "render/frame_uniforms.h"
#include "render/geometry_pass.h"
#include "render/gl_util.h"
#include "render/ibl_bake.h"
#include "render/irradiance_map.h"
#include "render/light_passes.h"
#include "render/lighting_pass.h"
#include "render/lobe_channels.h"
#include "render/material_graph_program.h"
#include "render/material_table.h"
#include "render/mesh_cache.h"
#include "render/post_chain.h"
#include "render/progressive_accumulation.h"
#include "render/renderer.h"
#include "render/shader_program.h"
#include "render/stage.h"
#include "render/texture_set.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

namespace velvet::render {

/// Milliseconds since @p start (wall clock).
inline double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

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
    /// FrameSettings::accumulation >= 0: the jittered frame, and the running mean of them
    ColorTarget accumulationFrame;
    ProgressiveAccumulation accumulation;
    /// The frame of the progressive mean being drawn (renderAccumulated; -1 outside one), and the
    /// one whose traced light the reflection source holds (-2: none, or a frame outside the
    /// mean): frame k of the mean reads frame k - 1's light instead of drawing a first pass
    /// (drawReflectingSurfaces), and each such frame adds one more bounce.
    int accumulationIndex = -1;
    int reflectionSourceFrame = -2;
    /// reflectionSourceFrame as the frame found it (prepareFrame resets the member: a frame that
    /// does not trace leaves the source's light stale).
    int reflectionSourceFrameBefore = -2;
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
    GpuMaterial packedB{};      ///< the A/B split's B as last packed (material id 1)
    /// The A/B split's B's own texture slots (made when a split frame first draws, dropped by
    /// the first frame without a split): B is B, files and all, not B's values over A's maps.
    std::unique_ptr<TextureSet> texturesB;
    std::array<TextureRef, kTextureSlotCount> texturesBRefs{}; ///< what texturesB was given
    /// Lighting variants (render/lighting_features.h): on unless the bench or a test compares
    /// against the generic program; a value edit since the last frame forbids a build.
    bool specialisedPrograms = true;
    bool valueEditSinceFrame = false;
    /// prepareFrame adopted a new graph structure (its build ran on the driver's threads: this
    /// frame must not then stall on a specialised build).
    bool structureAdoptedThisFrame = false;
    /// This frame draws the A/B split, or the last one did (steadySince()).
    bool splitDrawnOrEnded = false;
    bool lastFrameSplit = false;
    /// Whether this frame may build a specialised program: not after a value edit, not the
    /// frame that adopts a graph built asynchronously, not while textures stream in (each
    /// arrival changes the record's slots). The viewport draws once more when they pause.
    bool mayBuildSpecialised() const {
        return !valueEditSinceFrame && !structureAdoptedThisFrame &&
               textures.progress().loading == 0 &&
               (!texturesB || texturesB->progress().loading == 0);
    }
    bool geometryDeferred = false; ///< the last frame's G-buffer wanted an unbuilt specialisation
    /// Inline frames keep the last frame's background pixels after a value edit
    /// (render/frame_reuse.h); uploadedBytes is the texture bytes uploaded as of that frame.
    FrameReuse backgroundReuse;
    /// The G-buffer kept after a value edit of a material whose G-buffer values are all per
    /// material (keepsGBuffer()); gbufferUploadedBytes as uploadedBytes, for its own key.
    FrameReuse gbufferReuse;
    std::uint64_t gbufferUploadedBytes = 0;
    /// The G-buffer as last drawn came from the specialised program (the generic one, drawing
    /// while a specialisation builds, runs the mesh-visibility code whatever the mesh).
    bool gbufferSpecialised = false;
    BackgroundDownsample backgroundDownsample; ///< the inline background at a quarter size
    BackgroundDome backgroundDome;             ///< the inline HDRI background from its cache
    std::uint64_t uploadedBytes = 0;
    /// The texture bytes uploaded as of the last frame's screen-space passes (a normal map
    /// arriving changes the normals the occlusion and the shadow mask read).
    std::uint64_t screenPassUploadedBytes = 0;
    /// Specialised builds that failed, lighting and G-buffer, already warned about.
    int reportedLightingFailures = 0, reportedGeometryFailures = 0;
    /// A specialised program that failed to build is a warning (once each): the generic one
    /// draws the same image, more slowly.
    void warnSpecialisationFailures() {
        const int lightingFailures = lighting.specialisationFailures();
        const int geometryFailures =
            graph.specialisationFailures() + (graphB ? graphB->specialisationFailures() : 0);
        if (lightingFailures == reportedLightingFailures &&
            geometryFailures == reportedGeometryFailures)
            return;
        const std::string& message =
            lightingFailures != reportedLightingFailures ? lighting.lastSpecialisationError()
            : graphB && graphB->specialisationFailures() ? graphB->lastSpecialisationError()
                                                         : graph.lastSpecialisationError();
        reportedLightingFailures = lightingFailures;
        reportedGeometryFailures = geometryFailures;
        lobeWarnings.warning("", "shaders",
                             "a program specialised to this frame's features failed to build; "
                             "the generic program draws instead (the same image, slower): " +
                                 message);
    }
    EnvironmentCache environments;
    IblBaker ibl;             ///< prefiltered cube, DFG LUT, sheen tables
    IrradianceMap irradiance; ///< the environment's irradiance, every frame's
    unsigned emptyVao = 0;
    unsigned queries[4] = {}; // GL query names
    unsigned lightsQuery = 0; ///< between the full-screen lighting pass and the local lights
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
    FramePasses passes; ///< the last frame's (Renderer::lastFramePasses)
    mutable FrameTimings timings;
    double cpuMs = 0;
    /// Uploads since construction; graphCompiles and graphValueUploads come from graph.
    UploadStats uploads;

    /// Frees the VAO and the timer queries (renderer_impl.cpp: GL stays out of this header).
    ~Impl();

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
        if (!backgroundDownsample.build(&message))
            errors += (errors.empty() ? "" : "\n") + message;
        if (!backgroundDome.build(&message))
            errors += (errors.empty() ? "" : "\n") + message;
        if (!irradiance.build(&message))
            errors += (errors.empty() ? "" : "\n") + message;
        if (!accumulation.build(&message))
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

    /// A/B split: material id 1 is FrameSettings::splitMaterial with its own texture slots
    /// (splitTextures).
    void uploadSplitMaterial(const Material& b, const MaterialGraphProgram* program) {
        packedB = packMaterialRecord(b, *texturesB, (program ? *program : graph).writtenFields(),
                                     compactGBuffer);
        writeMaterialTable(&packedB);
    }
    /// B's texture slots for this frame: made like A's the first time (same colour config,
    /// loading mode and budget), given B's files when they changed, polled every frame (a file
    /// changed on disk, a load finished). Problems with B's files join the warnings.
    TextureSet& splitTextures(const Material& b);
    /// The first frame without a split lets B's textures go.
    void dropSplitTextures() {
        texturesB.reset();
        texturesBRefs = {};
    }
    /// Whether @p m may have a lobe that the frames at rest sample
    /// (FrameSettings::reflectionSamples): a base glossy enough (kSampledReflectionMaxRoughness) by
    /// its roughness, or by one that varies per pixel (a roughness texture, a graph, which may
    /// drive it); or a sheen (common_environment.glsl's sampledSheenLight), which a graph may also
    /// bring.
    static bool mayReflectSampled(const Material& m) {
        return m.scalar(ParamId::Roughness) <= kSampledReflectionMaxRoughness ||
               !m.texture(TextureSlot::MetallicRoughness).empty() ||
               !m.texture(TextureSlot::SpecRoughMetal).empty() || bool(m.graph) ||
               m.scalar(ParamId::SheenWeight) > 0.0f;
    }
    /// The features of the records this frame draws (A, B when split, the ground when shown) with
    /// the lights' shadows, the occlusion switch and the bake. While the environment bakes the
    /// generic program draws (no variant is built for the few frames of a bake).
    LightingFeatures frameFeatures(const FrameSettings& fs) const {
        if (!specialisedPrograms || !ibl.specularReady() || !ibl.dfgReady())
            return LightingFeatures::generic();
        std::vector<GpuMaterial> records{packedA};
        if (fs.splitMaterial)
            records.push_back(packedB);
        if (scene.environment.ground != GroundMode::Off)
            records.push_back(packedGround);
        LightingFeatures f =
            lightingFeaturesOf(records, stage.shadowsDirectionalLight(scene.lights),
                               scene.environment.ambientOcclusion, true, fs.specularMultiScatter);
        f.directionalLights = frameDirectionalLightCount(scene.lights);
        if (!fs.splitMaterial && scene.environment.ground != GroundMode::Plain)
            f.materialId = 0; // the scene's material's record (ids: render/stage_interface.h)
        f.shadowMask = stage.hasShadows();
        f.occlusionInMask = stage.packsOcclusion(scene, fs.packOcclusion);
        f.localShadows = stage.shadowsLocalLight(scene.lights);
        f.irradianceMap = irradiance.texture() != 0;
        // Only where a lobe may be glossy enough: a rough velvet's refinement compiles nothing.
        f.sampledReflections = fs.reflectionSamples > 0 &&
                               (mayReflectSampled(scene.material) ||
                                (fs.splitMaterial && mayReflectSampled(*fs.splitMaterial)));
        return f;
    }

    /// Whether this frame traces the mesh's light in screen space
    /// (FrameSettings::screenSpaceReflections): the final image with reflections sampled (a frame
    /// at rest, a still) and a mesh that can see itself (one with its visibility baked: the
    /// convex preview meshes have none), once the environment is baked.
    bool wantsScreenSpaceReflections(const FrameSettings& fs) const {
        if (!fs.screenSpaceReflections || fs.reflectionSamples <= 0 ||
            fs.view != DebugView::Final || !mesh || !mesh->gpu.hasVisibility())
            return false;
        // Not while the environment bakes (the generic program draws, which may sample anything).
        const LightingFeatures f = frameFeatures(fs);
        return !f.isGeneric();
    }
    /// The surfaces into the first pass's target, then again with screen-space reflections of it
    /// into the HDR target (drawLitPasses). @p drawn false when the reflecting program is not
    /// available this frame (not built yet: nothing drawn, the caller draws the plain surfaces).
    /// False + message on a failure.
    bool drawReflectingSurfaces(const FrameSettings& fs, bool emission,
                                const ShaderProgram& surfaceProgram, bool& drawn,
                                std::string* error);

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
    /// After a TextureSet setting that drops its textures (colour management, loading mode,
    /// storage context): B's split set goes, A's slots are requested again.
    void texturesDropped() {
        dropSplitTextures(); // made again with the new settings by the next split frame
        if (initialized) {
            refreshTextureSlots(nullptr);
            uploadMaterial();
        }
    }
    /// The lights; @p problems hears of each directional light past kMaxDirectionalLights.
    void uploadLights(Problems* problems);
    void requestEnvironment(Problems* problems) {
        ++uploads.environmentRequests;
        environment = &environments.get(scene.environment, problems, ibl.cacheSignature());
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
        const int builds = graphB->compileCount();
        graphB->buildPending(textures.sharedCache());
        structureAdoptedThisFrame = structureAdoptedThisFrame || graphB->compileCount() != builds;
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
    /// The display step inside the lighting pass (FrameSettings::displayOnly, issue 16): its
    /// source, the background and surface programs built with it, the display framebuffer.
    struct InlineDisplay {
        InlinePost source;
        bool chain = false; ///< the post chain's fused pass (else the built-in curve)
        PostRunInputs inputs;
        const ShaderProgram* background = nullptr;
        /// The background drawn at a quarter size and upsampled (render/background_downsample.h),
        /// when the picture and the display step allow it; else null.
        const ShaderProgram* smallBackground = nullptr;
        int downsample = 1; ///< its factor (backgroundDownsampleFactor)
        /// The HDRI's dome (render/background_dome.h) when it applies: its cache's program, size
        /// and key (what the picture depends on, the camera's pose excluded); else null.
        const ShaderProgram* cacheBackground = nullptr;
        int cacheWidth = 0, cacheHeight = 0;
        FrameKey cacheKey;
        const ShaderProgram* surfaces = nullptr;
        unsigned framebuffer = 0;
        int width = 0, height = 0;
        /// The mesh's pixel rectangle (Stage::meshRectangle), the surfaces' scissor; unset when
        /// its bounds reach behind the camera.
        bool scissored = false;
        int meshRect[4] = {};
    };
    /// Whether this frame takes the inline path (FrameSettings::displayOnly's conditions, the
    /// programs built or allowed to build); fills @p out. False + message only on a GL failure
    /// (@p failed set).
    bool chooseInlineDisplay(const FrameSettings& fs, const FrameBlock& b, unsigned targetFbo,
                             const DisplayChoice& choice, bool emission, InlineDisplay& out,
                             bool& failed, std::string* error);
    /// Whether nothing a reuse key cannot see changed since the frame that set @p uploadedAsOf
    /// (the texture bytes uploaded then, updated): not a split frame nor the one after it, no
    /// texture arriving or loading, no graph structure adopted this frame.
    bool steadySince(std::uint64_t& uploadedAsOf);
    /// The frame's part of the screen-space passes' keys (the occlusion, render/ao_pass.h, and
    /// the shadow mask, render/stage.h): the camera and, where the material bends its normals,
    /// its record (a value edit may then move them; a graph edit invalidates them in update());
    /// what it cannot see (steadySince()) invalidates what they kept. Once a frame: it notes the
    /// uploads.
    FrameKey screenPassKey(const FrameSettings& fs, const FrameBlock& b);
    /// After the geometry pass and the ground: the stage's screen-space passes, the occlusion
    /// (render/ao_pass.h) and the shadow masks (render/shadow_mask.h, with the occlusion packed
    /// in where it rides there), under one screenPassKey(). Leaves the viewport for the caller.
    bool drawStageScreenPasses(const FrameSettings& fs, const FrameBlock& block,
                               std::string* error);
    /// Whether this frame may keep the last one's G-buffer instead of drawing it: nothing the
    /// geometry pass writes depends on A's values (its record reads its base colour, metallic
    /// and roughness from the table: kRecordValuesPerMaterial; no graph, no lobe map, no
    /// normal it bends, no emission, and a mesh without the visibility its specular occlusion
    /// would take from the roughness), nothing else is drawn into it (no ground, no split), and
    /// the camera, the size and the targets are as they were: a value edit, a slider dragged,
    /// draws the lighting alone. Updates other than values invalidate it (update()).
    bool keepsGBuffer(const FrameSettings& fs, const FrameBlock& b, unsigned framebuffer,
                      bool emission, bool lobeTargets);
    /// Whether this inline frame may keep the last one's background pixels (frame_reuse.h).
    bool keepsBackground(const FrameSettings& fs, const FrameBlock& b, const IblBlock& ibl,
                         const InlineDisplay& d, unsigned targetFbo);
    /// The key of the dome's cache (InlineDisplay::cacheKey) for this frame.
    FrameKey backgroundCacheKey(const FrameSettings& fs, const FrameBlock& b, const IblBlock& ibl,
                                const InlineDisplay& d);
    /// Draws the background (unless @p keepBackground) and the surfaces with the inline
    /// programs into out.framebuffer.
    void drawInlineDisplay(const InlineDisplay& d, bool keepBackground);
    /// The background, the surfaces and the shadow catcher into the bound HDR target (cleared
    /// first unless the geometry pass wrote emission into it). False + message.
    bool drawLitPasses(const FrameSettings& fs, const FrameBlock& block, bool emission,
                       const ShaderProgram& surfaceProgram, std::string* error);
    /// The chain's inputs for this frame (runPost, the inline display step).
    PostRunInputs postInputs(const FrameSettings& fs, const FrameBlock& b, unsigned targetFbo,
                             const DisplayChoice& choice);
    /// Runs scene.post on the lit HDR target (render/post_chain.h); @p finalInput becomes its
    /// HDR result, or @p displayed is set when the chain wrote the target itself.
    bool runPost(const FrameSettings& fs, const FrameBlock& b, unsigned targetFbo,
                 const DisplayChoice& choice, unsigned& finalInput, bool& displayed,
                 std::string* error);
    /// FrameSettings::renderScale in (0, 1): the frame at the smaller size into our own target,
    /// stretched over the caller's (one linear blit).
    bool renderScaled(Renderer& self, const FrameSettings& fs, unsigned targetFbo,
                      std::string* error);
    /// FrameSettings::accumulation >= 0: the frame into our own display target, folded into
    /// the running mean, the mean copied into the caller's (render/progressive_accumulation.h).
    bool renderAccumulated(Renderer& self, const FrameSettings& fs, unsigned targetFbo,
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

} // namespace velvet::render
