#pragma once
/// @file renderer.h
/// The deferred renderer: G-buffer pass, lighting (directional lights + HDRI ambient), background,
/// tone mapping to display. Owns every GL object; needs a current OpenGL 4.5 core context (a Qt one
/// in the editor, a bare EGL one in the CLI and tests) and no Qt.

#include "core/diagnostics.h"
#include "core/image.h"
#include "core/scene.h"
#include "core/scene_parts.h"
#include "render/texture_progress.h"

#include <glm/mat4x4.hpp>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {
class ColorManagement;
class TextureCache;
} // namespace velvet

namespace velvet::render {

class PostChainRenderer;
class WorkerGlContext;

/// Directional lights the lighting pass draws (MAX_LIGHTS in the generated render_interface.glsl);
/// update() with ScenePart::Lights reports each one past this as a warning naming its JSON path
/// ("lights[i]").
inline constexpr int kMaxDirectionalLights = 16;

/// What the final pass shows (the renderer issue adds every G-buffer and lighting view).
/// Debug views write raw values to the linear image (readLinear): Albedo linear base colour, Normal
/// world normal, Depth view-space distance along -Z in metres, Roughness, Metallic, Position world
/// position; the display image maps them for viewing.
enum class DebugView {
    Final,
    Albedo,
    Normal,
    Depth,
    Roughness,
    Metallic,
    Position,
    /// @name Appended with the lights (numbers are stable; resources/shaders/debug_views.glsl)
    /// G-buffer / material views write raw values: Specular colour x weight, Clearcoat (weight,
    /// roughness, 0), Sheen colour, Occlusion, Emissive colour x strength, MaterialId (the integer
    /// id). LightsPerPixel: the number of point/spot/area lights whose radius (and, for a spot,
    /// outer cone) contains the pixel
    /// (the display image is a heat map, 0 black .. 32+ red). The lobe views show the direct light
    /// of every analytic light (not the environment) through one lobe: DiffuseOnly, SpecularOnly
    /// (base specular + sheen + clearcoat), BaseSpecular, SheenOnly, ClearcoatOnly alone.
    /// @{
    Specular,
    Clearcoat,
    Sheen,
    Occlusion,
    Emissive,
    MaterialId,
    LightsPerPixel,
    DiffuseOnly,
    SpecularOnly,
    BaseSpecular,
    SheenOnly,
    ClearcoatOnly,
    /// @}
    /// KHR_materials_anisotropy per pixel: the world-space stretch direction times the strength
    /// (its length is the strength, 0 where the surface is isotropic; its sign is arbitrary, as
    /// t and -t stretch the lobe alike, so the display image shows seams where it flips).
    Anisotropy,
    /// The specular occlusion image-based light's reflections get (the G-buffer's RT2 alpha:
    /// the material's occlusion times the share of the reflection's lobe the mesh's visibility
    /// from itself leaves open, render/mesh_visibility.h), times screen-space occlusion.
    SpecularOcclusion,
};

/// How point, spot and area lights are drawn (render/light_passes.h); all give the same image.
/// Auto: brute force up to a few lights, tiled above.
enum class LightPath { Auto, Volumes, Tiled, Brute };

/// Built-in tone-mapping operators (scene-linear in, display-linear Rec.709 out), followed by
/// OCIO's display encoding; skipped when the chosen OCIO view tone maps itself (FrameSettings).
enum class ToneMapper { KhronosPbrNeutral, AcesFitted, Reinhard, Linear };

struct FrameSettings {
    int width = 256;
    int height = 256;
    /// Set: the frame is drawn from this camera instead of the scene's (the editor's orbit is a
    /// per-frame setting, never a scene edit: a camera move uploads nothing). The frame block and
    /// motion blur's view-projection use it. Unset: Scene::camera as update() last took it.
    std::optional<Camera> camera;
    /// Exposure in stops (scene-linear x 2^EV) before the tone mapper, or fed to the OCIO display
    /// transform's dynamic exposure uniform when a tone-mapping OCIO view is chosen. A uniform
    /// either way: changing it compiles nothing.
    float exposureEv = 0.0f;
    ToneMapper toneMapper = ToneMapper::KhronosPbrNeutral;
    DebugView view = DebugView::Final;
    /// The many-lights path for point, spot and area lights (chosen per frame).
    LightPath lightPath = LightPath::Auto;
    /// @name Image-based lighting
    /// @{
    /// Seconds of animation for BackgroundMode::ProceduralFbm (a fixed time gives a fixed image).
    float time = 0.0f;
    /// Adds the energy of multiply scattered light to the environment's specular lobes
    /// (Fdez-Agüera 2019); off gives the single-scattering split sum, which loses energy on rough
    /// surfaces.
    bool specularMultiScatter = true;
    /// @}
    /// The frame is one of a camera move (the editor's orbit, pan or dolly while the mouse drags):
    /// the look-dev stage draws its shadow masks and occlusion at a quarter of the frame's size
    /// each way instead of half (render/stage_interface.h's kNavigatingStageDownsample), as DCC
    /// viewports lower their resolution while navigating; the frames at rest draw them at half
    /// again (BENCHMARKS.md, "The stage at a quarter while the camera moves"). Stills, turntables
    /// and the refinement never set it.
    bool navigating = false;
    /// Lets a value edit keep the last frame's G-buffer where nothing in it depends on the values
    /// (FramePasses::gbufferKept). The image is the same either way; off draws it every frame:
    /// the bench's "before".
    bool keepGBuffer = true;
    /// Lets the maps' depth bounds settle shadow-mask texels without filtering them
    /// (render/shadow_depth_bounds.h). The result is the same either way; off filters every
    /// texel: the reference the settled mask is tested against, and the bench's "before".
    bool settleShadows = true;
    /// Lets the occlusion ride in the shadow masks' free fourth channel, read with the shadows'
    /// upsample (render/ao_pass.h, OcclusionPass::packInto). The result is the same up to the two
    /// upsamples' weights and 8 bits; off gives the occlusion its own upsample: the bench's
    /// "before" and the reference the packed one is tested against.
    bool packOcclusion = true;
    /// @name OpenColorIO display (docs/color-management.md)
    /// The display encoding is always OCIO's own GPU shader. An empty display is the config's
    /// default display (sRGB in the shipped config), an empty displayView that display's default
    /// view. When the view only encodes (its view transform is the config's default, "Standard"
    /// in the shipped config) and no look is set — the default — the built-in toneMapper runs
    /// and OCIO's shader for that view encodes its display-linear output (one pass; sRGB: the
    /// piecewise curve, Display P3: primaries and curve). A tone-mapping view (ACES, AgX), a view
    /// without a view transform (Raw) or a look is OCIO's whole transform instead (exposure, look,
    /// view) and toneMapper is not used. Only when no config can be loaded at all does the
    /// hand-written sRGB OETF encode (warned once, Renderer::takeWarnings()). Debug views use the
    /// display's encoding or their own fixed mappings.
    /// @{
    std::string display;
    std::string displayView;
    std::string look; ///< one look name, or OCIO's comma-separated list
    /// @}
    /// Whether any OCIO name is set (a display, view or look other than the defaults).
    bool usesColorManagement() const {
        return !display.empty() || !displayView.empty() || !look.empty();
    }
    /// @name Post chain (render/post_chain.h; `time` above also animates grain and brushes)
    /// The previous frame's view-projection (without a jitter), for motion blur. Unset: the one
    /// this renderer drew last (the first frame counts as a still camera).
    /// @{
    bool hasPreviousViewProj = false;
    glm::mat4 previousViewProj{1.0f};
    /// @}
    /// @name A/B split (the editor's viewport toolbar)
    /// Set: the same scene is drawn with the scene's material left of splitPosition (A) and this
    /// material right of it (B) in one frame: one G-buffer with a second, scissored draw of the
    /// mesh with material id 1, then one lighting and post pass over both halves. B draws its
    /// own texture files (slots of its own, loaded like A's); any parameter or BRDF term may
    /// differ.
    /// Uploading B rewrites the material table only, unless B's graph is not A's: then B draws
    /// with a G-buffer program of its own (compiled the first time, rebuilt when B's graph
    /// changes structure).
    /// @{
    std::optional<Material> splitMaterial;
    float splitPosition = 0.5f; ///< the seam, as a fraction of the width (0..1)
    bool splitSwapped = false;  ///< B left of the seam, A right of it
    /// @}
    /// Interactive reduced resolution: in (0, 1) the frame is rendered at width x height scaled
    /// by this (at least 1 x 1) into an internal display-encoded target and stretched over the
    /// target with linear filtering; 1 renders at full size. readLinear() then returns the
    /// reduced image, readDisplay() the stretched one.
    float renderScale = 1.0f;
    /// The caller reads the display image only (its target, readDisplay()), not readLinear():
    /// the renderer may then run the display step — the post chain when it is one fused pass
    /// that tone maps, or the built-in curve — inside the lighting pass and never write the
    /// scene-linear target (one full-screen pass and an HDR write and read fewer, issue 16; the
    /// same pixels). Taken when the final image has no emission, no ground, no point, spot or
    /// area light, a specialised lighting program and a single-sampled target (an 8-bit one
    /// when it is the default framebuffer); Renderer::lastFramePasses() tells. readLinear() is
    /// then empty.
    bool displayOnly = false;
    /// @name Reflections sampled (common_environment.glsl's sampledReflection)
    /// 0: an isotropic base reflects the environment by the split sum, one prefiltered lookup
    /// (every interactive frame). n > 0: by n GGX visible-normal samples per pixel, each read
    /// from the equirect's mips at its footprint; closer to the path tracer at grazing angles,
    /// for the frames that have time: the viewport's refinement at rest, supersampled stills.
    /// The frames of a mean draw different sets (reflectionSampleSet; each pixel also rotates its
    /// own), and reflectionSampleTotal, the samples the mean will hold, sets their filtering.
    /// @{
    int reflectionSamples = 0;
    int reflectionSampleTotal = 0;
    int reflectionSampleSet = 0;
    /// Pixels per side of the frame that are samples of one output pixel (a supersampled
    /// still's factor; 1 for a frame of the progressive mean): they draw consecutive sets.
    int reflectionSampleBlock = 1;
    /// With reflections sampled and a mesh that can see itself (not a convex preview mesh): the
    /// surfaces are drawn twice, the second pass reading the first's image where a few rays a
    /// pixel meet the mesh in the depth buffer (screen_space_reflection.glsl): samples of a
    /// glossy lobe (the shader ball's copper shows the copper it faces instead of an environment
    /// darkened by the mesh's occlusion) and of the diffuse light (the key light on the ring
    /// lights the pedestal under it). The frame then goes through the scene-linear target (no
    /// display step inside the lighting pass). Off: the occlusions alone.
    bool screenSpaceReflections = true;
    /// @}
    /// @name Progressive anti-aliasing (render/progressive_accumulation.h)
    /// @{
    /// The projection offset by this many pixels (x right, y up; progressiveJitter), so the
    /// frame samples each pixel there instead of at its centre.
    glm::vec2 jitter{0.0f};
    /// -1: the frame goes to the target as drawn. 0: it starts the renderer's running mean of
    /// frames, and the target gets the mean; n > 0: it is added to the mean
    /// (Renderer::accumulatedSamples()). Ignored, as the jitter, with renderScale < 1 (a reduced
    /// frame is drawn alone, never averaged).
    int accumulation = -1;
    /// @}
};

/// Reflection samples per pixel that each frame of a progressive mean and each sample of a
/// supersampled still draws (FrameSettings::reflectionSamples): the mean of 16 such frames holds
/// the 256 with which the glossy metals met the path tracer (BENCHMARKS.md, "Reflections sampled
/// at rest").
inline constexpr int kRefinementReflectionSamples = 16;
/// Frames in the viewport's progressive mean at rest (its refinement): each after the first
/// reads the light of the one before where it traces the mesh's light in screen space, so the
/// mean holds one to this many bounces of the mesh's own light.
inline constexpr int kRefinementFrames = 16;
/// The roughest isotropic lobe whose reflections are sampled (rougher ones keep the split sum:
/// their shape hardly changes at grazing angles, and the cube's GGX prefilter beats the
/// equirect's box-filtered mips; common_environment.glsl, SAMPLED_REFLECTION_MAX_ROUGHNESS).
inline constexpr float kSampledReflectionMaxRoughness = 0.7f;

/// What the last frame drew after the G-buffer (Renderer::lastFramePasses).
struct FramePasses {
    /// Full-screen passes: the background, the surfaces, the shadow catcher, each post-chain
    /// step and the display pass.
    int fullScreen = 0;
    /// Copies of a whole image (the display target into the caller's, FrameSettings::displayOnly).
    int copies = 0;
    /// The scene-linear target holds the frame (readLinear() has it).
    bool linear = false;
    /// The display step ran inside the lighting pass (FrameSettings::displayOnly).
    bool inlineDisplay = false;
    /// The inline frame kept the last frame's background pixels: nothing they depend on
    /// changed, as after a material value edit (render/frame_reuse.h).
    bool backgroundKept = false;
    /// How many times smaller each way the inline frame drew its background before upsampling
    /// it (render/background_downsample.h); 1: full size (or kept, or not inline).
    int backgroundDownsample = 1;
    /// The inline frame drew its HDRI background as a dome from the picture's cache
    /// (render/background_dome.h), and whether it drew that cache this frame.
    bool backgroundDome = false;
    bool backgroundCacheDrawn = false;
    /// G-buffer colour targets cleared and written: the lobe-channel targets only when a drawn
    /// material has a lobe map (or a split frame's B may have one).
    int gbufferTargets = 0;
    /// The frame kept the last frame's G-buffer (no geometry pass): a value edit of a material
    /// whose G-buffer values are all per material, the camera where it was
    /// (kRecordValuesPerMaterial, render/material_table.h).
    bool gbufferKept = false;
    /// The surfaces were drawn twice, the second time with screen-space reflections of the
    /// first (FrameSettings::screenSpaceReflections).
    bool screenSpaceReflections = false;
    /// It read the light of the progressive mean's frame before instead of drawing a first pass.
    bool reflectionSourceReused = false;
};

/// GPU timings of the last frame (GL timer queries; 0 where unavailable). Logged, never asserted.
struct FrameTimings {
    double gbufferMs = 0, lightingMs = 0, postMs = 0, totalMs = 0;
    /// The point/spot/area light pass alone (part of lightingMs).
    double localLightsMs = 0;
    /// Environment prefiltering (IBL bake slices) run at the start of this frame, wall clock
    /// with glFinish; 0 once the bake is complete.
    double iblMs = 0;
    /// The look-dev stage (docs/shadows.md): the shadow maps, drawn only in frames after the
    /// lights or the mesh changed (0 otherwise), and the screen-space occlusion (0 when off).
    double shadowMapsMs = 0, occlusionMs = 0;
    /// The frame kept the last frame's occlusion (render/ao_pass.h: the camera, the depth and the
    /// normals as they were; occlusionMs is then 0). Counted, not timed: always set.
    bool occlusionKept = false;
    /// The frame's occlusion rode in the shadow masks' fourth channel (FrameSettings::
    /// packOcclusion, Stage::packsOcclusion). Counted, not timed: always set.
    bool occlusionInMask = false;
    /// The screen-space shadow mask's passes (render/shadow_mask.h; 0 without a shadowed light,
    /// and when the frame kept the last frame's masks).
    double shadowMaskMs = 0;
    /// The frame kept the last frame's shadow masks (render/stage.h: the camera, the normals,
    /// the lights and the maps as they were, as after a material value edit). Always set.
    bool shadowMaskKept = false;
    /// How many shadow-mask passes the frame's masks took: one per shadowed light with receivers
    /// on screen, never more than the cap (kMaxShadowLights); a frame that kept the masks
    /// (shadowMaskKept) reports the frame that drew them. Counted, not timed: always set.
    int shadowMaskPasses = 0;
    /// The shadow masks' texels drawn (settled or filtered) and, of those, the ones the PCSS
    /// lookup filtered (occlusion queries; with the timers: 0 when none were issued); kept
    /// masks report the frame that drew them, as shadowMaskPasses.
    long long shadowMaskTexels = 0, shadowMaskFiltered = 0;
};

/// What the renderer uploaded since construction (Renderer::uploadStats), one count per kind
/// of scene upload. Per-frame work counts only when it really uploads: a texture slot or the
/// material record re-uploaded because a file changed on disk, an HDRI read again because it
/// changed. The A/B split's material (FrameSettings::splitMaterial) is per frame and not counted.
struct UploadStats {
    int meshSelections = 0;       ///< preview mesh selections (an upload the first time per mesh)
    int textureSlotRefreshes = 0; ///< the texture slots taken again (TextureSet::setMaterial)
    int materialUploads = 0;      ///< the scene material's record written to the material table
    int graphCompiles = 0;        ///< material graph -> GLSL compiles (not GL program builds)
    int graphValueUploads = 0;    ///< the graph's value block written
    int lightUploads = 0;         ///< point, spot and area lights uploaded (render/light_passes.h)
    int environmentRequests = 0;  ///< environment looked up and its bake requested
};

class Renderer {
public:
    Renderer();
    /// Must run with the renderer's context current (frees GL objects).
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Loads and compiles shaders; needs a current GL 4.5 core context. False + message on failure
    /// (a compile error names file:line).
    bool initialize(std::string* error);

