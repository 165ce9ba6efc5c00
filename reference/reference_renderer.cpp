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
#include "reference/path_sampling.h"

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

// ---- Material at a hit: parameters and texture slots (glTF: factor x texture) ----
struct Textures {
    std::shared_ptr<const Image> baseColor, metallicRoughness, specRoughMetal, normal, emissive;
    // The KHR lobes' slots (factor x texture, the channels of texture_ref.h).
    std::shared_ptr<const Image> clearcoat, clearcoatRoughness, sheenColor, sheenRoughness,
        specular, specularColor, anisotropy;
};

glm::vec4 sampleTexture(const Image& img, glm::vec2 uv) { // bilinear, repeat (GL_REPEAT)
    const float fx = uv.x * img.width - 0.5f, fy = uv.y * img.height - 0.5f;
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    const float ax = fx - x0, ay = fy - y0;
    auto at = [&](int x, int y) {
        x = ((x % img.width) + img.width) % img.width;
        y = ((y % img.height) + img.height) % img.height;
        return img.rgba(x, y);
    };
    return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), ax),
                    glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), ax), ay);
}

struct LocalLight {
    const Light* light;
    glm::vec3 dir, axisX, axisY; // direction the light travels (unit); rectangle axes
    glm::vec3 radiance;          // colour x intensity
    float cosOuter = 0, cosInner = 0;
};

struct Context {
    RTCScene scene = nullptr;
    const MeshData* mesh = nullptr;
    brdf::Surface surface;
    Textures tex;
    const GraphMaterial* graph = nullptr; ///< the material graph, when it feeds any input
    float normalScale = 1;
    float anisotropyRotation = 0; ///< degrees, counter-clockwise from the tangent
    EnvironmentLight env;
    std::vector<LocalLight> lights;
    BackgroundMode background = BackgroundMode::Sharp;
    glm::vec3 backgroundColor{0.18f};
    int maxBounces = 4;
    float sceneScale = 1;
};

struct Hit {
    float t;
    glm::vec3 p, n, ng;
    brdf::Surface s;
};

