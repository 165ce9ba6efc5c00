#pragma once
/// @file brdf_probe.h
/// Evaluates the GPU BRDF (resources/shaders/common_brdf.glsl) at arbitrary sample points through
/// a small compute shader (resources/shaders/brdf_probe.comp), so tests can compare every GLSL
/// term with its C++ twin (core/brdf.h) at sampled (n, l, v, roughness) rather than through
/// rendered pixels. Needs a current GL 4.5 core context; not used by the renderer itself.

#include "core/brdf.h"
#include "render/shader_program.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <string>
#include <vector>

namespace velvet::render {

/// One evaluation point: unit vectors (world space) and the material as shading uses it.
struct BrdfProbeSample {
    glm::vec3 n{0, 0, 1};
    glm::vec3 l{0, 0, 1};
    glm::vec3 v{0, 0, 1};
    brdf::Surface surface;
};

/// What the GPU returned for one sample. Term values use n.l and n.v clamped to >= 1e-4, alpha
/// = max(roughness, kMinRoughness)^2 and the half vector, exactly as shadeDirectional() does.
struct BrdfProbeResult {
    glm::vec3 full{0.0f};    ///< shadeDirectional(): f(l, v) max(n.l, 0), every lobe layered
    float distribution = 0;  ///< distribution(surface.distribution, n.h, alpha)
    float visibility = 0;    ///< visibility(surface.visibility, ...)
    float sheenD = 0;        ///< distributionCharlie(n.h, sheenRoughness)
    float sheenV = 0;        ///< visibilitySheen(surface.sheenModel, ...)
    glm::vec3 fresnel{0.0f}; ///< fresnelDielectric(surface.fresnel, dielectricF0, ior, v.h)
    glm::vec3 diffuse{0.0f}; ///< diffuse(surface.diffuse, baseColor, roughness, ...)
};

class BrdfProbe {
public:
    BrdfProbe() = default;
    /// Must run with the context current (frees GL objects).
    ~BrdfProbe();
    BrdfProbe(const BrdfProbe&) = delete;
    BrdfProbe& operator=(const BrdfProbe&) = delete;

    /// Compiles brdf_probe.comp and uploads the sheen albedo tables (core/brdf.h, the same
    /// RGBA32F bilinear texture the renderer samples). False + message (file:line).
    bool initialize(std::string* error);

    /// Evaluates every sample on the GPU (one dispatch, read back with glGetNamedBufferSubData).
    std::vector<BrdfProbeResult> evaluate(const std::vector<BrdfProbeSample>& samples);

private:
    void release();
    ComputeProgram m_program;
    unsigned m_sheenLut = 0;
    unsigned m_sampleSsbo = 0, m_resultSsbo = 0;
    size_t m_capacity = 0;
};

} // namespace velvet::render