    /// Recompiles every shader program from disk (the editor's T key): G-buffer, lighting, tone
    /// map, the light paths, the IBL bake's compute programs, the cached OCIO display programs
    /// and the post chain's programs built so far (each effect's and each fused pass's). A
    /// program that fails to compile keeps its last good build, so rendering goes on;
    /// false + message (file:line and the driver's log for each failure).
    bool reloadShaders(std::string* error);

    /// @name Scene updates (DESIGN.md, "Changes")
    /// @{
    /// Takes the parts of @p scene that @p parts names into the renderer's own scene and
    /// (re)uploads only those; the other parts of @p scene are not read. Mesh: the mesh
    /// selection. MaterialStructure: the texture slots and the material record. MaterialValues:
    /// the material record only (no texture is looked at). Graph: the graph (compiled to GLSL;
    /// values and textures now, a new structure at the next render()). Lights: the light upload
    /// and a warning for each directional light past kMaxDirectionalLights. Environment: the
    /// environment (an HDRI loaded once per file) and its bake. PostChain: the chain (read at
    /// each frame). Camera: only the stored camera (an orbit should use FrameSettings::camera,
    /// which uploads nothing). Atlases: nothing (atlas regions reach the renderer as texture
    /// slots, MaterialStructure). Value edits never compile a shader. Problems (a missing HDRI,
    /// texture or mesh) are reported to @p problems and a fallback is used. Before initialize()
    /// the parts are only stored; initialize() uploads the whole stored scene.
    void update(const Scene& scene, ScenePart parts, Problems* problems = nullptr);
    /// Takes the whole scene: update(scene, ScenePart::All, problems).
    void setScene(const Scene& scene, Problems* problems = nullptr);
    /// Uploads counted since construction (tests: an orbit uploads nothing, a value edit one
    /// material record).
    UploadStats uploadStats() const;
    /// @}

