#include "render/renderer.h"

#include "core/brdf.h"
#include "core/color_management.h"
#include "core/graph/graph_compiler.h"
#include "core/graph/node_catalogue.h"
#include "core/mesh_import.h"
#include "core/texture_cache.h"
#include "render/camera.h"
#include "render/display_encoding.h"
#include "render/display_transform.h"
#include "render/environment_map.h"
#include "render/gbuffer.h"
#include "render/gbuffer_layout.h"
#include "render/gpu_mesh.h"
#include "render/graph_texture.h"
#include "render/ibl_bake.h"
#include "render/light_passes.h"
#include "render/material_table.h"
#include "render/post_chain.h"
#include "render/shader_program.h"
#include "render/texture_set.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <epoxy/gl.h>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/trigonometric.hpp>
#include <map>

namespace velvet::render {
namespace {

constexpr int kMaxLights = kMaxDirectionalLights;

/// Mirrors FrameBlock in common_frame.glsl (std140; vec4 / mat4 members only).
struct FrameBlock {
    glm::mat4 view, proj, invProj, invView, viewProj;
    glm::vec4 cameraPosition;
    glm::vec4 viewport;
    glm::vec4 envSh[9];
    glm::vec4 envParams;
    glm::vec4 ambientRadiance;
    glm::vec4 backgroundColor;
    glm::ivec4 modes;
    glm::vec4 post;
    glm::vec4 lightDirection[kMaxLights];
    glm::vec4 lightRadiance[kMaxLights];
};

/// Mirrors IblBlock in common_environment.glsl (std140, vec4 only).
struct IblBlock {
    glm::vec4 state;      ///< cube ready, its last level, DFG LUT ready, multiple scattering on
    glm::vec4 background; ///< blurred background level, time (s), unused, unused
};

/// IBL bake time allowed at the start of a frame (render/ibl_bake.h adapts its slices to
/// IblBakeOptions::sliceTargetMs; a frame may run one slice past this).
constexpr double kIblFrameBudgetMs = 12.0;
/// Roughness of the prefiltered level shown by BackgroundMode::Blurred.
constexpr float kBlurredBackgroundRoughness = 0.6f;

std::string glErrorName(GLenum e) {
    switch (e) {
    case GL_INVALID_ENUM:
        return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
        return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
        return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
        return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
        return "GL_OUT_OF_MEMORY";
    default:
        return "GL error " + std::to_string(e);
    }
}

/// Drains the GL error queue; returns the first error's name or "".
std::string takeGlErrors() {
    std::string first;
    for (int i = 0; i < 32; ++i) {
        const GLenum e = glGetError();
        if (e == GL_NO_ERROR)
            break;
        if (first.empty())
            first = glErrorName(e);
    }
    return first;
}

bool fail(std::string* error, const std::string& message) {
    if (error)
        *error = message;
    return false;
}

/// Reads RGBA float pixels of a framebuffer's colour attachment 0 (or the default back buffer),
/// top row first.
Image readFramebuffer(GLuint fbo, int width, int height) {
    Image img(width, height, 4);
    if (width <= 0 || height <= 0)
        return {};
    GLint previous = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glReadBuffer(fbo ? GL_COLOR_ATTACHMENT0 : GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    std::vector<float> rows(size_t(width) * height * 4);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rows.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(previous));
    const size_t rowFloats = size_t(width) * 4;
    for (int y = 0; y < height; ++y)
        std::copy_n(rows.data() + size_t(height - 1 - y) * rowFloats, rowFloats,
                    img.pixels.data() + size_t(y) * rowFloats);
    return img;
}

/// The generated include gbuffer.frag reads (graph_compiler.h's interface).
constexpr const char* kGraphInclude = "material_graph.glsl";

/// Compiles @p material's graph (an empty graph when it has none: a velvetGraph that changes
/// nothing), with the renderer's binding points.
graph::CompiledGraph compileMaterialGraph(const Material& material) {
    const graph::CompileOptions options = graphCompileOptions();
    static const graph::Graph empty;
    return graph::compileGraph(material.graph ? *material.graph : empty, options);
}

/// Views the point, spot and area lights contribute to (debug_views.glsl, isLightView).
bool isLightView(DebugView view) {
    return view == DebugView::Final || view == DebugView::LightsPerPixel ||
           (view >= DebugView::DiffuseOnly && view <= DebugView::ClearcoatOnly);
}

} // namespace

struct Renderer::Impl {
    bool initialized = false;
    bool parallelShaderCompile = false; ///< GL_KHR_parallel_shader_compile (shader_program.h)
    int compileCount = 0;

    /// The material graph compiled into the G-buffer program (render/renderer.h, "Material
    /// graph"): the interface of the linked program, and a structural edit being built (the old
    /// program, with linked's values and textures, draws until the new one is adopted).
    struct GraphTexture {
        GLuint texture = 0;
        std::uint64_t generation = 0;
        int width = 0, height = 0;
    };
    struct GraphState {
        graph::CompiledGraph linked;  ///< what gbufferProgram was built from
        graph::CompiledGraph pending; ///< a new structure, started at the next render()
        bool hasPending = false;      ///< pending is waiting to start or being built
        ProgramBuild build;           ///< pending's G-buffer program in flight
        std::string error; ///< the last graph that failed to compile or link ("" when fine)
        GLuint ubo = 0;
        size_t uboSlots = 0;
        std::vector<GraphTexture> textures; ///< one per linked.samplers entry
        GLuint fallback = 0;                ///< 1x1 white for a texture node without an image
        int uploads = 0;
    } graph;

