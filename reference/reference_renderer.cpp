// The reference path tracer: next-event estimation of every light and of the importance-sampled
// environment, combined with BRDF sampling by multiple importance sampling (Veach & Guibas 1995,
// the power heuristic), Russian roulette after the third vertex (Arvo & Kirk 1990). The BRDF is
// brdf::evalDirectional (all lobes layered, as the viewport's direct light); its sampling is a
// mixture of a cosine lobe and GGX half vectors for the base and the coat (Walter et al. 2007).
#include "reference/reference_renderer.h"

#include "core/brdf.h"
#include "core/color_management.h"
#include "core/ibl.h"
#include "core/lights.h"
#include "core/mesh.h"
#include "core/mesh_import.h"
#include "core/texture_cache.h"
#include "reference/graph_material.h"
#include "reference/light_sampling.h"
#include "reference/path_sampling.h"
#include "reference/scene_hit.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <numbers>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <vector>

namespace velvet::reference {
namespace {

using namespace detail;

glm::vec3 cameraBackground(const Context& ctx, glm::vec3 d) {
    if (ctx.background == BackgroundMode::SolidColor)
        return ctx.backgroundColor;
    return ctx.env.radiance(d); // Sharp; Blurred and the procedural FBM are shown sharp
}

/// Radiance along the camera ray o + t d; @p onMesh tells whether it hit the mesh.
glm::vec3 trace(const Context& ctx, glm::vec3 o, glm::vec3 d, Rng& rng, bool& onMesh) {
    glm::vec3 radiance(0.0f), throughput(1.0f);
    Hit hit;
    onMesh = intersect(ctx, o, d, 1e30f, hit);
    if (!onMesh)
        return cameraBackground(ctx, d);
    for (int bounce = 0;; ++bounce) {
        const glm::vec3 v = -d;
        const float eps = 1e-4f * ctx.sceneScale;
        const glm::vec3 origin = hit.p + hit.ng * eps;
        // Emission, seen through the clearcoat's Fresnel (KHR_materials_clearcoat).
        if (maxComponent(hit.s.emissive) > 0.0f)
            radiance +=
                throughput * hit.s.emissive *
                (1.0f - hit.s.clearcoat *
                            brdf::fresnelSchlick(0.04f, 1.0f, std::max(glm::dot(hit.n, v), 0.0f)));
        if (bounce >= ctx.maxBounces)
            break;
        for (const LocalLight& L : ctx.lights)
            radiance += throughput * sampleLight(ctx, L, hit, v, origin, rng);
        { // the environment (with the ambient lights)
            float pdfEnv = 0;
            const glm::vec3 l = ctx.env.sample(rng.uniform(), rng.uniform(), pdfEnv);
            if (pdfEnv > 0.0f && glm::dot(hit.n, l) > 0.0f && glm::dot(hit.ng, l) > 0.0f) {
                const glm::vec3 f = brdf::evalDirectional(hit.s, hit.n, v, l);
                if (maxComponent(f) > 0.0f && !occluded(ctx, origin, l, 1e30f))
                    radiance += throughput * hit.occlusion * f * ctx.env.radiance(l) *
                                powerHeuristic(pdfEnv, brdfPdf(hit.s, hit.n, v, l)) / pdfEnv;
            }
        }
        // Continue along a BRDF sample.
        const glm::vec3 l = sampleBrdf(hit.s, hit.n, v, rng);
        const float pdf = brdfPdf(hit.s, hit.n, v, l);
        if (pdf <= 0.0f || glm::dot(hit.ng, l) <= 0.0f)
            break;
        throughput *= brdf::evalDirectional(hit.s, hit.n, v, l) / pdf;
        if (maxComponent(throughput) <= 0.0f)
            break;
        Hit next;
        const bool hitSurface = intersect(ctx, origin, l, 1e30f, next);
        radiance += throughput * areaEmission(ctx, origin, l, hitSurface ? next.t : 1e30f, pdf);
        throughput *= hit.occlusion; // what follows is indirect light (the material's occlusion)
        if (!hitSurface) {
            radiance += throughput * ctx.env.radiance(l) * powerHeuristic(pdf, ctx.env.pdf(l));
            break;
        }
        if (bounce >= 2) { // Russian roulette
            const float q = std::min(maxComponent(throughput), 0.95f);
            if (rng.decision() >= q)
                break;
            throughput /= q;
        }
        hit = next;
        d = l;
    }
    return radiance;
}

/// Each pixel's sum divided by its own sample count (a cancelled pass leaves rows behind).
/// The fraction of each pixel's samples whose camera ray hit the mesh.
Image coverage(const std::vector<int>& hits, const std::vector<int>& count, int w, int h) {
    Image image(w, h, 1);
    for (size_t i = 0; i < hits.size(); ++i)
        image.pixels[i] = count[i] ? float(hits[i]) / float(count[i]) : 0.0f;
    return image;
}

Image averaged(const std::vector<glm::dvec3>& sum, const std::vector<int>& count, int w, int h) {
    Image image(w, h, 3);
    for (size_t i = 0; i < sum.size(); ++i) {
        const glm::dvec3 c = count[i] ? sum[i] / double(count[i]) : glm::dvec3(0.0);
        image.pixels[i * 3 + 0] = float(c.x);
        image.pixels[i * 3 + 1] = float(c.y);
        image.pixels[i * 3 + 2] = float(c.z);
    }
    return image;
}

} // namespace

bool render(const Scene& scene, const Options& options, Result& out, std::string* error,
            Problems* problems, const ProgressFn& progress, const std::atomic<bool>* cancel) {
    const int w = std::max(options.width, 1), h = std::max(options.height, 1);
    Context ctx;
    ctx.maxBounces = std::max(options.maxBounces, 0);
    // Mesh: the procedural preview mesh or the imported file, as render/mesh_cache.cpp.
    MeshData mesh;
    if (scene.mesh.kind == PreviewMeshKind::Custom) {
        std::string importError = scene.mesh.file.empty() ? "a custom mesh needs a file" : "";
        if (!scene.mesh.file.empty() && !importMesh(scene.mesh.file, mesh, &importError)) {
        }
        if (!importError.empty()) {
            if (problems)
                problems->error(scene.mesh.file, "mesh", importError + "; showing the sphere");
            mesh = makeSphere();
        }
    } else {
        mesh = makePreviewMesh(scene.mesh.kind);
    }
    ctx.mesh = &mesh;
    const MeshBounds bounds = meshBounds(mesh);
    ctx.sceneScale = bounds.empty() ? 1.0f : std::max(glm::length(bounds.size()), 1e-3f);

    ctx.surface = brdf::surfaceFromMaterial(scene.material);
    ctx.normalScale = scene.material.scalar(ParamId::NormalScale);
    ctx.anisotropyRotation = scene.material.scalar(ParamId::AnisotropyRotation);

    // Textures through the same cache and colour conversion as the viewport (TextureSet).
    ColorManagement colorManagement;
    std::string cmError;
    colorManagement.loadDefault(&cmError);
    TextureCache cache(colorManagement);
    auto load = [&](TextureSlot slot) -> std::shared_ptr<const Image> {
        const TextureRef& ref = scene.material.texture(slot);
        if (ref.empty())
            return nullptr;
        Texture t = cache.get(ref, slot);
        if (problems)
            for (Problem p : t.problems) {
                if (p.path.empty())
                    p.path = "textures." + std::string(textureSlotMeta(slot).id);
                problems->items.push_back(std::move(p));
            }
        if (!t.image || t.image->empty())
            return nullptr;
        if (ref.useRegion && problems)
            problems->warning(ref.file, "textures", "atlas regions are read as the whole image");
        if (!ref.uv.isIdentity() && problems) // the viewport's sampleSlot applies it
            problems->warning(ref.file, "textures." + std::string(textureSlotMeta(slot).id) + ".uv",
                              "the UV transform is not applied by the reference renderer yet");
        return t.image;
    };
    ctx.tex.baseColor = load(TextureSlot::BaseColor);
    ctx.tex.metallicRoughness = load(TextureSlot::MetallicRoughness);
    ctx.tex.specRoughMetal = load(TextureSlot::SpecRoughMetal);
    ctx.tex.normal = load(TextureSlot::Normal);
    ctx.tex.emissive = load(TextureSlot::Emissive);
    ctx.tex.clearcoat = load(TextureSlot::Clearcoat);
    ctx.tex.clearcoatRoughness = load(TextureSlot::ClearcoatRoughness);
    ctx.tex.sheenColor = load(TextureSlot::SheenColor);
    ctx.tex.sheenRoughness = load(TextureSlot::SheenRoughness);
    ctx.tex.specular = load(TextureSlot::Specular);
    ctx.tex.specularColor = load(TextureSlot::SpecularColor);
    ctx.tex.anisotropy = load(TextureSlot::Anisotropy);
    // The occlusion map (or the graph's occlusion) scales the indirect light a hit receives, as
    // glTF 2.0 defines it ("areas that receive less indirect lighting"): the environment and the
    // light bounced off the mesh, not the lights. The path tracer finds the mesh's own occlusion
    // itself, but not a material's micro-geometry that exists only as a normal map (a weave's
    // gaps between threads, which its node feeds to occlusion), which the map stands for; the
    // viewport applies it to its image-based light. The coat's own normal map has no
    // counterpart in brdf::Surface yet.
    ctx.tex.occlusion = load(TextureSlot::Occlusion);
    ctx.occlusionStrength = scene.material.scalar(ParamId::OcclusionStrength);
    if (!scene.material.texture(TextureSlot::ClearcoatNormal).empty() && problems)
        problems->warning(scene.material.texture(TextureSlot::ClearcoatNormal).file,
                          "textures.clearcoatNormal",
                          "the reference shades the coat with the base normal; its own normal map "
                          "is not applied");
    // The material graph through the graph compiler's CPU twin, as the viewport runs its GLSL.
    const GraphMaterial graphMaterial(scene.material, cache, problems);
    if (graphMaterial.active())
        ctx.graph = &graphMaterial;

    // Environment.
    const Environment& env = scene.environment;
    ctx.env.intensity = env.intensity;
    ctx.env.c = std::cos(glm::radians(env.rotationDeg));
    ctx.env.s = std::sin(glm::radians(env.rotationDeg));
    ctx.background = env.background;
    ctx.backgroundColor = env.backgroundColor;
    Image hdri;
    std::string imageError;
    if (!env.hdri.empty() && readImage(env.hdri, hdri, &imageError)) {
        Image rgb(hdri.width, hdri.height, 3);
        for (int y = 0; y < hdri.height; ++y)
            for (int x = 0; x < hdri.width; ++x) {
                const glm::vec4 p = hdri.rgba(x, y);
                float* o = rgb.at(x, y);
                o[0] = p.r, o[1] = p.g, o[2] = p.b;
            }
        ctx.env.image = std::move(rgb);
    } else {
        const glm::vec3 c =
            env.hdri.empty() ? env.color : glm::vec3(0.5f); // render's fallback grey
        if (!env.hdri.empty() && problems)
            problems->warning(env.hdri, "environment.hdri",
                              "environment HDRI not used (" + imageError +
                                  "); lighting with a uniform grey environment instead");
        ctx.env.image = Image(1, 1, 3);
        ctx.env.image.pixels = {c.x, c.y, c.z};
    }
    for (const Light& l : scene.lights) {
        if (l.type == LightType::Ambient) {
            ctx.env.ambient += l.color * l.intensity;
            continue;
        }
        LocalLight L{&l, glm::vec3(0, -1, 0), {}, {}, l.color * l.intensity};
        if (glm::length(l.direction) > 0.0f)
            L.dir = glm::normalize(l.direction);
        L.cosOuter = std::cos(glm::radians(l.outerConeDeg));
        L.cosInner = std::cos(glm::radians(l.innerConeDeg));
        lights::rectangleAxes(L.dir, L.axisX, L.axisY);
        ctx.lights.push_back(L);
    }
    ctx.env.build();

    // Embree.
    RTCDevice device = rtcNewDevice(nullptr);
    if (!device) {
        *error = "Embree: cannot create a device";
        return false;
    }
    RTCScene rtcScene = rtcNewScene(device);
    ctx.scene = rtcScene;
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                           RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                           mesh.vertices.size()));
    auto* ib = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.triangleCount()));
    for (size_t i = 0; i < mesh.vertices.size(); ++i)
        for (int k = 0; k < 3; ++k)
            vb[i * 3 + k] = mesh.vertices[i].position[k];
    std::copy(mesh.indices.begin(), mesh.indices.end(), ib);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(rtcScene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(rtcScene);

    const CameraRays camera(scene.camera, w, h);
    std::vector<glm::dvec3> sum(size_t(w) * h, glm::dvec3(0.0));
    std::vector<int> count(size_t(w) * h, 0), hits(size_t(w) * h, 0);
    const auto start = std::chrono::steady_clock::now();
    std::atomic<bool> stopped{false};
    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    int pass = 0;
    for (; pass < options.samplesPerPixel && !stopped; ++pass) {
        arena.execute([&] {
            tbb::parallel_for(
                tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
                    for (int y = rows.begin(); y != rows.end(); ++y) {
                        if (cancel && cancel->load()) {
                            stopped = true;
                            return;
                        }
                        for (int x = 0; x < w; ++x) {
                            const size_t index = size_t(y) * w + x;
                            Rng rng(mix64(options.seed ^ mix64(index + 1)), std::uint64_t(pass));
                            rng.stratify(std::uint32_t(pass),
                                         mix64(options.seed * 0x2545f4914f6cdd1dULL ^ index));
                            const float nx = (float(x) + rng.uniform()) / float(w) * 2.0f - 1.0f;
                            const float ny = 1.0f - (float(y) + rng.uniform()) / float(h) * 2.0f;
                            glm::vec3 o, d;
                            camera.ray(nx, ny, o, d);
                            bool onMesh = false;
                            glm::vec3 c = trace(ctx, o, d, rng, onMesh);
                            hits[index] += onMesh ? 1 : 0;
                            if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z))
                                c = glm::vec3(0.0f);
                            sum[index] += glm::dvec3(c);
                            ++count[index];
                        }
                    }
                });
        });
        if (!stopped)
            out.passesDone = pass + 1;
        if (progress)
            progress(pass + 1, options.samplesPerPixel);
        const int done = pass + 1;
        const bool showNow = done <= 32 ? (done & (done - 1)) == 0 : done % 32 == 0;
        if (options.onPassImage && !stopped && showNow)
            options.onPassImage(averaged(sum, count, w, h), coverage(hits, count, w, h), done);
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (options.timeLimitSeconds > 0 && elapsed >= options.timeLimitSeconds)
            break;
    }
    rtcReleaseScene(rtcScene);
    rtcReleaseDevice(device);
    out.cancelled = stopped;
    out.image = averaged(sum, count, w, h);
    out.coverage = coverage(hits, count, w, h);
    return true;
}

} // namespace velvet::reference