    /// Warnings the renderer found outside update()'s problem list, since the last call: no
    /// OpenColorIO config could be loaded (Problem::file names the config path; the display
    /// then uses the built-in sRGB curve), or the config has no encoding view for a display
    /// (path "display"). Each is reported once per renderer (again only after
    /// setColorManagement()), and nothing is printed: the host drains this after initialize()
    /// and render() and shows the items (the editor's Log; renderSceneOffscreen appends them to
    /// its problems, which the CLI prints).
    Problems takeWarnings();

    /// The OpenColorIO config the display encoding, the display transforms and the texture
    /// slots' input colour spaces come from. Without one, initialize() loads
    /// ColorManagement::defaultConfigPath() ($OCIO or the shipped config), once for all of them.
    void setColorManagement(std::shared_ptr<const ColorManagement> colorManagement);

    /// Renders one frame into framebuffer @p targetFbo (0: the default framebuffer) at
    /// settings.width x settings.height, display-encoded (the built-in tone mapper + OCIO's
    /// encoding for the display, or the chosen tone-mapping OCIO view). False + message on GL
    /// failure, or, before anything is drawn, on an unknown display, view or look (the message
    /// names it and the config). Each frame first stats the material's texture files (one stat
    /// each) and re-uploads the ones changed on disk, so an image edited in another program shows
    /// without setScene.
    bool render(const FrameSettings& settings, unsigned targetFbo, std::string* error = nullptr);