bool intersect(const Context& ctx, glm::vec3 o, glm::vec3 d, float tMax, Hit& hit) {
    RTCIntersectContext ic;
    rtcInitIntersectContext(&ic);
    RTCRayHit rh{};
    rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = tMax;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(ctx.scene, &ic, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return false;
    const auto& m = *ctx.mesh;
    const std::uint32_t* tri = m.indices.data() + size_t(rh.hit.primID) * 3;
    const Vertex &a = m.vertices[tri[0]], &b = m.vertices[tri[1]], &c = m.vertices[tri[2]];
    const float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;
    hit.t = rh.ray.tfar;
    hit.p = o + d * hit.t;
    hit.ng = glm::normalize(glm::cross(b.position - a.position, c.position - a.position));
    glm::vec3 n = glm::normalize(w * a.normal + u * b.normal + v * c.normal);
    const glm::vec4 tangent = w * a.tangent + u * b.tangent + v * c.tangent;
    const glm::vec2 uv = w * a.uv + u * b.uv + v * c.uv;
    brdf::Surface s = ctx.surface;
    if (ctx.tex.baseColor)
        s.baseColor *= glm::vec3(sampleTexture(*ctx.tex.baseColor, uv));
    if (ctx.tex.metallicRoughness) {
        const glm::vec4 t = sampleTexture(*ctx.tex.metallicRoughness, uv);
        s.roughness *= t.g, s.metallic *= t.b;
    }
    if (ctx.tex.specRoughMetal) {
        const glm::vec4 t = sampleTexture(*ctx.tex.specRoughMetal, uv);
        s.specularWeight *= t.r, s.roughness *= t.g, s.metallic *= t.b;
    }
    if (ctx.tex.emissive)
        s.emissive *= glm::vec3(sampleTexture(*ctx.tex.emissive, uv));
    if (ctx.tex.clearcoat)
        s.clearcoat *= sampleTexture(*ctx.tex.clearcoat, uv).r;
    if (ctx.tex.clearcoatRoughness)
        s.clearcoatRoughness *= sampleTexture(*ctx.tex.clearcoatRoughness, uv).g;
    if (ctx.tex.sheenColor)
        s.sheenColor *= glm::vec3(sampleTexture(*ctx.tex.sheenColor, uv));
    if (ctx.tex.sheenRoughness)
        s.sheenRoughness *= sampleTexture(*ctx.tex.sheenRoughness, uv).a;
    if (ctx.tex.specular)
        s.specularWeight *= sampleTexture(*ctx.tex.specular, uv).a;
    if (ctx.tex.specularColor)
        s.specularColor *= glm::vec3(sampleTexture(*ctx.tex.specularColor, uv));
    // KHR_materials_anisotropy: the texture's RG is the tangent-space direction, B scales strength.
    AnisotropyInputs aniso{glm::vec2(1.0f, 0.0f), ctx.anisotropyRotation};
    if (ctx.tex.anisotropy) {
        const glm::vec4 t = sampleTexture(*ctx.tex.anisotropy, uv);
        aniso.direction = glm::vec2(t) * 2.0f - 1.0f;
        s.anisotropyStrength *= t.b;
    }
    glm::vec3 tn(0.0f, 0.0f, 1.0f);
    bool normalMapped = false;
    if (ctx.tex.normal) { // glTF: normalize((t * 2 - 1) * (s, s, 1))
        tn = glm::vec3(sampleTexture(*ctx.tex.normal, uv)) * 2.0f - 1.0f;
        tn.x *= ctx.normalScale, tn.y *= ctx.normalScale;
        normalMapped = true;
    }
    if (ctx.graph) // the graph's outputs over the parameters and textures (gbuffer.frag)
        ctx.graph->apply(uv, s, tn, normalMapped, &aniso);
    s.roughness = std::clamp(s.roughness, 0.0f, 1.0f);
    if (normalMapped) { // Gram-Schmidt frame from the interpolated tangent
        glm::vec3 t = glm::vec3(tangent) - n * glm::dot(n, glm::vec3(tangent));
        if (glm::dot(t, t) > 1e-12f) {
            t = glm::normalize(t);
            const glm::vec3 bt = glm::cross(n, t) * (tangent.w < 0.0f ? -1.0f : 1.0f);
            n = glm::normalize(t * tn.x + bt * tn.y + n * tn.z);
        }
    }
    // Two-sided: the shading frame faces the incoming ray, as the viewport's gl_FrontFacing flip.
    if (glm::dot(hit.ng, d) > 0.0f)
        hit.ng = -hit.ng;
    if (glm::dot(n, hit.ng) < 0.0f)
        n = glm::normalize(n - 2.0f * glm::dot(n, hit.ng) * hit.ng);
    hit.n = n;
    if (s.anisotropyStrength > 0.0f)
        s.anisotropyDirection = anisotropyWorldDirection(n, tangent, aniso);
    hit.s = s;
    return true;
}

bool occluded(const Context& ctx, glm::vec3 o, glm::vec3 d, float tMax) {
    RTCIntersectContext ic;
    rtcInitIntersectContext(&ic);
    RTCRay r{};
    r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
    r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
    r.tnear = 0.0f;
    r.tfar = tMax;
    r.mask = ~0u;
    rtcOccluded1(ctx.scene, &ic, &r);
    return r.tfar < 0.0f;
}

// ---- BRDF sampling: a mixture of cosine, base GGX and coat GGX half vectors ----
struct LobeWeights {
    float diffuse, specular, coat;
};
LobeWeights lobeWeights(const brdf::Surface& s) {
    float d = (1.0f - s.metallic) * (maxComponent(s.baseColor) + maxComponent(s.sheenColor));
    float sp = 0.25f + s.metallic;
    float c = 0.5f * s.clearcoat;
    const float sum = std::max(d + sp + c, 1e-6f);
    return {d / sum, sp / sum, c / sum};
}
float alphaOf(float roughness) {
    const float r = std::max(roughness, brdf::kMinRoughness);
    return r * r;
}
float ggxPdf(glm::vec3 n, glm::vec3 v, glm::vec3 l, float alpha) { // pdf(h) = D n.h
    const glm::vec3 h = glm::normalize(v + l);
    const float NdotH = std::max(glm::dot(n, h), 0.0f), VdotH = glm::dot(v, h);
    if (VdotH <= 0.0f)
        return 0.0f;
    return brdf::distributionGGX(NdotH, brdf::sinSquared(n, h), alpha) * NdotH / (4.0f * VdotH);
}
float brdfPdf(const brdf::Surface& s, glm::vec3 n, glm::vec3 v, glm::vec3 l) {
    const float NdotL = glm::dot(n, l);
    if (NdotL <= 0.0f)
        return 0.0f;
    const LobeWeights w = lobeWeights(s);
    return w.diffuse * NdotL / kPi + w.specular * ggxPdf(n, v, l, alphaOf(s.roughness)) +
           w.coat * ggxPdf(n, v, l, alphaOf(s.clearcoatRoughness));
}
glm::vec3 sampleBrdf(const brdf::Surface& s, glm::vec3 n, glm::vec3 v, Rng& rng) {
    const LobeWeights w = lobeWeights(s);
    const float pick = rng.uniform();
    const glm::vec2 xi(rng.uniform(), rng.uniform());
    glm::vec3 t, b;
    basis(n, t, b);
    if (pick < w.diffuse) { // cosine-weighted
        const float r = std::sqrt(xi.x), phi = 2.0f * kPi * xi.y;
        return t * (r * std::cos(phi)) + b * (r * std::sin(phi)) +
               n * std::sqrt(std::max(0.0f, 1.0f - xi.x));
    }
    const float alpha = alphaOf(pick < w.diffuse + w.specular ? s.roughness : s.clearcoatRoughness);
    const glm::vec3 hl = ibl::importanceSampleGgx(xi, alpha);
    const glm::vec3 h = t * hl.x + b * hl.y + n * hl.z;
    return glm::reflect(-v, h);
}

// ---- Lights ----
/// Radiance times throughput reaching the point from light @p L sampled once (next event), with
/// the MIS weight against BRDF sampling for the area lights.
glm::vec3 sampleLight(const Context& ctx, const LocalLight& L, const Hit& hit, glm::vec3 v,
                      glm::vec3 origin, Rng& rng) {
    const Light& light = *L.light;
    glm::vec3 l;
    float dist, pdfSolid = 0;
    glm::vec3 Li;
    bool delta = true;
    if (light.type == LightType::Directional) {
        l = -L.dir, dist = 1e30f, Li = L.radiance;
    } else if (light.type == LightType::Point || light.type == LightType::Spot) {
        const glm::vec3 toLight = light.position - hit.p;
        dist = glm::length(toLight);
        l = toLight / std::max(dist, 1e-6f);
        Li = L.radiance * lights::distanceAttenuation(dist, light.range);
        if (light.type == LightType::Spot)
            Li *= lights::spotConeAttenuation(glm::dot(L.dir, -l), L.cosOuter, L.cosInner);
    } else if (light.shape == AreaShape::Sphere) {
        delta = false;
        const glm::vec3 toC = light.position - hit.p;
        const float dc = glm::length(toC), r = light.size.x;
        if (dc <= r)
            return glm::vec3(0.0f);
        // Uniform in the cone the sphere subtends (its visible surface, by solid angle).
        const float cosMax = std::sqrt(std::max(0.0f, 1.0f - r * r / (dc * dc)));
        const float cosT = 1.0f - rng.uniform() * (1.0f - cosMax);
        const float sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT)),
                    phi = 2.0f * kPi * rng.uniform();
        glm::vec3 w = toC / dc, t, b;
        basis(w, t, b);
        l = t * (sinT * std::cos(phi)) + b * (sinT * std::sin(phi)) + w * cosT;
        const float proj = glm::dot(toC, l);
        dist = proj - std::sqrt(std::max(0.0f, r * r - (dc * dc - proj * proj)));
        pdfSolid = 1.0f / (2.0f * kPi * (1.0f - cosMax));
        Li = L.radiance * lights::windowFalloff(dc, light.range);
    } else {
        delta = false;
        const float hx = 0.5f * light.size.x, hy = 0.5f * light.size.y;
        const glm::vec3 q = light.position + L.axisX * ((rng.uniform() * 2 - 1) * hx) +
                            L.axisY * ((rng.uniform() * 2 - 1) * hy);
        const glm::vec3 toQ = q - hit.p;
        dist = glm::length(toQ);
        l = toQ / std::max(dist, 1e-6f);
        const float cosLight = glm::dot(L.dir, -l); // one-sided: emits along its direction
        if (cosLight <= 0.0f)
            return glm::vec3(0.0f);
        pdfSolid = dist * dist / (4.0f * hx * hy * cosLight);
        Li = L.radiance * lights::windowFalloff(glm::length(light.position - hit.p), light.range);
    }
    if (maxComponent(Li) <= 0.0f || glm::dot(hit.n, l) <= 0.0f || glm::dot(hit.ng, l) <= 0.0f)
        return glm::vec3(0.0f);
    const glm::vec3 f = brdf::evalDirectional(hit.s, hit.n, v, l); // includes n.l
    if (maxComponent(f) <= 0.0f || occluded(ctx, origin, l, dist * (1.0f - 1e-4f)))
        return glm::vec3(0.0f);
    if (delta)
        return f * Li;
    return f * Li * powerHeuristic(pdfSolid, brdfPdf(hit.s, hit.n, v, l)) / pdfSolid;
}

