// BRDF and light sampling of the path tracer (reference/light_sampling.h).
#include "reference/light_sampling.h"

#include "core/ibl.h"
#include "core/lights.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace velvet::reference::detail {
namespace {

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
} // namespace

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
    // The direction is one 2D sample of a stratified Rng; the lobe a decision (path_sampling.h).
    const glm::vec2 xi(rng.uniform(), rng.uniform());
    const float pick = rng.decision();
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
namespace {
/// A direction uniform (by solid angle) in the cone about unit @p axis whose half-angle has the
/// cosine @p cosMax: the pdf is 1 / (2 pi (1 - cosMax)).
glm::vec3 uniformInCone(glm::vec3 axis, float cosMax, Rng& rng) {
    const float cosT = 1.0f - rng.uniform() * (1.0f - cosMax);
    const float sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT)),
                phi = 2.0f * kPi * rng.uniform();
    glm::vec3 t, b;
    basis(axis, t, b);
    return t * (sinT * std::cos(phi)) + b * (sinT * std::sin(phi)) + axis * cosT;
}

/// Turns @p l, the direction to a light's centre, into a direction uniform in the cone of the
/// disc the light's source subtends (cos of its half-angle @p cosMax) and returns the factor its
/// radiance takes, so that a surface facing it receives the light's intensity: E = L pi sin^2 a,
/// and with the pdf 1 / (2 pi (1 - cos a)) a sample carries L / pdf = E 2 / (1 + cos a). The
/// mean of n.l over the cone is n.c (1 + cos a) / 2, so a surface that sees the whole disc is lit
/// as by the point or direction the viewport shades with; only the penumbra differs.
float discSample(glm::vec3& l, float cosMax, Rng& rng) {
    l = uniformInCone(l, cosMax, rng);
    return 2.0f / (1.0f + cosMax);
}
} // namespace

glm::vec3 sampleLight(const Context& ctx, const LocalLight& L, const Hit& hit, glm::vec3 v,
                      glm::vec3 origin, Rng& rng) {
    const Light& light = *L.light;
    glm::vec3 l;
    float dist, pdfSolid = 0;
    glm::vec3 Li;
    bool delta = true;
    if (light.type == LightType::Directional) {
        // The disc of the light's angular diameter (Light::sourceAngleDeg; discSample).
        l = -L.dir, dist = 1e30f, Li = L.radiance;
        if (light.sourceAngleDeg > 0.0f)
            Li *= discSample(
                l, std::cos(glm::radians(0.5f * std::min(light.sourceAngleDeg, 90.0f))), rng);
    } else if (light.type == LightType::Point || light.type == LightType::Spot) {
        const glm::vec3 toLight = light.position - hit.p;
        dist = glm::length(toLight);
        l = toLight / std::max(dist, 1e-6f);
        Li = L.radiance * lights::distanceAttenuation(dist, light.range);
        if (light.type == LightType::Spot)
            Li *= lights::spotConeAttenuation(glm::dot(L.dir, -l), L.cosOuter, L.cosInner);
        // The ball of the light's source radius (Light::sourceRadius, the viewport's penumbra),
        // seen as the disc it subtends from here; its falloff and cone stay the centre's.
        if (light.sourceRadius > 0.0f && dist > light.sourceRadius) {
            const float sinMax = light.sourceRadius / dist;
            Li *= discSample(l, std::sqrt(1.0f - sinMax * sinMax), rng);
            dist -= light.sourceRadius; // the shadow ray stops at the ball's near side
        }
    } else if (light.shape == AreaShape::Sphere) {
        delta = false;
        const glm::vec3 toC = light.position - hit.p;
        const float dc = glm::length(toC), r = light.size.x;
        if (dc <= r)
            return glm::vec3(0.0f);
        // Uniform in the cone the sphere subtends (its visible surface, by solid angle).
        const float cosMax = std::sqrt(std::max(0.0f, 1.0f - r * r / (dc * dc)));
        l = uniformInCone(toC / dc, cosMax, rng);
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

} // namespace velvet::reference::detail