    /// The last frame's scene-linear HDR colour (before exposure and tone mapping), RGBA float;
    /// empty after a frame that did not write it (FrameSettings::displayOnly).
    Image readLinear() const;
    /// What the last frame drew after the G-buffer (passes, copies, the linear target).
    FramePasses lastFramePasses() const;
    /// The frames in the progressive mean the last FrameSettings::accumulation frame showed.
    int accumulatedSamples() const;
    /// Copies that mean into @p targetFbo and draws nothing (a repaint or a grab of a still
    /// view that has finished refining: the same picture each time); readDisplay() then reads
    /// it. False, with nothing done, when there is no mean of @p width x @p height.
    bool showAccumulated(int width, int height, unsigned targetFbo);
    /// The last frame's display-encoded colour as written to the target, RGBA in [0, 1].
    Image readDisplay() const;

    /// @name Material graph (core/graph/graph_compiler.h)
    /// The scene material's graph is compiled into the G-buffer program as the generated include
    /// "material_graph.glsl". update() with only value or texture-file changes uploads the
    /// value block and rebinds textures (no compile); a structural change starts the new
    /// G-buffer program at the next render() without waiting for it: where the driver compiles
    /// on its own threads (GL_KHR_parallel_shader_compile) each render() polls it and draws the
    /// old program, with the old graph's values and textures, until the new one is adopted. A
    /// host should keep repainting while graphPending(). Without the extension the first
    /// render() builds it synchronously. A graph that fails to compile or link leaves the last
    /// good program drawing.
    /// @{
    /// The preview mesh drawn now: the largest distance of a vertex from the origin (the
    /// built-in meshes fit the unit sphere: about 1; an imported cube fills [-1, 1]^3: sqrt 3).
    /// 1 before initialize().
    float meshRadius() const;
    /// Why the last graph was not compiled, or "" when the drawn program matches the scene.
    const std::string& graphError() const;
    /// A structural graph change is waiting for its program (true until it is adopted or fails).
    bool graphPending() const;
    /// The cache texture nodes load their files through (shared with the material's texture
    /// slots), for node thumbnails (render/graph_preview.h) with this renderer's context current:
    /// a file is decoded once for the frame and its thumbnail.
    TextureCache& graphTextureCache();
    /// Waits for a pending structure's program now (headless rendering: renderSceneOffscreen).
    void finishGraph();
    /// Whether the driver offers GL_KHR_parallel_shader_compile (known after initialize()).
    bool parallelShaderCompile() const;
    /// @}

