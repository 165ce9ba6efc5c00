#include "render/stage.h"

#include "render/gpu_mesh.h"

#include <algorithm>
#include <cmath>
#include <epoxy/gl.h>
#include <glm/common.hpp>

namespace velvet::render {
namespace {

/// The ground's half size in bounding-sphere radii (at least kGroundMinHalfSize metres): far
/// enough to reach the horizon of any sensible view; the catcher's far part is invisible and the
/// plain ground fades into it between kFadeStart and kFadeEnd radii from the mesh.
constexpr float kGroundHalfSizeRadii = 40.0f, kGroundMinHalfSize = 20.0f;
constexpr float kFadeStart = 1.6f, kFadeEnd = 4.0f;
/// Below the mesh's lowest point by this fraction of its radius, so that a face lying on the
/// floor (the drape's hem) does not fight the ground for depth.
constexpr float kGroundGap = 0.002f;

float groundHalfSize(float radius) {
    return std::max(kGroundHalfSizeRadii * radius, kGroundMinHalfSize);
}

BoundingSphere sphereOf(const MeshBounds& bounds) {
    return boundingSphere(bounds);
}

} // namespace

GpuMaterial groundMaterial(const Environment& environment) {
    Material m;
    m.setColor(ParamId::BaseColor, glm::clamp(environment.groundColor, 0.0f, 1.0f));
    m.setScalar(ParamId::Metallic, 0.0f);
    m.setScalar(ParamId::Roughness, std::clamp(environment.groundRoughness, 0.0f, 1.0f));
    return packMaterial(m);
}

Stage::~Stage() {
    if (m_ubo)
        glDeleteBuffers(1, &m_ubo);
    if (m_queries[0])
        glDeleteQueries(6, m_queries);
}

bool Stage::initialize(std::string* error) {
    if (!m_shadows.initialize(error) || !reload(error))
        return false;
    glCreateBuffers(1, &m_ubo);
    glNamedBufferStorage(m_ubo, sizeof(StageBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glCreateQueries(GL_TIMESTAMP, 6, m_queries);
    return true;
}

bool Stage::reload(std::string* error) {
    std::string errors, message;
    if (m_groundProgram.build("ground.vert", "ground.frag", {}, &message))
        ++m_groundCompiles;
    else
        errors = message;
    if (!m_occlusion.build(&message))
        errors += (errors.empty() ? "" : "\n") + message;
    if (!m_mask.build(&message))
        errors += (errors.empty() ? "" : "\n") + message;
    if (m_groundCompiles > 1 && !m_shadows.reload(&message)) // initialize() built it once
        errors += (errors.empty() ? "" : "\n") + message;
    if (!errors.empty() && error)
        *error = errors;
    return errors.empty();
}

int Stage::compileCount() const {
    return m_shadows.compileCount() + m_occlusion.compileCount() + m_mask.compileCount() +
           m_groundCompiles;
}

void Stage::plan(const std::vector<Light>& lights, const MeshBounds& bounds, Problems* problems) {
    m_bounds = bounds;
    m_shadows.plan(lights, sphereOf(bounds), problems);
}

void Stage::annotate(FrameBlock& block, const std::vector<Light>& lights) const {
    const std::vector<int> slots = m_shadows.slotOfLight(lights.size());
    int directional = 0;
    for (size_t i = 0; i < lights.size() && directional < kMaxDirectionalLights; ++i)
        if (lights[i].type == LightType::Directional)
            block.lightDirection[directional++].w = float(slots[i]);
}

bool Stage::shadowsDirectionalLight(const std::vector<Light>& lights) const {
    const std::vector<int> slots = m_shadows.slotOfLight(lights.size());
    int directional = 0;
    for (size_t i = 0; i < lights.size() && directional < kMaxDirectionalLights; ++i)
        if (lights[i].type == LightType::Directional && ++directional && slots[i] > 0)
            return true;
    return false;
}

bool Stage::shadowsLocalLight(const std::vector<Light>& lights) const {
    return std::any_of(m_shadows.slots().begin(), m_shadows.slots().end(),
                       [&](const ShadowSlot& s) {
                           return size_t(s.light) < lights.size() &&
                                  lights[size_t(s.light)].type != LightType::Directional;
                       });
}

bool Stage::packsOcclusion(const Scene& scene, bool allowed) const {
    // A channel is free with at most three slots, and the mesh's pixels read the mask where a
    // directional light has a slot (WITH_DIRECTIONAL_SHADOWS; the catcher and the plain ground
    // read it with any slot).
    const size_t slots = m_shadows.slots().size();
    return allowed && scene.environment.ambientOcclusion && slots > 0 &&
           slots < size_t(kMaxShadowLights) && shadowsDirectionalLight(scene.lights);
}

void Stage::drawShadows(const GpuMesh& mesh) {
    glQueryCounter(m_queries[0], GL_TIMESTAMP);
    m_shadowTimed = m_shadows.draw(mesh);
    glQueryCounter(m_queries[1], GL_TIMESTAMP);
}

void Stage::beginFrame(const Scene& scene, int width, int height, int downsample,
                       bool packOcclusion) {
    StageBlock b{};
    m_shadows.fill(b, scene.lights);
    const Environment& env = scene.environment;
    const BoundingSphere sphere = sphereOf(m_bounds);
    const float r = sphere.radius;
    const float height0 = m_bounds.empty() ? 0.0f : m_bounds.min.y - kGroundGap * r;
    b.ground = glm::vec4(height0, float(int(env.ground)), kFadeStart * r, kFadeEnd * r);
    b.meshSphere = glm::vec4(sphere.center, r);
    b.groundSquare = glm::vec4(sphere.center.x, 0.0f, sphere.center.z, groundHalfSize(r));
    b.counts.y = std::max(downsample, 1);
    b.counts.z = packsOcclusion(scene, packOcclusion) ? 1 : 0;
    b.occlusion =
        glm::vec4(env.ambientOcclusion ? 1.0f : 0.0f, std::max(env.occlusionRadius, 0.0f),
                  float(maskSize(width, b.counts.y)), float(maskSize(height, b.counts.y)));
    glNamedBufferSubData(m_ubo, 0, sizeof(StageBlock), &b);
    glBindBufferBase(GL_UNIFORM_BUFFER, stage_binding::kStageUbo, m_ubo);
    m_block = b;
}

void Stage::drawGround(const Environment& environment) {
    if (environment.ground == GroundMode::Off)
        return;
    const BoundingSphere sphere = sphereOf(m_bounds);
    const float r = sphere.radius;
    const float height0 = m_bounds.empty() ? 0.0f : m_bounds.min.y - kGroundGap * r;
    const float half = groundHalfSize(r);
    const int id = environment.ground == GroundMode::ShadowCatcher ? kGroundCatcherMaterialId
                                                                   : kGroundPlainMaterialId;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE); // unseen from below: a camera under the floor still sees the mesh
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    const unsigned program = m_groundProgram.id();
    glUseProgram(program);
    glProgramUniform1i(program, 0, id);
    glProgramUniform4f(program, 1, sphere.center.x, height0, sphere.center.z, half);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

bool Stage::drawOcclusion(const Environment& environment, const glm::mat4& viewProj, int width,
                          int height, bool bentNormals, FrameKey frameKey, unsigned emptyVao,
                          std::string* error) {
    m_occlusionOn = environment.ambientOcclusion;
    m_occlusionTimed = m_occlusionKept = false;
    if (!m_occlusionOn) {
        m_occlusion.invalidate(); // its targets are not kept up to date meanwhile
        return true;
    }
    const PixelRect near = occlusionRect(m_bounds, std::max(environment.occlusionRadius, 0.0f),
                                         viewProj, width, height);
    // The stage's part of the key: what the ground's depth and the search depend on.
    frameKey.add(environment.ground).add(environment.occlusionRadius).add(m_bounds);
    glQueryCounter(m_queries[2], GL_TIMESTAMP);
    const int d = downsample();
    const PixelRect texels = OcclusionPass::texelRect(near, width, height, d);
    m_occlusionTexels = texels;
    m_block.occlusionTexels =
        glm::ivec4(texels.x, texels.y, texels.x + texels.width, texels.y + texels.height);
    glNamedBufferSubData(m_ubo, offsetof(StageBlock, occlusionTexels), sizeof(glm::ivec4),
                         &m_block.occlusionTexels);
    if (!m_occlusion.run(width, height, d, texels, bentNormals, std::move(frameKey), emptyVao,
                         &m_occlusionKept, error))
        return false;
    glQueryCounter(m_queries[3], GL_TIMESTAMP);
    m_occlusionTimed = !m_occlusionKept;
    return true;
}

void Stage::drawShadowMask(unsigned framebuffer, unsigned maskTexture, unsigned keyTexture,
                           unsigned groundMaskTexture, const Environment& environment,
                           const glm::mat4& viewProj, int width, int height, FrameKey frameKey,
                           unsigned emptyVao, bool settle, bool bentNormals) {
    m_maskTexture = m_keyTexture = m_groundMaskTexture = 0;
    m_maskKept = false;
    if (!hasShadows()) {
        m_maskPasses = 0;
        m_maskReuse.invalidate(); // its targets are not kept up to date meanwhile
        return;
    }
    m_maskTexture = maskTexture;
    m_keyTexture = keyTexture;
    m_groundMaskTexture = groundMaskTexture;
    const float r = sphereOf(m_bounds).radius;
    const float height0 = m_bounds.empty() ? 0.0f : m_bounds.min.y - kGroundGap * r;
    // The stage's part of the key: what the masks' passes read besides the G-buffer.
    for (const ShadowSlot& s : m_shadows.slots()) // member by member: no padding bytes
        frameKey.add(s.light)
            .add(s.perspective)
            .add(s.view)
            .add(s.proj)
            .add(s.nearPlane)
            .add(s.farPlane)
            .add(s.sourceSize)
            .add(s.metresPerUv);
    frameKey.add(m_block).add(m_shadows.drawCount()).add(environment.ground).add(m_bounds);
    frameKey.add(settle).add(bentNormals).add(framebuffer).add(maskTexture).add(keyTexture);
    frameKey.add(groundMaskTexture);
    if ((m_maskKept = m_maskReuse.reuse(std::move(frameKey)))) {
        // The passes and their timers are the frame's that drew the masks; an occlusion drawn
        // again (for a reason no key sees: invalidateScreenPasses()) goes into them again.
        if (m_block.counts.z != 0 && !m_occlusionKept)
            m_occlusion.packInto(framebuffer, m_occlusionTexels, emptyVao);
        return;
    }
    m_shadows.bind();
    glQueryCounter(m_queries[4], GL_TIMESTAMP);
    m_maskPasses =
        m_mask.run(framebuffer, m_shadows.slots(), m_bounds, environment.ground != GroundMode::Off,
                   height0, viewProj, width, height, downsample(), emptyVao, settle, bentNormals);
    // The masks' clear has reset the fourth channel: the occlusion, kept or drawn, goes back in
    // (timed with the masks).
    if (m_block.counts.z != 0)
        m_occlusion.packInto(framebuffer, m_occlusionTexels, emptyVao);
    glQueryCounter(m_queries[5], GL_TIMESTAMP);
    m_shadows.unbind();
}

bool Stage::meshRectangle(const glm::mat4& viewProj, int width, int height, int rect[4]) const {
    if (m_bounds.empty())
        return false;
    // The shadow mask's rectangle of the mesh alone (no ground: the slot is not looked at); the
    // whole frame where the bounds reach behind the camera.
    const PixelRect r = shadowReceiverRect({}, m_bounds, false, 0.0f, viewProj, width, height);
    rect[0] = r.x;
    rect[1] = r.y;
    rect[2] = r.width;
    rect[3] = r.height;
    return true;
}

void Stage::bind() const {
    glBindTextureUnit(stage_binding::kShadowMaskTex, m_maskTexture);
    glBindTextureUnit(stage_binding::kShadowKeyTex, m_keyTexture);
    glBindTextureUnit(stage_binding::kGroundShadowMaskTex, m_groundMaskTexture);
    if (m_occlusionOn)
        m_occlusion.bind();
}

void Stage::unbind() const {
    glBindTextureUnit(stage_binding::kShadowMaskTex, 0);
    glBindTextureUnit(stage_binding::kShadowKeyTex, 0);
    glBindTextureUnit(stage_binding::kGroundShadowMaskTex, 0);
    glBindTextureUnit(stage_binding::kOcclusionTex, 0);
}

double Stage::lastShadowMs() const {
    if (!m_shadowTimed)
        return 0.0;
    GLuint64 t0 = 0, t1 = 0;
    glGetQueryObjectui64v(m_queries[0], GL_QUERY_RESULT, &t0);
    glGetQueryObjectui64v(m_queries[1], GL_QUERY_RESULT, &t1);
    return double(t1 - t0) * 1e-6;
}

double Stage::lastOcclusionMs() const {
    if (!m_occlusionTimed)
        return 0.0;
    GLuint64 t0 = 0, t1 = 0;
    glGetQueryObjectui64v(m_queries[2], GL_QUERY_RESULT, &t0);
    glGetQueryObjectui64v(m_queries[3], GL_QUERY_RESULT, &t1);
    return double(t1 - t0) * 1e-6;
}

double Stage::lastShadowMaskMs() const {
    if (m_maskPasses == 0 || m_maskKept)
        return 0.0;
    GLuint64 t0 = 0, t1 = 0;
    glGetQueryObjectui64v(m_queries[4], GL_QUERY_RESULT, &t0);
    glGetQueryObjectui64v(m_queries[5], GL_QUERY_RESULT, &t1);
    return double(t1 - t0) * 1e-6;
}

} // namespace velvet::render
