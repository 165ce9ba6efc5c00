// The GLSL BRDF (resources/shaders/common_brdf.glsl) against its C++ twins (core/brdf.h) at
// sampled points, as the renderer issue asks: ~2,000 random (n, l, v, roughness) per term choice
// and material, evaluated on the GPU by render/brdf_probe (a compute shader that includes
// common_brdf.glsl), each term and the full layered BRDF within 1e-3 relative (1e-5 absolute
// floor near zero). Roughness is drawn from [0.2, 1] for the assertion: near kMinRoughness the
// sharp lobes are ill-conditioned in float (n.h differs by an ulp between GPU and CPU and D's
// slope amplifies it to ~1e-3 at worst); lowRoughness reports that range, never hides it.
#include "core/brdf.h"
#include "render/brdf_probe.h"
#include "render_test_util.h"

#include <QtTest>
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <random>
#include <string>
#include <vector>

using namespace velvet;

namespace {

constexpr int kSamplesPerCase = 2000;
constexpr float kRelTolerance = 1e-3f;
constexpr float kAbsFloor = 1e-5f;

struct NamedSurface {
    const char* name;
    brdf::Surface surface;
};

std::vector<NamedSurface> surfaces() {
    std::vector<NamedSurface> out;
    brdf::Surface dielectric;
    dielectric.baseColor = {0.8f, 0.3f, 0.2f};
    out.push_back({"dielectric", dielectric});
    brdf::Surface metal = dielectric;
    metal.baseColor = {1.0f, 0.78f, 0.34f};
    metal.metallic = 1.0f;
    out.push_back({"metal", metal});
    brdf::Surface halfMetal = dielectric;
    halfMetal.metallic = 0.5f;
    halfMetal.specularColor = {0.9f, 0.6f, 1.0f};
    halfMetal.specularWeight = 0.7f;
    halfMetal.ior = 1.8f;
    out.push_back({"half metal, coloured specular, ior 1.8", halfMetal});
    brdf::Surface coat = dielectric;
    coat.baseColor = {0.1f, 0.2f, 0.6f};
    coat.clearcoat = 1.0f;
    coat.clearcoatRoughness = 0.2f;
    out.push_back({"clearcoat", coat});
    brdf::Surface sheen = dielectric;
    sheen.baseColor = {0.3f, 0.05f, 0.1f};
    sheen.sheenColor = {0.9f, 0.7f, 0.8f};
    sheen.sheenRoughness = 0.5f;
    out.push_back({"sheen", sheen});
    return out;
}

/// One term changed at a time from the default (glTF Appendix B), every selectable value.
struct TermCase {
    std::string name;
    Distribution d = Distribution::GGX;
    Visibility v = Visibility::SmithGGXSeparable;
    Fresnel f = Fresnel::Schlick;
    Diffuse diffuse = Diffuse::Lambert;
    SheenModel sheen = SheenModel::CharlieContyKulla;
};

std::vector<TermCase> termCases() {
    std::vector<TermCase> out{{"default"}};
    for (int i = 1; i < 3; ++i)
        out.push_back({"D" + std::to_string(i), Distribution(i)});
    for (int i = 1; i < 7; ++i) {
        TermCase c{"V" + std::to_string(i)};
        c.v = Visibility(i);
        out.push_back(c);
    }
    for (int i = 1; i < 3; ++i) {
        TermCase c{"F" + std::to_string(i)};
        c.f = Fresnel(i);
        out.push_back(c);
    }
    TermCase burley{"Burley"};
    burley.diffuse = Diffuse::Burley;
    out.push_back(burley);
    for (int i = 1; i < 3; ++i) {
        TermCase c{"sheen" + std::to_string(i)};
        c.sheen = SheenModel(i);
        out.push_back(c);
    }
    return out;
}

/// A unit vector in the hemisphere around @p n with n.x >= @p minCos (uniform in solid angle).
glm::vec3 hemisphere(std::mt19937& rng, glm::vec3 n, float minCos) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const glm::vec3 t = glm::normalize(
        glm::cross(std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0), n));
    const glm::vec3 b = glm::cross(n, t);
    const float c = minCos + (1.0f - minCos) * u(rng);
    const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
    const float phi = 6.2831853f * u(rng);
    return glm::normalize(t * (s * std::cos(phi)) + b * (s * std::sin(phi)) + n * c);
}