    ShaderProgram gbufferProgram;
    /// post_tonemap.frag (exposure, built-in curve, display encoding), one per display encoding
    /// (keyed by its OCIO cache id; "" is the hand-written fallback).
    std::map<std::string, std::unique_ptr<ShaderProgram>> tonemapPrograms;
    /// lighting.frag in variants (its header): the surfaces per debug-view family, and the
    /// background per BackgroundMode. Final and the backgrounds are built with the other programs
    /// (a scene edit never compiles); the two debug families the first time a frame asks for them
    /// (a debug-view switch may compile once).
    enum LightingVariant {
        kLitFinal,
        kLitLobeViews,
        kLitGBufferViews,
        kLitBackground, ///< + int(BackgroundMode)
        kLitCount = kLitBackground + 4
    };
    ShaderProgram lightingPrograms[kLitCount];
    /// The HDR colour with the G-buffer's depth (read-only): the lighting pass depth-tests its
    /// full-screen triangles (at the far plane) so surfaces shade only geometry pixels and the
    /// background only the others.
    GLuint litFbo = 0;
    unsigned litFboHdrGeneration = 0, litFboGbufferGeneration = 0;
    /// The geometry pass's target: the G-buffer's attachments plus the HDR colour after them,
    /// which receives each pixel's emission (gbuffer.frag's gEmission).
    GLuint geometryFbo = 0;
    unsigned geometryFboHdrGeneration = 0, geometryFboGbufferGeneration = 0;
    int geometryFboEmission = -1; ///< whether the HDR draw buffer is on (-1: not set yet)
    GBuffer gbuffer;
    ColorTarget hdr;
    // Preview meshes, uploaded once per kind / custom file; a failed custom import is
    // remembered (its message re-reported) so it is not retried at every setScene.
    struct MeshEntry {
        GpuMesh gpu;
        bool doubleSided = false;
        std::string failure;
    };
    std::map<std::string, std::unique_ptr<MeshEntry>> meshes;
    const MeshEntry* mesh = nullptr;
    TextureSet textures;
    MaterialTable materials;
    GpuMaterial packedA{}; ///< the scene's material as last packed (material id 0)
    ColorTarget scaled;    ///< FrameSettings::renderScale < 1: the reduced display-encoded frame
    EnvironmentCache environments;
    GLuint frameUbo = 0;
    GLuint emptyVao = 0;
    IblBaker ibl; ///< prefiltered cube, DFG LUT, sheen tables
    GLuint iblUbo = 0;
    GLuint queries[4] = {};
    GLuint lightsQuery = 0; ///< between the full-screen lighting pass and the local lights
    LightPasses lights;
    bool queriesIssued = false;
    PostChainRenderer post; ///< the scene's post chain, run after lighting
    glm::mat4 lastViewProj{1.0f};
    bool haveLastViewProj = false;

    // The OCIO display transform: the config, the programs (cached by OCIO cache id inside
    // DisplayTransform) and which (display, view, look) maps to which cache id, so that switching
    // back to a view asks OCIO for nothing.
    std::shared_ptr<const ColorManagement> colorManagement;
    DisplayTransform displayTransform;
    std::map<std::string, std::string> displayCacheIds;
    std::string displayKey;
    // The display encoding after a built-in curve (OCIO's shader for the display's un-tone-mapped
    // view): which display maps to which encoding, and whether the config failed to load (the
    // hand-written sRGB OETF then encodes; warned once).
    DisplayEncoding encoding;
    std::map<std::string, std::string> encodingIds;
    bool configFailed = false;

    Scene scene;
    bool haveScene = false;
    const GpuEnvironment* environment = nullptr;

    unsigned lastTarget = 0;
    int lastWidth = 0, lastHeight = 0;
    mutable FrameTimings timings;
    double cpuMs = 0;

    ~Impl() {
        if (frameUbo)
            glDeleteBuffers(1, &frameUbo);
        if (emptyVao)
            glDeleteVertexArrays(1, &emptyVao);
        if (iblUbo)
            glDeleteBuffers(1, &iblUbo);
        if (queries[0])
            glDeleteQueries(4, queries);
        if (lightsQuery)
            glDeleteQueries(1, &lightsQuery);
        if (litFbo)
            glDeleteFramebuffers(1, &litFbo);
        if (geometryFbo)
            glDeleteFramebuffers(1, &geometryFbo);
        releaseGraph();
    }

    /// Whether @p m can emit light: emissive colour x strength above 0, or its material graph
    /// feeds an emission input of the Material output (decides whether a frame writes emission).
    static bool materialEmits(const Material& m) {
        const glm::vec3 e = m.color(ParamId::EmissiveColor) * m.scalar(ParamId::EmissiveStrength);
        if (e.r > 0.0f || e.g > 0.0f || e.b > 0.0f)
            return true;
        const graph::Graph* g = m.graph.get();
        const graph::NodeId out = g ? g->outputNode() : graph::kInvalidNodeId;
        if (out == graph::kInvalidNodeId)
            return false;
        for (ParamId id : {ParamId::EmissiveColor, ParamId::EmissiveStrength})
            if (g->connectionTo(out, graph::PortIndex(graph::outputInputForParam(id))))
                return true;
        return false;
    }

    static LightingVariant lightingVariantFor(DebugView view) {
        if (view == DebugView::Final)
            return kLitFinal;
        if (view == DebugView::LightsPerPixel ||
            (view >= DebugView::DiffuseOnly && view <= DebugView::ClearcoatOnly))
            return kLitLobeViews;
        return kLitGBufferViews;
    }

    /// Builds lighting.frag's variant @p v; false + message on failure (the last good build, if
    /// any, is kept).
    bool buildLightingVariant(LightingVariant v, std::string* error) {
        std::vector<std::string> defines{"FULLSCREEN_FAR_PLANE"};
        if (v == kLitLobeViews)
            defines.emplace_back("LIGHTING_LOBE_VIEWS");
        else if (v == kLitGBufferViews)
            defines.emplace_back("LIGHTING_GBUFFER_VIEWS");
        else if (v >= kLitBackground) {
            defines.emplace_back("LIGHTING_BACKGROUND");
            defines.emplace_back("BACKGROUND_MODE " + std::to_string(v - kLitBackground));
        }
        if (!lightingPrograms[v].build("fullscreen.vert", "lighting.frag", defines, error))
            return false;
        ++compileCount;
        return true;
    }

    /// The variant for @p view, built the first time it is asked for.
    const ShaderProgram* lightingVariant(DebugView view, std::string* error) {
        const LightingVariant v = lightingVariantFor(view);
        if (lightingPrograms[v].id() == 0 && !buildLightingVariant(v, error))
            return nullptr;
        return &lightingPrograms[v];
    }

    void releaseGraph() {
        if (graph.ubo)
            glDeleteBuffers(1, &graph.ubo);
        graph.ubo = 0;
        graph.uboSlots = 0;
        for (GraphTexture& t : graph.textures)
            if (t.texture)
                glDeleteTextures(1, &t.texture);
        graph.textures.clear();
        if (graph.fallback)
            glDeleteTextures(1, &graph.fallback);
        graph.fallback = 0;
    }