/// Emission of the area lights along a BRDF-sampled ray that reaches @p tMax first, with the
/// MIS weight against light sampling.
glm::vec3 areaEmission(const Context& ctx, glm::vec3 o, glm::vec3 d, float tMax, float brdfPdfL) {
    glm::vec3 sum(0.0f);
    for (const LocalLight& L : ctx.lights) {
        const Light& light = *L.light;
        if (light.type != LightType::Area)
            continue;
        float pdfSolid = 0;
        if (light.shape == AreaShape::Sphere) {
            const glm::vec3 oc = o - light.position;
            const float r = light.size.x, bq = glm::dot(oc, d), cq = glm::dot(oc, oc) - r * r;
            const float disc = bq * bq - cq;
            if (cq <= 0.0f || disc < 0.0f)
                continue;
            const float t = -bq - std::sqrt(disc);
            if (t <= 0.0f || t >= tMax)
                continue;
            const float dc2 = glm::dot(oc, oc);
            const float cosMax = std::sqrt(std::max(0.0f, 1.0f - r * r / dc2));
            pdfSolid = 1.0f / (2.0f * kPi * (1.0f - cosMax));
            sum += L.radiance * lights::windowFalloff(std::sqrt(dc2), light.range) *
                   powerHeuristic(brdfPdfL, pdfSolid);
        } else {
            const float denom = glm::dot(d, L.dir);
            if (denom >= 0.0f) // seen from behind: one-sided
                continue;
            const float t = glm::dot(light.position - o, L.dir) / denom;
            if (t <= 0.0f || t >= tMax)
                continue;
            const glm::vec3 q = o + d * t - light.position;
            const float hx = 0.5f * light.size.x, hy = 0.5f * light.size.y;
            if (std::abs(glm::dot(q, L.axisX)) > hx || std::abs(glm::dot(q, L.axisY)) > hy)
                continue;
            pdfSolid = t * t / (4.0f * hx * hy * -denom);
            sum += L.radiance *
                   lights::windowFalloff(glm::length(light.position - o), light.range) *
                   powerHeuristic(brdfPdfL, pdfSolid);
        }
    }
    return sum;
}

