#include "render/frame_uniforms.h"

#include "render/camera.h"
#include "render/environment_map.h"
#include "render/ibl_bake.h"
#include "render/shader_program.h"

#include <algorithm>
#include <cmath>
#include <epoxy/gl.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

namespace velvet::render {
namespace {

/// Roughness of the prefiltered level shown by BackgroundMode::Blurred.
constexpr float kBlurredBackgroundRoughness = 0.6f;

} // namespace

glm::mat4 jitterMatrix(glm::vec2 jitter, int width, int height) {
    // A sub-pixel offset in clip space, x' = x + (2 jitter / size) w, for a perspective and an
    // orthographic projection alike (render/progressive_accumulation.h).
    glm::mat4 offset(1.0f);
    offset[3] = glm::vec4(2.0f * jitter.x / float(std::max(width, 1)),
                          2.0f * jitter.y / float(std::max(height, 1)), 0.0f, 1.0f);
    return offset;
}

FrameBlock makeFrameBlock(const Scene& scene, const Camera& cam, const GpuEnvironment& environment,
                          const FrameSettings& fs) {
    FrameBlock b{};
    const float aspect = float(fs.width) / float(std::max(fs.height, 1));
    b.viewMatrix = viewMatrix(cam);
    b.projMatrix = jitterMatrix(fs.jitter, fs.width, fs.height) * projectionMatrix(cam, aspect);
    b.invProjMatrix = glm::inverse(b.projMatrix);
    b.invViewMatrix = glm::inverse(b.viewMatrix);
    b.viewProjMatrix = b.projMatrix * b.viewMatrix;
    b.cameraPosition = glm::vec4(cameraEye(cam), cam.orthographic ? 1.0f : 0.0f);
    b.viewport = glm::vec4(float(fs.width), float(fs.height), 1.0f / float(fs.width),
                           1.0f / float(fs.height));
    const Environment& env = scene.environment;
    for (int i = 0; i < 9; ++i)
        b.envSh[i] = glm::vec4(environment.sh[i] * env.intensity, 0.0f);
    const float rot = glm::radians(env.rotationDeg);
    b.envParams =
        glm::vec4(std::cos(rot), std::sin(rot), env.intensity, float(environment.levels - 1));
    glm::vec3 ambient(0.0f);
    int count = 0; // frameDirectionalLightCount's
    for (const Light& l : scene.lights) {
        if (l.type == LightType::Ambient) {
            ambient += l.color * l.intensity;
        } else if (l.type == LightType::Directional && count < kMaxDirectionalLights) {
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
                                    ? std::min(4.0f, float(environment.levels - 1))
                                    : 0.0f;
    b.backgroundColor = glm::vec4(env.backgroundColor, backgroundLod);
    b.modes = glm::ivec4(count, int(fs.view), int(fs.toneMapper), int(env.background));
    b.post = glm::vec4(std::exp2(fs.exposureEv), 2.0f * std::max(cam.distance, 0.1f),
                       float(environment.width), 0.0f);
    return b;
}

int frameDirectionalLightCount(const std::vector<Light>& lights) {
    const auto directional = std::count_if(lights.begin(), lights.end(), [](const Light& l) {
        return l.type == LightType::Directional;
    });
    return std::min(int(directional), kMaxDirectionalLights);
}

IblBlock makeIblBlock(const IblBaker& ibl, const FrameSettings& fs) {
    const int levels = ibl.specularLevels();
    return {glm::vec4(ibl.specularReady() ? 1.0f : 0.0f, float(std::max(levels - 1, 0)),
                      ibl.dfgReady() ? 1.0f : 0.0f, fs.specularMultiScatter ? 1.0f : 0.0f),
            glm::vec4(kBlurredBackgroundRoughness * float(std::max(levels - 1, 0)), fs.time, 0.0f,
                      0.0f),
            glm::vec4(float(std::max(fs.reflectionSamples, 0)),
                      float(std::max(fs.reflectionSampleTotal, fs.reflectionSamples)),
                      float(std::max(fs.reflectionSampleSet, 0)),
                      float(std::max(fs.reflectionSampleBlock, 1)))};
}

FrameUniforms::~FrameUniforms() {
    if (m_frameUbo)
        glDeleteBuffers(1, &m_frameUbo);
    if (m_iblUbo)
        glDeleteBuffers(1, &m_iblUbo);
}

void FrameUniforms::initialize() {
    glCreateBuffers(1, &m_frameUbo);
    glNamedBufferStorage(m_frameUbo, sizeof(FrameBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glCreateBuffers(1, &m_iblUbo);
    glNamedBufferStorage(m_iblUbo, sizeof(IblBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
}

void FrameUniforms::bindFrame(const FrameBlock& b) {
    glNamedBufferSubData(m_frameUbo, 0, sizeof(FrameBlock), &b);
    glBindBufferBase(GL_UNIFORM_BUFFER, binding::kFrameUbo, m_frameUbo);
}

void FrameUniforms::bindIbl(const IblBlock& b) {
    glNamedBufferSubData(m_iblUbo, 0, sizeof(IblBlock), &b);
    glBindBufferBase(GL_UNIFORM_BUFFER, binding::kIblUbo, m_iblUbo);
}

} // namespace velvet::render