    GeneratedSources graphSources() const { return {{kGraphInclude, graph.linked.glsl}}; }

    /// Uploads the value block of the linked graph (a value edit: no shader is touched).
    void uploadGraphValues() {
        const std::vector<glm::vec4>& values = graph.linked.values;
        const size_t slots = std::max<size_t>(values.size(), 1);
        if (!graph.ubo || graph.uboSlots < slots) {
            if (graph.ubo)
                glDeleteBuffers(1, &graph.ubo);
            glCreateBuffers(1, &graph.ubo);
            glNamedBufferStorage(graph.ubo, GLsizeiptr(slots * sizeof(glm::vec4)), nullptr,
                                 GL_DYNAMIC_STORAGE_BIT);
            graph.uboSlots = slots;
        }
        if (!values.empty())
            glNamedBufferSubData(graph.ubo, 0, GLsizeiptr(values.size() * sizeof(glm::vec4)),
                                 values.data());
    }

    /// Loads (through the texture slots' cache) and uploads each texture node's image when its
    /// file, colour space or contents changed. Cheap when nothing did: one cache lookup each.
    void refreshGraphTextures(Problems* problems) {
        const auto& samplers = graph.linked.samplers;
        if (graph.textures.size() > samplers.size()) {
            for (size_t i = samplers.size(); i < graph.textures.size(); ++i)
                if (graph.textures[i].texture)
                    glDeleteTextures(1, &graph.textures[i].texture);
        }
        graph.textures.resize(samplers.size());
        for (size_t i = 0; i < samplers.size(); ++i) {
            GraphTexture& t = graph.textures[i];
            if (samplers[i].file.empty()) {
                t.generation = 0;
                continue;
            }
            const Texture tex = textures.sharedCache().get(samplers[i].file, TextureUsage::Color,
                                                           samplers[i].colorSpace);
            if (problems)
                for (Problem p : tex.problems) {
                    if (p.path.empty())
                        p.path = "graph.nodes (node " + std::to_string(samplers[i].node) + ")";
                    problems->items.push_back(std::move(p));
                }
            if (!tex.image || tex.image->empty()) {
                t.generation = 0;
                continue;
            }
            if (t.texture && t.generation == tex.generation)
                continue;
            uploadGraphTexture(*tex.image, t.texture, t.width, t.height);
            t.generation = tex.generation;
            ++graph.uploads;
        }
    }

    void bindGraph() {
        glBindBufferBase(GL_UNIFORM_BUFFER, GLuint(graphCompileOptions().valuesBinding), graph.ubo);
        if (!graph.fallback)
            graph.fallback = createGraphFallbackTexture();
        for (size_t i = 0; i < graph.linked.samplers.size(); ++i) {
            const GraphTexture* t = i < graph.textures.size() ? &graph.textures[i] : nullptr;
            glBindTextureUnit(GLuint(graph.linked.samplers[i].unit),
                              t && t->texture && t->generation ? t->texture : graph.fallback);
        }
    }

    void unbindGraph() {
        for (const graph::SamplerBinding& s : graph.linked.samplers)
            glBindTextureUnit(GLuint(s.unit), 0);
    }

    /// Takes the scene material's graph: a value or texture edit updates the block and the
    /// bindings now; a structural edit (different shader text) is built at the next render().
    void setGraph(const Material& material, Problems* problems) {
        graph::CompiledGraph next = compileMaterialGraph(material);
        if (!next.ok) {
            graph.error = next.error;
            graph.hasPending = false;
            graph.build.abandon();
            if (problems)
                problems->error("", "graph", next.error + "; the previous graph is kept");
            return;
        }
        if (next.glsl == graph.linked.glsl) { // back to the drawn structure: drop any build
            graph.linked = std::move(next);
            graph.hasPending = false;
            graph.build.abandon();
            uploadGraphValues();
            refreshGraphTextures(problems);
            return;
        }
        if (graph.hasPending && next.glsl == graph.pending.glsl) {
            // The structure in flight with new values: they are uploaded when it is adopted.
            graph.pending = std::move(next);
            return;
        }
        graph.pending = std::move(next);
        graph.hasPending = true;
        graph.build.abandon(); // an older structure in flight is no longer wanted
    }

    /// Starts the G-buffer program for a pending structure, and adopts it once the driver has
    /// finished (polled each frame; with @p wait, now). Until then the old program draws with
    /// linked's interface. A failure keeps the old program and its graph interface (so the
    /// frame still draws) and is reported by graphError().
    void buildPendingGraph(bool wait = false) {
        if (!graph.hasPending)
            return;
        std::string message;
        if (!graph.build.active() &&
            !graph.build.start("gbuffer.vert", "gbuffer.frag", {},
                               {{kGraphInclude, graph.pending.glsl}}, &message)) {
            graph.hasPending = false;
            graph.error = message;
            return;
        }
        if (!wait && !graph.build.ready())
            return; // the driver's threads are still compiling: draw the old program
        graph.hasPending = false;
        if (!graph.build.finish(gbufferProgram, &message)) {
            graph.error = message;
            return;
        }
        ++compileCount;
        graph.error.clear();
        graph.linked = std::move(graph.pending);
        graph.pending = {};
        uploadGraphValues();
        refreshGraphTextures(nullptr);
    }

    /// Builds every program from disk. With @p keepGoing (shader reload) a failed program keeps
    /// its last good build, the others are still rebuilt and the errors are joined.
    bool buildPrograms(std::string* error, bool keepGoing = false) {
        struct {
            ShaderProgram& program;
            const char* vs;
            const char* fs;
        } programs[] = {{gbufferProgram, "gbuffer.vert", "gbuffer.frag"}};
        std::string errors;
        for (auto& p : programs) {
            std::string message;
            const GeneratedSources generated =
                &p.program == &gbufferProgram ? graphSources() : GeneratedSources{};
            if (!p.program.build(p.vs, p.fs, {}, generated, &message)) {
                errors += (errors.empty() ? "" : "\n") + message;
                if (!keepGoing)
                    break;
                continue;
            }
            ++compileCount;
        }
        // lighting.frag: Final and Background always (the first frame needs them), the debug
        // families again only when built before (a reload).
        for (int v = 0; v < kLitCount && (keepGoing || errors.empty()); ++v) {
            if ((v == kLitLobeViews || v == kLitGBufferViews) && lightingPrograms[v].id() == 0)
                continue;
            std::string message;
            if (!buildLightingVariant(LightingVariant(v), &message))
                errors += (errors.empty() ? "" : "\n") + message;
        }
        if (!errors.empty() && error)
            *error = errors;
        return errors.empty();
    }