glm::vec3 cameraBackground(const Context& ctx, glm::vec3 d) {
    if (ctx.background == BackgroundMode::SolidColor)
        return ctx.backgroundColor;
    return ctx.env.radiance(d); // Sharp; Blurred and the procedural FBM are shown sharp
}

glm::vec3 trace(const Context& ctx, glm::vec3 o, glm::vec3 d, Rng& rng) {
    glm::vec3 radiance(0.0f), throughput(1.0f);
    Hit hit;
    if (!intersect(ctx, o, d, 1e30f, hit))
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
                    radiance += throughput * f * ctx.env.radiance(l) *
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
        if (!hitSurface) {
            radiance += throughput * ctx.env.radiance(l) * powerHeuristic(pdf, ctx.env.pdf(l));
            break;
        }
        if (bounce >= 2) { // Russian roulette
            const float q = std::min(maxComponent(throughput), 0.95f);
            if (rng.uniform() >= q)
                break;
            throughput /= q;
        }
        hit = next;
        d = l;
    }
    return radiance;
}

/// Each pixel's sum divided by its own sample count (a cancelled pass leaves rows behind).
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
    // A path tracer finds occlusion itself, so the occlusion map (a real-time stand-in for it)
    // is not applied; the coat's own normal map has no counterpart in brdf::Surface yet.
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
    ctx.scene = rtcNewScene(device);
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
    rtcAttachGeometry(ctx.scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(ctx.scene);

    const CameraRays camera(scene.camera, w, h);
    std::vector<glm::dvec3> sum(size_t(w) * h, glm::dvec3(0.0));
    std::vector<int> count(size_t(w) * h, 0);
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
                            const float nx = (float(x) + rng.uniform()) / float(w) * 2.0f - 1.0f;
                            const float ny = 1.0f - (float(y) + rng.uniform()) / float(h) * 2.0f;
                            glm::vec3 o, d;
                            camera.ray(nx, ny, o, d);
                            glm::vec3 c = trace(ctx, o, d, rng);
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
            options.onPassImage(averaged(sum, count, w, h), done);
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (options.timeLimitSeconds > 0 && elapsed >= options.timeLimitSeconds)
            break;
    }
    rtcReleaseScene(ctx.scene);
    rtcReleaseDevice(device);
    out.cancelled = stopped;
    out.image = averaged(sum, count, w, h);
    return true;
}

} // namespace velvet::reference