/// Error in units of the tolerance (<= 1 passes): |gpu - cpu| / max(1e-3 |cpu|, 1e-5).
float scaledError(float gpu, float cpu) {
    if (!std::isfinite(gpu) || !std::isfinite(cpu))
        return gpu == cpu ? 0.0f : 1e9f;
    return std::abs(gpu - cpu) / std::max(kRelTolerance * std::abs(cpu), kAbsFloor);
}
float scaledError(glm::vec3 gpu, glm::vec3 cpu) {
    return std::max(
        {scaledError(gpu.x, cpu.x), scaledError(gpu.y, cpu.y), scaledError(gpu.z, cpu.z)});
}
float relativeError(float gpu, float cpu) {
    return std::abs(gpu - cpu) / std::max(std::abs(cpu), kAbsFloor / kRelTolerance);
}
float relativeError(glm::vec3 gpu, glm::vec3 cpu) {
    return std::max(
        {relativeError(gpu.x, cpu.x), relativeError(gpu.y, cpu.y), relativeError(gpu.z, cpu.z)});
}

/// The C++ twins of what brdf_probe.comp writes, with the same clamps.
render::BrdfProbeResult cpuTwin(const render::BrdfProbeSample& p) {
    const brdf::Surface& s = p.surface;
    const float NdotL = std::max(glm::dot(p.n, p.l), 1e-4f);
    const float NdotV = std::max(glm::dot(p.n, p.v), 1e-4f);
    const glm::vec3 h = glm::normalize(p.l + p.v);
    const float NdotH = std::clamp(glm::dot(p.n, h), 0.0f, 1.0f);
    const float VdotH = std::clamp(glm::dot(p.v, h), 0.0f, 1.0f);
    const float rough = std::max(s.roughness, brdf::kMinRoughness);
    const float alpha = rough * rough;
    render::BrdfProbeResult r;
    r.full = brdf::evalDirectional(s, p.n, p.v, p.l);
    r.distribution = brdf::distribution(s.distribution, NdotH, alpha);
    r.visibility = brdf::visibility(s.visibility, NdotL, NdotV, NdotH, VdotH, alpha);
    r.sheenD = brdf::distributionCharlie(NdotH, s.sheenRoughness);
    r.sheenV = brdf::visibilitySheen(s.sheenModel, NdotL, NdotV, s.sheenRoughness);
    r.fresnel = brdf::fresnelDielectric(s.fresnel, brdf::dielectricF0(s), s.ior, VdotH);
    r.diffuse = brdf::diffuse(s.diffuse, s.baseColor, rough, NdotL, NdotV, VdotH);
    return r;
}

std::vector<render::BrdfProbeSample> randomSamples(std::mt19937& rng, const brdf::Surface& base,
                                                   const TermCase& c, float minRoughness) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::normal_distribution<float> g(0.0f, 1.0f);
    std::vector<render::BrdfProbeSample> out(kSamplesPerCase);
    for (auto& p : out) {
        glm::vec3 n;
        do
            n = glm::vec3(g(rng), g(rng), g(rng));
        while (glm::dot(n, n) < 1e-6f);
        p.n = glm::normalize(n);
        // n.l, n.v >= 0.02: grazing angles are where every term is clamped; they are covered by
        // the clamp test below.
        p.l = hemisphere(rng, p.n, 0.02f);
        p.v = hemisphere(rng, p.n, 0.02f);
        p.surface = base;
        p.surface.roughness = minRoughness + (1.0f - minRoughness) * u(rng);
        p.surface.distribution = c.d;
        p.surface.visibility = c.v;
        p.surface.fresnel = c.f;
        p.surface.diffuse = c.diffuse;
        p.surface.sheenModel = c.sheen;
    }
    return out;
}

} // namespace

class TestRenderBrdfProbe : public QObject {
    Q_OBJECT