    /// The config, loading ColorManagement::defaultConfigPath() the first time; null when it
    /// cannot be loaded (warned once on stderr: frames then use the hand-written sRGB OETF).
    const ColorManagement* config() {
        if (!colorManagement && !configFailed) {
            auto loaded = std::make_shared<ColorManagement>();
            std::string message;
            if (loaded->loadDefault(&message)) {
                colorManagement = std::move(loaded);
            } else {
                configFailed = true;
                std::fprintf(stderr,
                             "velvet: warning: no OpenColorIO config could be loaded (%s); the "
                             "display is encoded with the built-in sRGB curve instead of OCIO\n",
                             message.c_str());
            }
        }
        return colorManagement.get();
    }

    /// Whether the frame's display goes through OCIO alone (a tone-mapping view such as ACES or
    /// AgX, a view without a view transform such as Raw, or a look, which must act on
    /// scene-linear values before any curve) rather than the built-in curve followed by OCIO's
    /// encoding. False + message on an unknown display or view.
    bool ocioToneMaps(const FrameSettings& fs, bool& toneMaps, std::string* error) {
        toneMaps = false;
        if (!fs.usesColorManagement())
            return true;
        const ColorManagement* cm = config();
        if (!cm)
            return fail(error, "a display/view was chosen but no OpenColorIO config could be "
                               "loaded from " +
                                   ColorManagement::defaultConfigPath().string());
        const std::optional<bool> encodes = cm->isEncodingView(fs.display, fs.displayView, error);
        if (!encodes)
            return false;
        toneMaps = !*encodes || !fs.look.empty();
        return true;
    }

    /// Selects the encoding of @p display for the built-in curves (the fallback without a config).
    bool selectEncoding(const std::string& display, std::string* error) {
        const ColorManagement* cm = config();
        if (!cm) {
            encoding.selectFallback();
            return true;
        }
        if (const auto it = encodingIds.find(display);
            it != encodingIds.end() && encoding.selectCached(it->second))
            return true;
        const std::optional<GpuDisplayTransform> t =
            cm->gpuDisplayEncoding(display, error, DisplayEncoding::options());
        if (!t || !encoding.select(*t, error))
            return false;
        encodingIds[display] = t->cacheId;
        return true;
    }

    /// post_tonemap.frag for the selected encoding, compiled the first time it is used.
    ShaderProgram* tonemapProgram(std::string* error) {
        auto& program = tonemapPrograms[encoding.cacheId()];
        if (program)
            return program.get();
        auto built = std::make_unique<ShaderProgram>();
        if (!buildTonemap(*built, encoding.cacheId(), error)) {
            tonemapPrograms.erase(encoding.cacheId());
            return nullptr;
        }
        return (program = std::move(built)).get();
    }

    bool buildTonemap(ShaderProgram& program, const std::string& encodingId, std::string* error) {
        if (!program.build("fullscreen.vert", "display_output.frag", {}, encoding.sources(encodingId),
                           error))
            return false;
        encoding.setUniforms(program.id(), encodingId);
        ++compileCount;
        return true;
    }

    /// Selects the display transform @p fs names, building it the first time. Exposure is left
    /// out of the key and extracted as 0: it is a dynamic uniform set at every draw.
    bool selectDisplayTransform(const FrameSettings& fs, std::string* error) {
        const std::string key = fs.display + '\n' + fs.displayView + '\n' + fs.look;
        if (key == displayKey && displayTransform.hasSelection())
            return true;
        if (const auto it = displayCacheIds.find(key);
            it != displayCacheIds.end() && displayTransform.selectCached(it->second)) {
            displayKey = key;
            return true;
        }
        if (!config())
            return fail(error, "no OpenColorIO config could be loaded from " +
                                   ColorManagement::defaultConfigPath().string());
        const DisplaySettings settings{fs.display, fs.displayView, fs.look, 0.0f};
        const std::optional<GpuDisplayTransform> transform =
            colorManagement->gpuDisplayTransform(settings, error);
        if (!transform || !displayTransform.select(*transform, error))
            return false;
        displayCacheIds[key] = transform->cacheId;
        displayKey = key;
        return true;
    }

    /// Selects (uploading once) the mesh @p ref names; a custom mesh that fails to import is
    /// reported and the sphere drawn instead.
    void selectMesh(const MeshRef& ref, Problems* problems) {
        const bool custom = ref.kind == PreviewMeshKind::Custom;
        const std::string key = std::to_string(int(ref.kind)) + (custom ? ":" + ref.file : "");
        auto& entry = meshes[key];
        if (!entry) {
            entry = std::make_unique<MeshEntry>();
            MeshData data;
            std::string error;
            // importMesh runs `velvet import-mesh` in a child process when the application set
            // the helper, in process otherwise (core/mesh_import.h).
            if (custom && ref.file.empty())
                entry->failure = "a custom mesh needs a file";
            else if (custom && !importMesh(ref.file, data, &error))
                entry->failure = error;
            else if (!custom)
                data = makePreviewMesh(ref.kind);
            if (entry->failure.empty()) {
                entry->gpu.upload(data);
                entry->doubleSided = data.doubleSided;
            }
        }
        if (!entry->failure.empty()) {
            if (problems)
                problems->error(ref.file, "mesh", entry->failure + "; showing the sphere");
            selectMesh(MeshRef{}, nullptr);
            return;
        }
        mesh = entry.get();
    }

    /// The material record: parameters, then texture presence bits and the means of the slots
    /// the G-buffer cannot carry (render/texture_set.h). Never a shader.
    void uploadMaterial() {
        GpuMaterial g = packMaterial(scene.material);
        textures.applyTo(g);
        packedA = g;
        materials.upload({g});
    }

    /// A/B split: material id 1 is FrameSettings::splitMaterial with A's textures.
    void uploadSplitMaterial(const Material& b) {
        GpuMaterial g = packMaterial(b);
        textures.applyTo(g);
        materials.upload({packedA, g});
    }

