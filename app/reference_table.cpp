// The viewport-versus-reference table (app/reference_table.h).
#include "app/reference_table.h"

#include "core/default_stage.h"
#include "core/document_io.h"
#include "core/image_ops.h"
#include "core/light_rigs.h"
#include "core/resources.h"
#include "reference/reference_renderer.h"
#include "render/headless_context.h"
#include "render/offscreen.h"
#include "render/progressive_accumulation.h"
#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

namespace velvet::cli {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

std::string meshName(PreviewMeshKind kind) {
    return std::string(previewMeshKindNames()[size_t(kind)]);
}

} // namespace

std::vector<std::string> libraryPresets() {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(resources::path("presets"), ec))
        if (entry.path().extension() == ".json")
            names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::optional<Scene> referenceTableScene(const ReferenceTableCase& c, Problems& problems) {
    const std::filesystem::path file = resources::path("presets") / (c.preset + ".json");
    std::optional<Material> material = loadMaterialFile(file, problems);
    if (!material || problems.hasErrors())
        return std::nullopt;
    Scene scene = stageSceneWithMaterial(*material, &problems);
    scene.materialPreset = file.string();
    scene.mesh.kind = c.mesh;
    auto lights = lightRigLights(c.rig);
    if (!lights) {
        problems.error(c.rig, "rig", "unknown light rig");
        return std::nullopt;
    }
    scene.lights = std::move(*lights);
    // The stage the editor puts the mesh on (screen-space occlusion for the shader ball: the
    // viewport's best stand-in for what the path tracer finds), less the ground, which the
    // reference does not have.
    applyStageDefaults(scene.environment, c.mesh);
    scene.environment.ground = GroundMode::Off;
    return scene;
}

struct ReferenceTable::Impl {
    std::unique_ptr<render::HeadlessContext> context;
    std::unique_ptr<render::Renderer> renderer;
    std::unique_ptr<render::OffscreenTarget> target;
    bool first = true;
    ~Impl() { // GL objects die with the context current
        target.reset();
        renderer.reset();
    }
};

ReferenceTable::ReferenceTable() : m_impl(std::make_unique<Impl>()) {}
ReferenceTable::~ReferenceTable() = default;

bool ReferenceTable::start(std::string* error) {
    if (!render::HeadlessContext::isAnyContextCurrent()) {
        m_impl->context = render::HeadlessContext::create(error);
        if (!m_impl->context)
            return false;
    }
    m_impl->renderer = std::make_unique<render::Renderer>();
    m_impl->target = std::make_unique<render::OffscreenTarget>();
    return m_impl->renderer->initialize(error);
}

static_assert(ReferenceTableOptions{}.reflectionSamples == render::kRefinementReflectionSamples,
              "the table compares the viewport as it stands at rest");

bool ReferenceTable::measure(const ReferenceTableCase& c, const ReferenceTableOptions& options,
                             ReferenceTableRow& row, std::string* error) {
    row = {};
    row.c = c;
    Problems problems;
    std::optional<Scene> scene = referenceTableScene(c, problems);
    if (!scene) {
        *error = c.preset + ": ";
        for (const Problem& p : problems.items)
            *error += p.toString() + "; ";
        return false;
    }
    const int n = std::max(options.size, 1), ss = std::max(options.supersample, 1);
    render::Renderer& renderer = *m_impl->renderer;
    if (!m_impl->target->resize(n * ss, n * ss, error))
        return false;

    // The viewport, ss x ss samples per pixel averaged (the reference averages its samples over
    // the pixel's square too).
    auto start = std::chrono::steady_clock::now();
    if (m_impl->first) {
        renderer.setScene(*scene, &problems);
        m_impl->first = false;
    } else {
        renderer.update(*scene, ScenePart::All, &problems);
    }
    renderer.finishEnvironment();
    renderer.finishGraph();
    renderer.finishTextures();
    render::FrameSettings fs;
    fs.width = fs.height = n * ss;
    fs.reflectionSamples = options.reflectionSamples;
    fs.reflectionSampleTotal = options.reflectionSamples * ss * ss * render::kRefinementFrames;
    fs.reflectionSampleBlock = ss;
    fs.screenSpaceReflections = options.screenSpaceReflections;
    // As the editor's refinement at rest draws it: kRefinementFrames frames, each offset by its
    // sub-pixel jitter (a weave's threads finer than a sample average over the pixel, as the
    // reference's samples do), drawing its own set of reflection samples (the mean's total
    // above sets their filtering) and reading the light of the one before where it traces the
    // mesh's light (one bounce more a frame), and their mean: the editor at rest at ss times
    // the table's size, box-filtered.
    ImageMean linear;
    for (int k = 0; k < render::kRefinementFrames; ++k) {
        fs.accumulation = k;
        fs.jitter = render::progressiveJitter(k);
        fs.reflectionSampleSet = k;
        if (!renderer.render(fs, m_impl->target->framebuffer(), error))
            return false;
        linear.add(renderer.readLinear());
    }
    const Image frame = boxDownsample(linear.takeMean(), ss);
    Image viewport(n, n, 3);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const glm::vec4 mean = frame.rgba(x, y);
            float* o = viewport.at(x, y);
            o[0] = mean.r, o[1] = mean.g, o[2] = mean.b;
        }
    row.viewportMs = msSince(start);

    // The reference of the same scene.
    start = std::chrono::steady_clock::now();
    reference::Options ro;
    ro.width = ro.height = n;
    ro.samplesPerPixel = options.samples;
    ro.maxBounces = options.bounces;
    ro.seed = options.seed;
    ro.threads = options.threads;
    reference::Result result;
    if (!reference::render(*scene, ro, result, error))
        return false;
    row.referenceMs = msSince(start);

    // Over the pixels the mesh covers (every reference sample hit it): the background is not
    // the material's (the stage blurs it in the viewport, the path tracer shows it sharp).
    Image deltaE;
    DeltaEStats all;
    row.viewport = defaultDisplayTransform(viewport);
    row.reference = defaultDisplayTransform(result.image);
    if (!compareImages(row.viewport, row.reference, deltaE, all, error))
        return false;
    row.stats = deltaEStats(deltaE, result.coverage);
    if (row.stats.pixels == 0) {
        *error = c.preset + " on the " + meshName(c.mesh) + ": the mesh covers no pixel";
        return false;
    }
    for (size_t i = 0; i < deltaE.pixels.size(); ++i)
        if (result.coverage.pixels[i] < 1.0f)
            deltaE.pixels[i] = 0.0f;
    row.deltaE = std::move(deltaE);
    return true;
}

std::string referenceTableHeader() {
    return "| preset | mesh | lights | mean ΔE00 | p95 ΔE00 | max ΔE00 | goal |\n"
           "|---|---|---|---:|---:|---:|---|\n";
}

std::string referenceTableLine(const ReferenceTableRow& row) {
    char line[256];
    std::snprintf(line, sizeof line, "| %s | %s | %s | %.2f | %.2f | %.2f | %s |\n",
                  row.c.preset.c_str(), meshName(row.c.mesh).c_str(), row.c.rig.c_str(),
                  row.stats.mean, row.stats.p95, row.stats.max,
                  meetsReferenceGoal(row.stats) ? "met" : "MISSED");
    return line;
}

} // namespace velvet::cli