    render::BrdfProbe m_probe;

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        QVERIFY2(m_probe.initialize(&error), error.c_str());
    }

    // Every term choice x every material: each term and the layered BRDF within 1e-3 relative.
    void gpuMatchesCpuTwins() {
        std::mt19937 rng(20240611u);
        const char* termNames[] = {"full", "D", "V", "sheen D", "sheen V", "F", "diffuse"};
        float worstRel[7] = {};
        int failures = 0;
        for (const TermCase& c : termCases())
            for (const NamedSurface& m : surfaces()) {
                const auto samples = randomSamples(rng, m.surface, c, 0.2f);
                const auto gpu = m_probe.evaluate(samples);
                QCOMPARE(gpu.size(), samples.size());
                for (size_t i = 0; i < samples.size(); ++i) {
                    const auto cpu = cpuTwin(samples[i]);
                    const float scaled[7] = {scaledError(gpu[i].full, cpu.full),
                                             scaledError(gpu[i].distribution, cpu.distribution),
                                             scaledError(gpu[i].visibility, cpu.visibility),
                                             scaledError(gpu[i].sheenD, cpu.sheenD),
                                             scaledError(gpu[i].sheenV, cpu.sheenV),
                                             scaledError(gpu[i].fresnel, cpu.fresnel),
                                             scaledError(gpu[i].diffuse, cpu.diffuse)};
                    const float rel[7] = {relativeError(gpu[i].full, cpu.full),
                                          relativeError(gpu[i].distribution, cpu.distribution),
                                          relativeError(gpu[i].visibility, cpu.visibility),
                                          relativeError(gpu[i].sheenD, cpu.sheenD),
                                          relativeError(gpu[i].sheenV, cpu.sheenV),
                                          relativeError(gpu[i].fresnel, cpu.fresnel),
                                          relativeError(gpu[i].diffuse, cpu.diffuse)};
                    for (int t = 0; t < 7; ++t) {
                        worstRel[t] = std::max(worstRel[t], rel[t]);
                        if (scaled[t] > 1.0f && ++failures <= 10)
                            qWarning("%s, %s, %s: gpu vs cpu off by %.3g of the tolerance "
                                     "(roughness %.3f)",
                                     c.name.c_str(), m.name, termNames[t], double(scaled[t]),
                                     double(samples[i].surface.roughness));
                    }
                }
            }
        for (int t = 0; t < 7; ++t)
            qInfo("worst relative error, %s: %.3g", termNames[t], double(worstRel[t]));
        QCOMPARE(failures, 0);
    }

    // Roughness in [0, 0.2]: reported (worst relative error of the layered BRDF and of D),
    // asserted only within 1e-2.
    void lowRoughness() {
        std::mt19937 rng(7u);
        float worstFull = 0.0f, worstD = 0.0f;
        for (const TermCase& c : termCases()) {
            std::vector<render::BrdfProbeSample> samples;
            for (const NamedSurface& m : surfaces()) {
                auto s = randomSamples(rng, m.surface, c, 0.0f);
                for (auto& p : s)
                    p.surface.roughness *= 0.2f;
                samples.insert(samples.end(), s.begin(), s.begin() + 400);
            }
            const auto gpu = m_probe.evaluate(samples);
            for (size_t i = 0; i < samples.size(); ++i) {
                const auto cpu = cpuTwin(samples[i]);
                worstFull = std::max(worstFull, relativeError(gpu[i].full, cpu.full));
                worstD = std::max(worstD, relativeError(gpu[i].distribution, cpu.distribution));
            }
        }
        qInfo("roughness in [0, 0.2]: worst relative error, full %.3g, D %.3g", double(worstFull),
              double(worstD));
        QVERIFY(worstFull < 1e-2f);
        QVERIFY(worstD < 1e-2f);
    }

    // Back-facing light gives zero; the clamps at grazing n.v agree.
    void clampsAgree() {
        brdf::Surface s = surfaces()[0].surface;
        std::vector<render::BrdfProbeSample> samples;
        const glm::vec3 n(0, 0, 1);
        samples.push_back({n, glm::normalize(glm::vec3(0.3f, 0.0f, -0.5f)), n, s});
        samples.push_back({n, glm::normalize(glm::vec3(0.3f, 0.0f, 0.5f)),
                           glm::normalize(glm::vec3(-1.0f, 0.0f, 1e-6f)), s});
        const auto gpu = m_probe.evaluate(samples);
        QCOMPARE(gpu[0].full.x, 0.0f);
        for (size_t i = 0; i < samples.size(); ++i)
            QVERIFY2(scaledError(gpu[i].full, cpuTwin(samples[i]).full) <= 1.0f,
                     qPrintable(QString("sample %1").arg(i)));
    }
};

QTEST_GUILESS_MAIN(TestRenderBrdfProbe)
#include "test_render_brdf_probe.moc"