    /// Runs scene.post on the lit HDR target (render/post_chain.h).
    bool runPost(const FrameSettings& fs, const FrameBlock& b, unsigned targetFbo, bool ocioAll,
                 unsigned& finalInput, bool& displayed, std::string* error) {
        gbuffer.bindTextures(); // depth and normals for motion blur, DoF, toon, vaporwave
        PostRunInputs in;
        in.hdrTexture = hdr.texture();
        in.width = fs.width;
        in.height = fs.height;
        in.viewProj = b.viewProj;
        in.proj = b.proj;
        in.prevViewProj = fs.hasPreviousViewProj ? fs.previousViewProj
                          : haveLastViewProj     ? lastViewProj
                                                 : b.viewProj;
        in.time = fs.time;
        in.exposureEv = fs.exposureEv;
        // The tonemap effect's operator indices: pbr-neutral, aces, reinhard, …, linear (5).
        in.implicitToneMapper = fs.toneMapper == ToneMapper::AcesFitted ? 1
                                : fs.toneMapper == ToneMapper::Reinhard ? 2
                                : fs.toneMapper == ToneMapper::Linear   ? 5
                                                                        : 0;
        in.forceDisplayTransform = ocioAll;
        in.encoding = &encoding;
        in.displayTransform = [this, &fs, ocioAll](unsigned texture, float ev, std::string* err) {
            // The "display" operator with an encoding-only view: the full transform of fs.
            if (!ocioAll && !selectDisplayTransform(fs, err))
                return false;
            displayTransform.draw(texture, fs.exposureEv + ev);
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

    FrameBlock frameBlock(const FrameSettings& fs) const {
        FrameBlock b{};
        const Camera& cam = scene.camera;
        const float aspect = float(fs.width) / float(std::max(fs.height, 1));
        b.view = viewMatrix(cam);
        b.proj = projectionMatrix(cam, aspect);
        b.invProj = glm::inverse(b.proj);
        b.invView = glm::inverse(b.view);
        b.viewProj = b.proj * b.view;
        b.cameraPosition = glm::vec4(cameraEye(cam), cam.orthographic ? 1.0f : 0.0f);
        b.viewport = glm::vec4(float(fs.width), float(fs.height), 1.0f / float(fs.width),
                               1.0f / float(fs.height));
        const Environment& env = scene.environment;
        for (int i = 0; i < 9; ++i)
            b.envSh[i] = glm::vec4(environment->sh[i] * env.intensity, 0.0f);
        const float rot = glm::radians(env.rotationDeg);
        b.envParams =
            glm::vec4(std::cos(rot), std::sin(rot), env.intensity, float(environment->levels - 1));
        glm::vec3 ambient(0.0f);
        int count = 0;
        for (const Light& l : scene.lights) {
            if (l.type == LightType::Ambient) {
                ambient += l.color * l.intensity;
            } else if (l.type == LightType::Directional && count < kMaxLights) {
                const float len = glm::length(l.direction);
                const glm::vec3 toLight = len > 0.0f ? -l.direction / len : glm::vec3(0, 1, 0);
                b.lightDirection[count] = glm::vec4(toLight, 0.0f);
                b.lightRadiance[count] = glm::vec4(l.color * l.intensity, 0.0f);
                ++count;
            }
            // Point, spot and area lights: LightPasses (render/light_passes.h).
        }
        b.ambientRadiance = glm::vec4(ambient, 0.0f);
        const float backgroundLod = env.background == BackgroundMode::Blurred
                                        ? std::min(4.0f, float(environment->levels - 1))
                                        : 0.0f;
        b.backgroundColor = glm::vec4(env.backgroundColor, backgroundLod);
        b.modes = glm::ivec4(count, int(fs.view), int(fs.toneMapper), int(env.background));
        b.post = glm::vec4(std::exp2(fs.exposureEv), 2.0f * std::max(cam.distance, 0.1f),
                           float(environment->width), 0.0f);
        return b;
    }
};

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
    d.graph.linked = compileMaterialGraph(d.scene.material);
    if (!d.graph.linked.ok) { // too many texture nodes: start without the graph
        d.graph.error = d.graph.linked.error;
        d.graph.linked = compileMaterialGraph(Material{});
    }
    if (!d.buildPrograms(error))
        return false;
    // The default display's tone-map program too, so that the first frame and every value edit
    // after it compile nothing (the encoding comes from the config, loaded here if none is set).
    if (!d.selectEncoding({}, error) || !d.tonemapProgram(error))
        return false;
    glCreateBuffers(1, &d.frameUbo);
    glNamedBufferStorage(d.frameUbo, sizeof(FrameBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glCreateVertexArrays(1, &d.emptyVao);
    glCreateQueries(GL_TIMESTAMP, 4, d.queries);
    glCreateQueries(GL_TIMESTAMP, 1, &d.lightsQuery);
    if (!d.lights.initialize(error))
        return false;
    d.compileCount += d.lights.compileCount();
    if (d.haveScene)
        d.lights.upload(d.scene.lights);
    if (!d.ibl.initialize(error))
        return false;
    d.compileCount += 3; // the IBL bake's compute programs
    glCreateBuffers(1, &d.iblUbo);
    glNamedBufferStorage(d.iblUbo, sizeof(IblBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
    d.selectMesh(d.scene.mesh, nullptr);
    d.textures.setMaterial(d.scene.material, nullptr);
    d.uploadMaterial();
    d.uploadGraphValues();
    d.refreshGraphTextures(nullptr);
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
    d.graph.build.abandon(); // a structure in flight restarts next frame, from the files on disk
    const int lightCompiles = d.lights.compileCount();
    collect(d.lights.reload(&message), message);
    d.compileCount += d.lights.compileCount() - lightCompiles;
    collect(d.ibl.reload(&message, &d.compileCount), message);
    collect(d.displayTransform.reload(&message), message);
    for (auto& [id, program] : d.tonemapPrograms)
        collect(d.buildTonemap(*program, id, &message), message);
    collect(d.post.reload(&message), message); // counted by shaderCompileCount() through post
    if (!errors.empty())
        return fail(error, errors);
    return true;
}

void Renderer::setColorManagement(std::shared_ptr<const ColorManagement> colorManagement) {
    Impl& d = *m_impl;
    d.colorManagement = std::move(colorManagement);
    // Names may mean other transforms in another config; compiled programs stay valid (same
    // cache id, same shader).
    d.displayCacheIds.clear();
    d.displayKey.clear();
    d.encodingIds.clear();
    d.configFailed = false;
    // Input colour space names are looked up in the new config too.
    d.textures.setColorManagement(d.colorManagement);
    if (d.initialized) {
        d.textures.setMaterial(d.scene.material, nullptr);
        d.uploadMaterial();
    }
}

void Renderer::setScene(const Scene& scene, Problems* problems) {
    Impl& d = *m_impl;
    d.scene = scene;
    d.haveScene = true;
    if (!d.initialized)
        return; // uploaded by initialize()
    d.selectMesh(scene.mesh, problems);
    d.textures.setMaterial(scene.material, problems);
    // Numbers only: rewrite the material table (never a shader).
    d.uploadMaterial();
    // The graph: values and textures now, a new structure at the next render().
    d.setGraph(scene.material, problems);
    d.lights.upload(scene.lights);
    if (problems) {
        // The full-screen pass has a fixed array of directional lights (MAX_LIGHTS in
        // common_frame.glsl); frameBlock() draws the first kMaxLights and drops the rest.
        int directional = 0;
        for (size_t i = 0; i < scene.lights.size(); ++i)
            if (scene.lights[i].type == LightType::Directional && ++directional > kMaxLights)
                problems->warning("", "lights[" + std::to_string(i) + "]",
                                  "directional light " + std::to_string(directional) +
                                      " is not drawn: the renderer draws the first " +
                                      std::to_string(kMaxLights) + " directional lights only");
    }
    d.environment = &d.environments.get(scene.environment, problems);
    d.ibl.request(*d.environment);
}

bool Renderer::render(const FrameSettings& fs, unsigned targetFbo, std::string* error) {
    Impl& d = *m_impl;
    if (!d.initialized)
        return fail(error, "Renderer::render called before initialize()");
    if (fs.width <= 0 || fs.height <= 0 || fs.width > 16384 || fs.height > 16384)
        return fail(error, "invalid frame size " + std::to_string(fs.width) + "x" +
                               std::to_string(fs.height));
    if (fs.renderScale > 0.0f && fs.renderScale < 1.0f) {
        // Reduced resolution: the whole frame at the smaller size into our own target, then
        // stretched over the caller's (one linear blit).
        const auto scaledStart = std::chrono::steady_clock::now();
        FrameSettings inner = fs;
        inner.renderScale = 1.0f;
        inner.width = std::max(1, int(std::lround(float(fs.width) * fs.renderScale)));
        inner.height = std::max(1, int(std::lround(float(fs.height) * fs.renderScale)));
        if (!d.scaled.resize(inner.width, inner.height, GL_RGBA8, error) ||
            !render(inner, d.scaled.framebuffer(), error))
            return false;
        glBlitNamedFramebuffer(d.scaled.framebuffer(), targetFbo, 0, 0, inner.width, inner.height,
                               0, 0, fs.width, fs.height, GL_COLOR_BUFFER_BIT, GL_LINEAR);
        glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);
        d.lastTarget = targetFbo;
        d.lastWidth = fs.width;
        d.lastHeight = fs.height;
        d.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() -
                                                            scaledStart)
                      .count();
        if (const std::string e = takeGlErrors(); !e.empty())
            return fail(error, "OpenGL error while stretching a reduced frame: " + e);
        return true;
    }
    const auto cpuStart = std::chrono::steady_clock::now();
    takeGlErrors(); // errors left by whoever owns the context are not ours
    // A texture file changed on disk (edited in another program): re-upload, re-pack the record.
    if (d.textures.poll())
        d.uploadMaterial();
    // A structural graph edit: start the new G-buffer program, or adopt it once the driver's
    // compiler threads have finished (GL_KHR_parallel_shader_compile); meanwhile this frame
    // draws the old program, so the window never waits for a compile. Without the extension the
    // build completes here (the frame waits, as before). A failure keeps the old program
    // (graphError()).
    d.buildPendingGraph();
    d.refreshGraphTextures(nullptr); // files changed on disk (polled above) re-upload
    // lighting.frag's variant for this view (built the first time a debug family is shown).
    const ShaderProgram* surfaceProgram = d.lightingVariant(fs.view, error);
    if (!surfaceProgram)
        return false;
    // An unknown display, view or look fails here, before anything is drawn. A tone-mapping view
    // (or a look) is OCIO's alone; otherwise the built-in curve runs and OCIO's shader for the
    // display's un-tone-mapped view encodes (debug views use that encoding too).
    bool ocioAll = false;
    if (!d.ocioToneMaps(fs, ocioAll, error))
        return false;
    const bool ocioDisplay = ocioAll && fs.view == DebugView::Final;
    if (ocioDisplay && !d.selectDisplayTransform(fs, error))
        return false;
    if (!d.selectEncoding(fs.display, error))
        return false;
    ShaderProgram* tonemap = d.tonemapProgram(error);
    if (!tonemap)
        return false;
    // Every frame (a stat of the HDRI): an HDRI edited on disk is read and prefiltered again.
    d.environment = &d.environments.get(d.scene.environment, nullptr);
    // Environment prefiltering: a few slices per frame (render/ibl_bake.h).
    d.ibl.request(*d.environment);
    {
        const auto iblStart = std::chrono::steady_clock::now();
        d.ibl.step(kIblFrameBudgetMs);
        d.timings.iblMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - iblStart)
                .count();
    }
    if (!d.gbuffer.resize(fs.width, fs.height, error) ||
        !d.hdr.resize(fs.width, fs.height, GL_RGBA16F, error))
        return false;
    if (targetFbo != 0) {
        const GLenum status = glCheckNamedFramebufferStatus(targetFbo, GL_DRAW_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            return fail(error, "target framebuffer " + std::to_string(targetFbo) +
                                   " is incomplete: " + framebufferStatusName(status));
    }

    const FrameBlock block = d.frameBlock(fs);
    glNamedBufferSubData(d.frameUbo, 0, sizeof(FrameBlock), &block);
    glBindBufferBase(GL_UNIFORM_BUFFER, binding::kFrameUbo, d.frameUbo);
    if (fs.splitMaterial)
        d.uploadSplitMaterial(*fs.splitMaterial);
    d.materials.bind();

    // Known state: a host (Qt) may leave anything bound or enabled.
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_MULTISAMPLE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glViewport(0, 0, fs.width, fs.height);
    glQueryCounter(d.queries[0], GL_TIMESTAMP);

    // 1. G-buffer, and emission into the HDR target (attachment gbufferColorAttachmentCount()).
    const bool emission = Impl::materialEmits(d.scene.material) ||
                          (fs.splitMaterial && Impl::materialEmits(*fs.splitMaterial));
    {
        GLint depthTexture = 0;
        glGetNamedFramebufferAttachmentParameteriv(d.gbuffer.framebuffer(), GL_DEPTH_ATTACHMENT,
                                                   GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME,
                                                   &depthTexture);
        if (!d.geometryFbo)
            glCreateFramebuffers(1, &d.geometryFbo);
        if (d.geometryFboHdrGeneration != d.hdr.generation() ||
            d.geometryFboGbufferGeneration != d.gbuffer.generation()) {
            const int n = gbufferColorAttachmentCount();
            std::vector<GLenum> drawBuffers;
            for (int i = 0; i < n; ++i) {
                GLint texture = 0;
                glGetNamedFramebufferAttachmentParameteriv(
                    d.gbuffer.framebuffer(), GLenum(GL_COLOR_ATTACHMENT0 + i),
                    GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &texture);
                glNamedFramebufferTexture(d.geometryFbo, GLenum(GL_COLOR_ATTACHMENT0 + i),
                                          GLuint(texture), 0);
                drawBuffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + i));
            }
            glNamedFramebufferTexture(d.geometryFbo, GLenum(GL_COLOR_ATTACHMENT0 + n),
                                      d.hdr.texture(), 0);
            drawBuffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + n));
            glNamedFramebufferTexture(d.geometryFbo, GL_DEPTH_ATTACHMENT, GLuint(depthTexture), 0);
            glNamedFramebufferDrawBuffers(d.geometryFbo, GLsizei(drawBuffers.size()),
                                          drawBuffers.data());
            const GLenum status = glCheckNamedFramebufferStatus(d.geometryFbo, GL_FRAMEBUFFER);
            if (status != GL_FRAMEBUFFER_COMPLETE)
                return fail(error,
                            "geometry framebuffer incomplete: " + framebufferStatusName(status));
            d.geometryFboHdrGeneration = d.hdr.generation();
            d.geometryFboGbufferGeneration = d.gbuffer.generation();
            d.geometryFboEmission = -1;
        }
        // Writing emission costs a 16-bit RGBA store per pixel and a blend in the lighting pass
        // (about 5 ms of a 58 ms 1280x720 frame on llvmpipe): only frames that can emit pay.
        if (d.geometryFboEmission != int(emission)) {
            const int n = gbufferColorAttachmentCount();
            std::vector<GLenum> drawBuffers;
            for (int i = 0; i < n; ++i)
                drawBuffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + i));
            drawBuffers.push_back(emission ? GLenum(GL_COLOR_ATTACHMENT0 + n) : GLenum(GL_NONE));
            glNamedFramebufferDrawBuffers(d.geometryFbo, GLsizei(drawBuffers.size()),
                                          drawBuffers.data());
            d.geometryFboEmission = int(emission);
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, d.geometryFbo);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    const float zeros[4] = {0, 0, 0, 0};
    const float noEmission[4] = {0, 0, 0, 1}; // the HDR target: black, opaque
    const auto clearGeometry = [&] {
        for (int i = 0; i < gbufferColorAttachmentCount(); ++i)
            glClearBufferfv(GL_COLOR, i, zeros);
        if (emission)
            glClearBufferfv(GL_COLOR, gbufferColorAttachmentCount(), noEmission);
    };
    clearGeometry();
    const float farDepth = 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &farDepth);
    glUseProgram(d.gbufferProgram.id());
    glProgramUniform1i(d.gbufferProgram.id(), 0, 0); // uMaterialId: one material for now
    d.textures.bind(d.gbufferProgram.id());
    d.bindGraph();
    if (d.mesh->doubleSided)
        glDisable(GL_CULL_FACE);
    d.mesh->gpu.draw();
    if (fs.splitMaterial) {
        // A/B split: the right part again, from a cleared G-buffer, with material B (id 1).
        const int seam = std::clamp(
            int(std::lround(std::clamp(fs.splitPosition, 0.0f, 1.0f) * fs.width)), 0, fs.width);
        glEnable(GL_SCISSOR_TEST);
        glScissor(seam, 0, fs.width - seam, fs.height);
        clearGeometry();
        glClearBufferfv(GL_DEPTH, 0, &farDepth);
        glProgramUniform1i(d.gbufferProgram.id(), 0, 1);
        d.mesh->gpu.draw();
        glProgramUniform1i(d.gbufferProgram.id(), 0, 0);
        glDisable(GL_SCISSOR_TEST);
    }
    d.textures.unbind();
    d.unbindGraph();
    glQueryCounter(d.queries[1], GL_TIMESTAMP);

    // 2. Lighting + background into the HDR target, with the G-buffer depth read-only.
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    {
        GLint depthTexture = 0;
        glGetNamedFramebufferAttachmentParameteriv(d.gbuffer.framebuffer(), GL_DEPTH_ATTACHMENT,
                                                   GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME,
                                                   &depthTexture);
        if (!d.litFbo)
            glCreateFramebuffers(1, &d.litFbo);
        if (d.litFboHdrGeneration != d.hdr.generation() ||
            d.litFboGbufferGeneration != d.gbuffer.generation()) {
            glNamedFramebufferTexture(d.litFbo, GL_COLOR_ATTACHMENT0, d.hdr.texture(), 0);
            glNamedFramebufferTexture(d.litFbo, GL_DEPTH_ATTACHMENT, GLuint(depthTexture), 0);
            d.litFboHdrGeneration = d.hdr.generation();
            d.litFboGbufferGeneration = d.gbuffer.generation();
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, d.litFbo);
    d.gbuffer.bindTextures();
    glBindTextureUnit(binding::kEnvironmentTex, d.environment->texture);
    glBindTextureUnit(binding::kSheenLutTex, d.ibl.sheenLut());
    glBindTextureUnit(binding::kIblSpecularTex, d.ibl.specularCube());
    glBindTextureUnit(binding::kIblDfgTex, d.ibl.dfgLut());
    {
        const int levels = d.ibl.specularLevels();
        const IblBlock iblBlock{
            glm::vec4(d.ibl.specularReady() ? 1.0f : 0.0f, float(std::max(levels - 1, 0)),
                      d.ibl.dfgReady() ? 1.0f : 0.0f, fs.specularMultiScatter ? 1.0f : 0.0f),
            glm::vec4(kBlurredBackgroundRoughness * float(std::max(levels - 1, 0)), fs.time, 0.0f,
                      0.0f)};
        glNamedBufferSubData(d.iblUbo, 0, sizeof(IblBlock), &iblBlock);
        glBindBufferBase(GL_UNIFORM_BUFFER, binding::kIblUbo, d.iblUbo);
        glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    }
    glBindVertexArray(d.emptyVao);
    if (!emission) // nothing in the HDR target yet: start from black, opaque
        glClearBufferfv(GL_COLOR, 0, noEmission);
    // Triangles at the far plane: GL_EQUAL passes where nothing was drawn (the background),
    // GL_GREATER where there is geometry (the surfaces), so neither pays for the other.
    glEnable(GL_DEPTH_TEST);
    if (fs.view == DebugView::Final) {
        glDepthFunc(GL_EQUAL);
        // Blurred falls back to Sharp (the same lookup) until the prefiltered cube is ready.
        BackgroundMode mode = d.scene.environment.background;
        if (mode == BackgroundMode::Blurred && !d.ibl.specularReady())
            mode = BackgroundMode::Sharp;
        const int m = int(mode) >= 0 && int(mode) <= 3 ? int(mode) : 0; // unknown: Sharp (as GLSL)
        glUseProgram(d.lightingPrograms[Impl::kLitBackground + m].id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    } // debug views: no background (the HDR target is black)
    glDepthFunc(GL_GREATER);
    // result = surface + emission x alpha (lighting.frag's header); the target's alpha stays 1.
    // Without emission the surfaces replace the black (no blend to pay for), alpha left at 1.
    if (emission) {
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_ONE);
    } else {
        glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
    }
    glUseProgram(surfaceProgram->id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glQueryCounter(d.lightsQuery, GL_TIMESTAMP);
    // Point, spot and area lights, added on top by the path the frame asks for.
    if (isLightView(fs.view))
        d.lights.draw(fs.lightPath, fs.width, fs.height, d.gbuffer.framebuffer(),
                      d.hdr.framebuffer(), d.hdr.texture(), d.emptyVao);
    glQueryCounter(d.queries[2], GL_TIMESTAMP);

    // 3. The scene's post chain. When it tone maps it writes the target itself; otherwise its
    // HDR result feeds the final pass below (an empty chain changes nothing).
    unsigned finalInput = d.hdr.texture();
    bool chainDisplayed = false;
    if (fs.view == DebugView::Final && PostChainRenderer::hasEnabledEffects(d.scene.post)) {
        if (!d.runPost(fs, block, targetFbo, ocioAll, finalInput, chainDisplayed, error))
            return false;
        glViewport(0, 0, fs.width, fs.height);
        glBindVertexArray(d.emptyVao);
    }
    d.lastViewProj = block.viewProj;
    d.haveLastViewProj = true;

    // 4. Into the target: OCIO's display transform (exposure, look, display/view in one generated
    // function), or the built-in exposure and tone-mapping curve followed by OCIO's display
    // encoding (one pass: OCIO's function is composed into post_tonemap.frag).
    glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);
    if (chainDisplayed) {
        // done by the chain's tone map and LDR effects
    } else if (ocioDisplay) {
        d.displayTransform.draw(finalInput, fs.exposureEv);
    } else {
        glBindTextureUnit(binding::kHdrTex, finalInput);
        d.encoding.bindLuts();
        glUseProgram(tonemap->id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        d.encoding.unbindLuts();
    }
    glQueryCounter(d.queries[3], GL_TIMESTAMP);
    d.queriesIssued = true;

    // Leave sane defaults for the host.
    glUseProgram(0);
    glBindVertexArray(0);
    glDepthMask(GL_TRUE);
    for (GLuint unit :
         {0u, 1u, 2u, 3u, GLuint(binding::kEnvironmentTex), GLuint(binding::kSheenLutTex),
          GLuint(binding::kHdrTex), GLuint(binding::kIblSpecularTex), GLuint(binding::kIblDfgTex)})
        glBindTextureUnit(unit, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);

    d.lastTarget = targetFbo;
    d.lastWidth = fs.width;
    d.lastHeight = fs.height;
    d.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpuStart)
                  .count();
    if (const std::string e = takeGlErrors(); !e.empty())
        return fail(error, "OpenGL error while rendering: " + e);
    return true;
}

