// The path tracer's ray queries and the material at a hit (reference/scene_hit.h).
#include "reference/scene_hit.h"

#include <algorithm>
#include <cmath>
#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

namespace velvet::reference::detail {
namespace {

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

} // namespace

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
    rtcIntersect1(static_cast<RTCScene>(ctx.scene), &ic, &rh);
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
    float ao = ctx.tex.occlusion ? sampleTexture(*ctx.tex.occlusion, uv).r : 1.0f;
    if (ctx.graph) // the graph's outputs over the parameters and textures (gbuffer.frag)
        ctx.graph->apply(uv, s, tn, normalMapped, &aniso, &ao);
    hit.occlusion = std::clamp(1.0f + ctx.occlusionStrength * (ao - 1.0f), 0.0f, 1.0f);
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
    rtcOccluded1(static_cast<RTCScene>(ctx.scene), &ic, &r);
    return r.tfar < 0.0f;
}

} // namespace velvet::reference::detail