    /// Number of shader programs compiled since construction (tests assert value edits add none;
    /// a new OCIO display/view/look adds one, a new display encoding one tone-map program (and
    /// one per fused chain pass that tone maps), exposure none).
    int shaderCompileCount() const;
    /// Environments whose irradiance cube the frames at rest integrated (render/irradiance_map.h).
    int irradianceIntegrations() const;
    /// The post-chain runner: its render-target pool and per-step timings (tests, bench).
    PostChainRenderer& postChain();
    FrameTimings lastTimings() const;

    /// @name Texture loading (render/texture_set.h)
    /// Synchronous by default: update() returns with every texture on the GPU. Asynchronous
    /// (the editor): files load on a worker thread and each render() uploads a bounded number of
    /// bytes, coarsest level first; a slot draws its parameter value until its first level is
    /// there, then a coarse proxy, then the full map. A host should keep repainting while
    /// textureProgress().loading > 0; load problems come through takeWarnings().
    /// @{
    void setAsyncTextures(bool async);
    /// A context in this renderer's share group for a thread that makes large textures'
    /// storage, so that no frame waits while the driver allocates it (TextureSet::
    /// setStorageContext; HeadlessContext::workerSharingCurrent, or the editor's own).
    void setTextureStorageContext(std::unique_ptr<WorkerGlContext> context);
    /// @}