Image Renderer::readLinear() const {
    const Impl& d = *m_impl;
    if (!d.initialized || !d.hdr.framebuffer())
        return {};
    return readFramebuffer(d.hdr.framebuffer(), d.hdr.width(), d.hdr.height());
}

Image Renderer::readDisplay() const {
    const Impl& d = *m_impl;
    if (!d.initialized || d.lastWidth == 0)
        return {};
    return readFramebuffer(d.lastTarget, d.lastWidth, d.lastHeight);
}

const std::string& Renderer::graphError() const {
    return m_impl->graph.error;
}

bool Renderer::graphPending() const {
    return m_impl->graph.hasPending;
}

TextureCache& Renderer::graphTextureCache() {
    return m_impl->textures.sharedCache();
}

void Renderer::finishGraph() {
    if (m_impl->initialized)
        m_impl->buildPendingGraph(/*wait=*/true);
}

bool Renderer::parallelShaderCompile() const {
    return m_impl->parallelShaderCompile;
}

int Renderer::shaderCompileCount() const {
    return m_impl->compileCount + m_impl->displayTransform.compileCount() +
           m_impl->post.compileCount();
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

bool graphOutputIsPerPixel(std::string_view field) {
    // What gbuffer.frag reads back from velvetGraph(): keep in step with it.
    static constexpr std::string_view kPerPixel[] = {
        "baseColor", "metallic",          "roughness",     "normal",          "normalScale",
        "occlusion", "occlusionStrength", "emissionColor", "emissionStrength"};
    for (std::string_view f : kPerPixel)
        if (f == field)
            return true;
    return false;
}

} // namespace velvet::render
