#include "render/shadow_maps.h"

#include "core/lights.h"
#include "render/gpu_mesh.h"

#include <algorithm>
#include <cmath>
#include <epoxy/gl.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

namespace velvet::render {
namespace {

/// Raster slope-scaled depth bias of the depth maps (glPolygonOffset factor, units): the first
/// half of the bias; the lookup's receiver-plane bias and normal offset are the second.
constexpr float kSlopeBias = 1.5f, kConstantBias = 2.0f;
/// Widest perspective map: a light closer to the sphere than this allows casts no shadow.
constexpr float kMaxHalfFovDeg = 80.0f;

float luminance(glm::vec3 c) {
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

glm::vec3 unit(glm::vec3 v, glm::vec3 fallback) {
    const float len = glm::length(v);
    return len > 0.0f ? v / len : fallback;
}

/// An up vector not parallel to @p forward.
glm::vec3 upFor(glm::vec3 forward) {
    return std::abs(forward.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

/// The light's diameter (m) seen by PCSS: area lights their own size (a rectangle the disc of
/// the same area), point and spot lights their source radius.
float localSourceDiameter(const Light& l) {
    if (l.type != LightType::Area)
        return 2.0f * std::max(l.sourceRadius, 0.0f);
    if (l.shape == AreaShape::Sphere)
        return 2.0f * std::max(l.size.x, 0.0f);
    return 2.0f * std::sqrt(std::max(l.size.x * l.size.y, 0.0f) / 3.14159265f);
}

/// Emitting area of an area light (m²) x its cosine towards @p toPoint: nits -> candela.
float areaCandelaFactor(const Light& l, glm::vec3 toPoint) {
    if (l.type != LightType::Area)
        return 1.0f;
    if (l.shape == AreaShape::Sphere)
        return 3.14159265f * l.size.x * l.size.x;
    const float cosLight = std::max(glm::dot(unit(l.direction, {0, -1, 0}), toPoint), 0.0f);
    return l.size.x * l.size.y * cosLight;
}

/// Illuminance (lux) the light gives a surface facing it at @p point.
float illuminanceAt(const Light& l, glm::vec3 point) {
    const float lum = luminance(l.color) * l.intensity;
    if (l.type == LightType::Directional)
        return lum;
    const glm::vec3 d = point - l.position;
    const float dist = glm::length(d);
    const glm::vec3 toPoint = unit(d, {0, -1, 0});
    float e = lum * areaCandelaFactor(l, toPoint) * lights::distanceAttenuation(dist, l.range);
    if (l.type == LightType::Spot)
        e *= lights::spotConeAttenuation(glm::dot(unit(l.direction, {0, -1, 0}), toPoint),
                                         std::cos(glm::radians(l.outerConeDeg)),
                                         std::cos(glm::radians(l.innerConeDeg)));
    return e;
}

} // namespace

BoundingSphere boundingSphere(const MeshBounds& bounds) {
    if (bounds.empty())
        return {};
    return {bounds.center(), std::max(0.5f * glm::length(bounds.size()), 1e-3f)};
}

std::vector<ShadowSlot> planShadows(const std::vector<Light>& lights, const BoundingSphere& casters,
                                    Problems* problems) {
    std::vector<ShadowSlot> slots;
    const glm::vec3 c = casters.center;
    const float R = casters.radius;
    for (size_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        if (!l.castShadows || l.type == LightType::Ambient)
            continue;
        ShadowSlot s;
        s.light = int(i);
        s.contribution = illuminanceAt(l, c);
        if (l.type == LightType::Directional) {
            // An orthographic box around the sphere, seen along the light.
            const glm::vec3 forward = unit(l.direction, {0, -1, 0});
            const float margin = 0.05f * R + 0.01f;
            const glm::vec3 eye = c - forward * (R + margin);
            s.view = glm::lookAt(eye, c, upFor(forward));
            s.nearPlane = 0.0f;
            s.farPlane = 2.0f * (R + margin);
            s.proj = glm::ortho(-R, R, -R, R, s.nearPlane, s.farPlane);
            s.sourceSize = 2.0f * std::tan(glm::radians(0.5f * std::max(l.sourceAngleDeg, 0.0f)));
            s.metresPerUv = 2.0f * R;
        } else {
            // A frustum from the light's centre that just holds the sphere.
            const glm::vec3 toCenter = c - l.position;
            const float d = glm::length(toCenter);
            const float half = d > R ? std::asin(std::min(R / d, 1.0f)) * 1.02f : 10.0f;
            if (half > glm::radians(kMaxHalfFovDeg)) {
                if (problems)
                    problems->warning("", "lights[" + std::to_string(i) + "]",
                                      "casts no shadow: the light is inside or too close to the "
                                      "mesh's bounding sphere (a shadow map needs it outside)");
                continue;
            }
            const glm::vec3 forward = toCenter / d;
            s.perspective = true;
            s.view = glm::lookAt(l.position, c, upFor(forward));
            s.nearPlane = std::max(d - R, 0.02f * d);
            s.farPlane = d + R;
            s.proj = glm::perspective(2.0f * half, 1.0f, s.nearPlane, s.farPlane);
            s.sourceSize = localSourceDiameter(l);
            s.metresPerUv = 2.0f * std::tan(half);
        }
        slots.push_back(s);
    }
    // The strongest at the mesh first (stable: equal lights keep the scene's order).
    std::stable_sort(slots.begin(), slots.end(), [](const ShadowSlot& a, const ShadowSlot& b) {
        return a.contribution > b.contribution;
    });
    if (slots.size() > size_t(kMaxShadowLights)) {
        if (problems)
            for (size_t k = kMaxShadowLights; k < slots.size(); ++k)
                problems->warning("", "lights[" + std::to_string(slots[k].light) + "]",
                                  "casts no shadow: only the " + std::to_string(kMaxShadowLights) +
                                      " strongest shadow-casting lights at the mesh do");
        slots.resize(kMaxShadowLights);
    }
    return slots;
}

ShadowMaps::~ShadowMaps() {
    if (m_texture)
        glDeleteTextures(1, &m_texture);
    if (m_fbo)
        glDeleteFramebuffers(1, &m_fbo);
    if (m_compareSampler)
        glDeleteSamplers(1, &m_compareSampler);
    if (m_depthSampler)
        glDeleteSamplers(1, &m_depthSampler);
}

bool ShadowMaps::initialize(std::string* error) {
    if (!reload(error))
        return false;
    glCreateFramebuffers(1, &m_fbo);
    glCreateSamplers(1, &m_compareSampler);
    glCreateSamplers(1, &m_depthSampler);
    for (GLuint s : {m_compareSampler, m_depthSampler}) {
        glSamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    // Hardware PCF: each compare tap is a bilinear blend of four depth tests.
    glSamplerParameteri(m_compareSampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(m_compareSampler, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(m_compareSampler, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glSamplerParameteri(m_compareSampler, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glSamplerParameteri(m_depthSampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(m_depthSampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    allocate(1, 1);
    return true;
}

bool ShadowMaps::reload(std::string* error) {
    if (!m_program.build("shadow_depth.vert", "shadow_depth.frag", {}, error) ||
        !m_bounds.build(error))
        return false;
    m_compileCount += 2;
    m_dirty = true;
    return true;
}

void ShadowMaps::allocate(int layers, int size) {
    if (layers == m_layers && size == m_size)
        return;
    if (m_texture)
        glDeleteTextures(1, &m_texture);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &m_texture);
    glTextureStorage3D(m_texture, 1, GL_DEPTH_COMPONENT32F, size, size, layers);
    m_layers = layers;
    m_size = size;
    // No slots: one texel of "nothing in front", so a stray lookup reads lit.
    const float far = 1.0f;
    glClearTexImage(m_texture, 0, GL_DEPTH_COMPONENT, GL_FLOAT, &far);
}

void ShadowMaps::plan(const std::vector<Light>& lights, const BoundingSphere& casters,
                      Problems* problems) {
    std::vector<ShadowSlot> slots = planShadows(lights, casters, problems);
    // A map holds the mesh's depth seen through its slot's view and projection, nothing else: an
    // edit of a light's colour, intensity, range or source size (a slider drag) keeps every map.
    const bool sameMaps = slots.size() == m_slots.size() &&
                          std::equal(slots.begin(), slots.end(), m_slots.begin(),
                                     [](const ShadowSlot& a, const ShadowSlot& b) {
                                         return a.view == b.view && a.proj == b.proj;
                                     });
    m_slots = std::move(slots);
    if (!sameMaps)
        m_dirty = true;
}

std::vector<int> ShadowMaps::slotOfLight(size_t lightCount) const {
    std::vector<int> out(lightCount, 0);
    for (size_t s = 0; s < m_slots.size(); ++s)
        if (size_t(m_slots[s].light) < lightCount)
            out[size_t(m_slots[s].light)] = int(s) + 1;
    return out;
}

bool ShadowMaps::draw(const GpuMesh& mesh) {
    if (!m_dirty && m_drawnMesh == &mesh)
        return false;
    m_dirty = false;
    m_drawnMesh = &mesh;
    if (m_slots.empty()) {
        allocate(1, 1);
        return false;
    }
    allocate(int(m_slots.size()), kShadowMapSize);
    ++m_drawCount;
    glBindFramebuffer(GL_FRAMEBUFFER, m_fbo);
    glDrawBuffer(GL_NONE);
    glViewport(0, 0, m_size, m_size);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    // Both faces: the drape is open, and a closed mesh's back faces would only move the bias.
    glDisable(GL_CULL_FACE);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(kSlopeBias, kConstantBias);
    glUseProgram(m_program.id());
    const float far = 1.0f;
    for (size_t s = 0; s < m_slots.size(); ++s) {
        glNamedFramebufferTextureLayer(m_fbo, GL_DEPTH_ATTACHMENT, m_texture, 0, GLint(s));
        glClearBufferfv(GL_DEPTH, 0, &far);
        const glm::mat4 viewProj = m_slots[s].proj * m_slots[s].view;
        glProgramUniformMatrix4fv(m_program.id(), 0, 1, GL_FALSE, &viewProj[0][0]);
        mesh.draw();
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(0.0f, 0.0f);
    m_bounds.update(m_texture, m_layers, m_size);
    return true;
}

void ShadowMaps::fill(StageBlock& b, const std::vector<Light>& lights) const {
    b.counts.x = int(m_slots.size());
    for (size_t i = 0; i < m_slots.size(); ++i) {
        const ShadowSlot& s = m_slots[i];
        const Light& l = lights[size_t(s.light)];
        b.shadowViewProj[i] = s.proj * s.view;
        b.shadowView[i] = s.view;
        b.shadowParams[i] =
            glm::vec4(s.perspective ? 1.0f : 0.0f, s.nearPlane, s.farPlane, s.sourceSize);
        b.shadowScale[i] = glm::vec4(s.metresPerUv, 1.0f / float(kShadowMapSize), 0.0f, 0.0f);
        const glm::vec3 dir = unit(l.direction, {0, -1, 0});
        const bool directional = l.type == LightType::Directional;
        b.shadowLight[i] =
            glm::vec4(directional ? -dir : l.position, directional                 ? 0.0f
                                                       : l.type == LightType::Area ? 2.0f
                                                                                   : 1.0f);
        float candela = l.intensity;
        if (l.type == LightType::Area) // the catcher treats it as a point: nits x area
            candela *= l.shape == AreaShape::Sphere ? 3.14159265f * l.size.x * l.size.x
                                                    : l.size.x * l.size.y;
        b.shadowRadiance[i] = glm::vec4(l.color * candela, l.range);
        const float cosOuter = l.type == LightType::Spot
                                   ? std::cos(glm::radians(std::clamp(l.outerConeDeg, 0.0f, 90.0f)))
                                   : -2.0f;
        b.shadowSpot[i] = glm::vec4(dir, cosOuter);
    }
}

void ShadowMaps::bind() const {
    glBindTextureUnit(stage_binding::kShadowCompareTex, m_texture);
    glBindSampler(stage_binding::kShadowCompareTex, m_compareSampler);
    glBindTextureUnit(stage_binding::kShadowDepthTex, m_texture);
    glBindSampler(stage_binding::kShadowDepthTex, m_depthSampler);
    glBindTextureUnit(stage_binding::kShadowBoundsTex, m_bounds.texture());
}

void ShadowMaps::unbind() const {
    for (GLuint unit :
         {GLuint(stage_binding::kShadowCompareTex), GLuint(stage_binding::kShadowDepthTex),
          GLuint(stage_binding::kShadowBoundsTex)}) {
        glBindTextureUnit(unit, 0);
        glBindSampler(unit, 0);
    }
}

} // namespace velvet::render