    /// @name The mesh's visibility from itself (render/mesh_visibility.h)
    /// Ray traced when a mesh that is not convex is first selected: before update() returns by
    /// default; on a worker thread when asynchronous (the editor: about 90 ms for the shader ball,
    /// more for a large import, that no frame waits for), the mesh drawing without the specular
    /// occlusion until a later render() adopts it. A host should keep repainting while
    /// meshBakePending().
    /// @{
    void setAsyncMeshBake(bool async);
    bool meshBakePending() const;
    /// @}

    /// The 16-byte G-buffer without the lobe channels (render/gbuffer_layout.h): every lobe per
    /// material, its textures as their mean, no anisotropy, as before the lobe channels. For
    /// velvet bench's side-by-side comparison; off by default.
    /// @{
    void setCompactGBuffer(bool compact);
    bool compactGBuffer() const;
    /// Bytes one render() may upload while textures load asynchronously (default 8 MiB).
    void setTextureUploadBudget(std::uint64_t bytes);
    TextureLoadProgress textureProgress() const;
    /// Loads and uploads every texture now (headless rendering: renderSceneOffscreen calls it).
    void finishTextures();
    const TextureUploadStats& textureUploadStats() const;
    /// Image files decoded and on-disk mip cache hits for the material's slots.
    std::uint64_t textureDecodes() const;
    std::uint64_t textureCacheHits() const;
    /// @}

