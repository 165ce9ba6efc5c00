#include "render/brdf_probe.h"

#include "render/sheen_lut.h"

#include <algorithm>
#include <epoxy/gl.h>

namespace velvet::render {
namespace {

/// Mirrors ProbeSample in brdf_probe.comp (std430, vec4 only).
struct ProbeSample {
    glm::vec4 n, l, v;
    glm::vec4 baseColorMetallic;
    glm::vec4 specularColorWeight;
    glm::vec4 sheenColorRoughness;
    glm::vec4 scalars; ///< roughness, ior, clearcoat, clearcoat roughness
    glm::ivec4 terms;
    glm::ivec4 terms2;
    glm::vec4 anisotropy; ///< xyz direction (perpendicular to n), w strength
};
/// Mirrors ProbeResult in brdf_probe.comp.
struct ProbeResult {
    glm::vec4 full, dvs, fresnel, diffuse;
};
constexpr int kLocalSize = 64;
constexpr GLuint kSampleBinding = 0, kResultBinding = 1;
constexpr GLint kCountLocation = 0;

} // namespace

BrdfProbe::~BrdfProbe() {
    release();
}

void BrdfProbe::release() {
    m_program.release();
    for (GLuint b : {m_sampleSsbo, m_resultSsbo})
        if (b)
            glDeleteBuffers(1, &b);
    if (m_sheenLut)
        glDeleteTextures(1, &m_sheenLut);
    m_sampleSsbo = m_resultSsbo = m_sheenLut = 0;
    m_capacity = 0;
}

bool BrdfProbe::initialize(std::string* error) {
    release();
    if (!m_program.build("brdf_probe.comp", {}, {}, error))
        return false;
    // The same sheen albedo texture the lighting binds (render/sheen_lut.h).
    m_sheenLut = createSheenAlbedoLut();
    return true;
}

std::vector<BrdfProbeResult> BrdfProbe::evaluate(const std::vector<BrdfProbeSample>& samples) {
    std::vector<BrdfProbeResult> out(samples.size());
    if (samples.empty() || !m_program.id())
        return out;
    std::vector<ProbeSample> packed(samples.size());
    for (size_t i = 0; i < samples.size(); ++i) {
        const BrdfProbeSample& s = samples[i];
        const brdf::Surface& m = s.surface;
        packed[i] = {
            glm::vec4(s.n, 0.0f),
            glm::vec4(s.l, 0.0f),
            glm::vec4(s.v, 0.0f),
            glm::vec4(m.baseColor, m.metallic),
            glm::vec4(m.specularColor, m.specularWeight),
            glm::vec4(m.sheenColor, m.sheenRoughness),
            glm::vec4(m.roughness, m.ior, m.clearcoat, m.clearcoatRoughness),
            glm::ivec4(int(m.distribution), int(m.visibility), int(m.fresnel), int(m.diffuse)),
            glm::ivec4(int(m.sheenModel), 0, 0, 0),
            glm::vec4(m.anisotropyDirection, m.anisotropyStrength)};
    }
    if (samples.size() > m_capacity) {
        for (GLuint b : {m_sampleSsbo, m_resultSsbo})
            if (b)
                glDeleteBuffers(1, &b);
        glCreateBuffers(1, &m_sampleSsbo);
        glNamedBufferStorage(m_sampleSsbo, GLsizeiptr(samples.size() * sizeof(ProbeSample)),
                             nullptr, GL_DYNAMIC_STORAGE_BIT);
        glCreateBuffers(1, &m_resultSsbo);
        glNamedBufferStorage(m_resultSsbo, GLsizeiptr(samples.size() * sizeof(ProbeResult)),
                             nullptr, GL_DYNAMIC_STORAGE_BIT);
        m_capacity = samples.size();
    }
    glNamedBufferSubData(m_sampleSsbo, 0, GLsizeiptr(packed.size() * sizeof(ProbeSample)),
                         packed.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSampleBinding, m_sampleSsbo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kResultBinding, m_resultSsbo);
    glBindTextureUnit(binding::kSheenLutTex, m_sheenLut);
    glUseProgram(m_program.id());
    glProgramUniform1i(m_program.id(), kCountLocation, int(samples.size()));
    glDispatchCompute(GLuint((samples.size() + kLocalSize - 1) / kLocalSize), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<ProbeResult> results(samples.size());
    glGetNamedBufferSubData(m_resultSsbo, 0, GLsizeiptr(results.size() * sizeof(ProbeResult)),
                            results.data());
    glUseProgram(0);
    glBindTextureUnit(binding::kSheenLutTex, 0);
    for (size_t i = 0; i < results.size(); ++i) {
        const ProbeResult& r = results[i];
        out[i] = {glm::vec3(r.full),   r.dvs.x, r.dvs.y, r.dvs.z, r.dvs.w, glm::vec3(r.fresnel),
                  glm::vec3(r.diffuse)};
    }
    return out;
}

} // namespace velvet::render