    /// @name Specialised programs (render/lighting_features.h, GeometryFeatures)
    /// The final image's lighting pass is built specialised to what the frame draws: the term
    /// choices every material shares, the lobes some material has, shadows, occlusion, the IBL
    /// bake's state; the G-buffer program to each material's texture slots and lobe map. A new
    /// set of features compiles once, at a frame that follows no value edit; until then (and,
    /// for lighting, while the environment bakes) the generic programs draw.
    /// Off: always the generic programs (velvet bench's comparison, the tests' reference).
    /// @{
    void setSpecialisedPrograms(bool on);
    /// Whether the last frame's surfaces were drawn by a specialised program.
    bool lastFrameSpecialised() const;
    /// The last frame drew a generic program where a specialised one is due (a value edit
    /// forbade its build): a host should draw once more when the edits pause.
    bool specialisationPending() const;
    /// Specialised builds that failed (the generic program drew instead), and the last message.
    int lightingSpecialisationFailures() const;
    std::string lightingSpecialisationError() const;
    /// @}

    /// @name Environment bake (render/ibl_bake.h)
    /// A new HDRI is prefiltered in slices of a few milliseconds at the start of each render()
    /// (at most about 12 ms a frame), so a window never freezes; until the bake completes the
    /// previous environment's bake, or the approximate path, is drawn. A host should keep
    /// repainting while environmentProgress() < 1.
    /// @{
    /// Completion of the environment bake in [0, 1].
    float environmentProgress() const;
    /// Runs the rest of the bake now (headless rendering: renderSceneOffscreen calls it).
    void finishEnvironment();
    /// Slices run since construction: count, worst and total wall-clock milliseconds; and the
    /// one-off shader warm-up of the first sliced frame (llvmpipe compiles a shader's machine
    /// code at its first dispatch), which is not a slice.
    struct EnvironmentBakeStats {
        int slices = 0;
        double worstSliceMs = 0, totalMs = 0;
        double warmUpMs = 0;
        /// The warm-up is spread over frames (about one program's compile each).
        int warmUpFrames = 0;
        double worstWarmUpFrameMs = 0;
    };
    EnvironmentBakeStats environmentBakeStats() const;
    /// @}

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace velvet::render
