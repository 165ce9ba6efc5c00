// The GLSL BRDF (resources/shaders/common_brdf.glsl) against its C++ twins (core/brdf.h) at
// sampled points, as the renderer issue asks: random (n, l, v, roughness) per term choice and
// material, evaluated on the GPU by render/brdf_probe (a compute shader that includes
// common_brdf.glsl), each term and the full layered BRDF within 1e-3 relative at every roughness
// the UI allows (0..1, below kMinRoughness the clamp applies). The only absolute floor is 1e-5,
// for values that are tiny compared with the lobe (a GGX peak at kMinRoughness is ~8e4, a tail
// under 1e-5 carries no visible energy); it never applies near a peak.
// Half of the samples put the half vector within a few alpha of n, where D is steepest: before
// D was written with sin^2 = |n x h|^2 (Filament's form), 1 - (n.h)^2 lost every digit there and
// GPU and twin differed by up to 4e-3 below roughness 0.2.
#include "core/brdf.h"
#include "core/brdf_energy.h"
#include "core/diffuse_albedo.h"
#include "render/brdf_probe.h"
#include "render/sheen_lut.h"
#include "render_test_util.h"

#include <QtTest>
#include <algorithm>
#include <cmath>
#include <epoxy/gl.h>
#include <glm/geometric.hpp>
#include <random>
#include <string>
#include <vector>

using namespace velvet;

namespace {

constexpr int kSamplesPerCase = 2000;
/// Roughness bands reported separately (the lower edge of the first is 0: clamped to
/// kMinRoughness by the shading code).
constexpr float kBands[] = {0.0f, brdf::kMinRoughness, 0.1f, 0.2f, 1.0f};
constexpr int kBandCount = 4;
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
    const float sin2H = brdf::sinSquared(p.n, h);
    const float VdotH = std::clamp(glm::dot(p.v, h), 0.0f, 1.0f);
    const float rough = std::max(s.roughness, brdf::kMinRoughness);
    const float alpha = rough * rough;
    render::BrdfProbeResult r;
    r.full = brdf::evalDirectional(s, p.n, p.v, p.l);
    r.distribution = brdf::distribution(s.distribution, NdotH, sin2H, alpha);
    r.visibility = brdf::visibility(s.visibility, NdotL, NdotV, NdotH, VdotH, alpha);
    r.sheenD = brdf::distributionCharlie(NdotH, sin2H, s.sheenRoughness);
    r.sheenV = brdf::visibilitySheen(s.sheenModel, NdotL, NdotV, s.sheenRoughness);
    r.fresnel = brdf::fresnelDielectric(s.fresnel, brdf::dielectricF0(s), s.ior, VdotH);
    r.diffuse = brdf::diffuse(s.diffuse, s.baseColor, rough, NdotL, NdotV, VdotH);
    return r;
}

/// kSamplesPerCase samples of @p base with term choice @p c: roughness uniform in
/// [minRoughness, maxRoughness]; every other sample is a peak sample, whose half vector is n
/// tilted by |N(0, 2 alpha)| (the lobe's steepest part), otherwise l and v are uniform.
std::vector<render::BrdfProbeSample> randomSamples(std::mt19937& rng, const brdf::Surface& base,
                                                   const TermCase& c, float minRoughness,
                                                   float maxRoughness = 1.0f) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::normal_distribution<float> g(0.0f, 1.0f);
    std::vector<render::BrdfProbeSample> out;
    out.reserve(kSamplesPerCase);
    while (int(out.size()) < kSamplesPerCase) {
        render::BrdfProbeSample p;
        glm::vec3 n;
        do
            n = glm::vec3(g(rng), g(rng), g(rng));
        while (glm::dot(n, n) < 1e-6f);
        p.n = glm::normalize(n);
        p.surface = base;
        p.surface.roughness = minRoughness + (maxRoughness - minRoughness) * u(rng);
        p.surface.distribution = c.d;
        p.surface.visibility = c.v;
        p.surface.fresnel = c.f;
        p.surface.diffuse = c.diffuse;
        p.surface.sheenModel = c.sheen;
        // n.l, n.v >= 0.02: grazing angles are where every term is clamped; they are covered by
        // the clamp test below.
        p.v = hemisphere(rng, p.n, 0.02f);
        if (out.size() % 2 == 1) {
            const float rough = std::max(p.surface.roughness, brdf::kMinRoughness);
            const float tilt = std::min(std::abs(g(rng)) * 2.0f * rough * rough, 1.2f);
            const glm::vec3 t = glm::normalize(glm::cross(p.n, p.v + glm::vec3(1e-3f, 0, 0)));
            const float phi = 6.2831853f * u(rng);
            const glm::vec3 axis = std::cos(phi) * t + std::sin(phi) * glm::cross(p.n, t);
            const glm::vec3 h = glm::normalize(std::cos(tilt) * p.n + std::sin(tilt) * axis);
            p.l = glm::normalize(glm::reflect(-p.v, h));
            if (glm::dot(p.n, p.l) < 0.02f)
                continue;
        } else {
            p.l = hemisphere(rng, p.n, 0.02f);
        }
        out.push_back(p);
    }
    return out;
}

int bandOf(float roughness) {
    for (int b = 0; b < kBandCount - 1; ++b)
        if (roughness < kBands[b + 1])
            return b;
    return kBandCount - 1;
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

    // The one albedo texture (render/sheen_lut.h, bound by the lighting and by this probe) holds
    // core's tables bit for bit: red the Conty-Kulla sheen table, green the one of Ashikhmin and
    // Neubelt (one function), blue Burley's diffuse albedo, alpha the specular lobe's E; it is
    // sampled as the C++ twins look it up (bilinear, clamp to edge).
    void sheenLutHoldsTheCppTables() {
        const GLuint lut = render::createSheenAlbedoLut();
        QVERIFY(lut != 0);
        constexpr int N = brdf::kSheenLutSize;
        GLint width = 0, height = 0, minFilter = 0, wrapS = 0, wrapT = 0;
        glGetTextureLevelParameteriv(lut, 0, GL_TEXTURE_WIDTH, &width);
        glGetTextureLevelParameteriv(lut, 0, GL_TEXTURE_HEIGHT, &height);
        glGetTextureParameteriv(lut, GL_TEXTURE_MIN_FILTER, &minFilter);
        glGetTextureParameteriv(lut, GL_TEXTURE_WRAP_S, &wrapS);
        glGetTextureParameteriv(lut, GL_TEXTURE_WRAP_T, &wrapT);
        QCOMPARE(width, N);
        QCOMPARE(height, N);
        QCOMPARE(minFilter, GLint(GL_LINEAR));
        QCOMPARE(wrapS, GLint(GL_CLAMP_TO_EDGE));
        QCOMPARE(wrapT, GLint(GL_CLAMP_TO_EDGE));
        std::vector<float> rgba(size_t(N) * N * 4, -1.0f);
        glGetTextureImage(lut, 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)),
                          rgba.data());
        glDeleteTextures(1, &lut);
        int differing = 0;
        const auto compareChannel = [&](const std::vector<float>& table, size_t channel) {
            QCOMPARE(table.size(), size_t(N) * N);
            for (size_t i = 0; i < table.size(); ++i)
                differing += rgba[i * 4 + channel] != table[i];
        };
        compareChannel(brdf::sheenAlbedoLut(SheenModel::CharlieContyKulla), 0);
        compareChannel(brdf::sheenAlbedoLut(SheenModel::CharlieAshikhmin), 1);
        compareChannel(brdf::sheenAlbedoLut(SheenModel::CharlieNeubelt), 1);
        compareChannel(brdf::burleyAlbedoLut(), 2);
        compareChannel(brdf::specularAlbedoLut(), 3);
        QCOMPARE(differing, 0);
        // The conty-kulla table is not the other two (the channels are not one table copied).
        QVERIFY(brdf::sheenAlbedoLut(SheenModel::CharlieContyKulla) !=
                brdf::sheenAlbedoLut(SheenModel::CharlieAshikhmin));
    }

    // Every term choice x every material, roughness over the UI's whole range (half of the
    // samples below 0.2, where the lobes are sharp; half at the lobe peak): each term and the
    // layered BRDF within 1e-3 relative. The worst relative error per roughness band is printed.
    void gpuMatchesCpuTwins() {
        std::mt19937 rng(20240611u);
        const char* termNames[] = {"full", "D", "V", "sheen D", "sheen V", "F", "diffuse"};
        float worstRel[kBandCount][7] = {};
        int failures = 0, counted[kBandCount] = {};
        for (const TermCase& c : termCases())
            for (const NamedSurface& m : surfaces())
                for (const float maxRoughness : {0.2f, 1.0f}) {
                    const auto samples = randomSamples(rng, m.surface, c, 0.0f, maxRoughness);
                    const auto gpu = m_probe.evaluate(samples);
                    QCOMPARE(gpu.size(), samples.size());
                    for (size_t i = 0; i < samples.size(); ++i) {
                        const auto cpu = cpuTwin(samples[i]);
                        const int band = bandOf(samples[i].surface.roughness);
                        ++counted[band];
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
                            worstRel[band][t] = std::max(worstRel[band][t], rel[t]);
                            if (scaled[t] > 1.0f && ++failures <= 10)
                                qWarning("%s, %s, %s: off by %.3g of the tolerance (relative "
                                         "%.3g, roughness %.4f)",
                                         c.name.c_str(), m.name, termNames[t], double(scaled[t]),
                                         double(rel[t]), double(samples[i].surface.roughness));
                        }
                    }
                }
        for (int b = 0; b < kBandCount; ++b) {
            QString line = QString("roughness [%1, %2), %3 samples, worst relative error:")
                               .arg(double(kBands[b]), 0, 'g', 3)
                               .arg(double(kBands[b + 1]), 0, 'g', 3)
                               .arg(counted[b]);
            for (int t = 0; t < 7; ++t)
                line += QString(" %1 %2").arg(termNames[t]).arg(double(worstRel[b][t]), 0, 'g', 3);
            qInfo("%s", qPrintable(line));
            QVERIFY2(counted[b] > 1000, "every roughness band is sampled");
        }
        QCOMPARE(failures, 0);
    }

    // KHR_materials_anisotropy: the layered BRDF of an anisotropic surface (strength 0.2 .. 1,
    // the stretch direction at a random angle in the tangent plane) matches the C++ twin within
    // the same 1e-3 relative tolerance, for a dielectric and a metal.
    void anisotropicGpuMatchesCpuTwin() {
        std::mt19937 rng(9241u);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        int failures = 0, anisotropic = 0;
        float worst = 0.0f;
        for (const NamedSurface& m : surfaces()) {
            auto samples = randomSamples(rng, m.surface, TermCase{"default"}, 0.05f, 1.0f);
            for (auto& p : samples) {
                const glm::vec3 a = glm::normalize(glm::cross(
                    p.n, std::abs(p.n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
                const float phi = 6.2831853f * u(rng);
                p.surface.anisotropyDirection =
                    std::cos(phi) * a + std::sin(phi) * glm::cross(p.n, a);
                p.surface.anisotropyStrength = 0.2f + 0.8f * u(rng);
                anisotropic += brdf::usesAnisotropy(p.surface);
            }
            const auto gpu = m_probe.evaluate(samples);
            for (size_t i = 0; i < samples.size(); ++i) {
                const glm::vec3 cpu = brdf::evalDirectional(samples[i].surface, samples[i].n,
                                                            samples[i].v, samples[i].l);
                worst = std::max(worst, relativeError(gpu[i].full, cpu));
                if (scaledError(gpu[i].full, cpu) > 1.0f && ++failures <= 10)
                    qWarning("%s: GPU %g %g %g, CPU %g %g %g", m.name, double(gpu[i].full.x),
                             double(gpu[i].full.y), double(gpu[i].full.z), double(cpu.x),
                             double(cpu.y), double(cpu.z));
            }
        }
        qInfo("%d anisotropic samples, worst relative error %.3g", anisotropic, double(worst));
        QVERIFY(anisotropic > kSamplesPerCase);
        QCOMPARE(failures, 0);
    }

    // The peak samples do land where D is steep: at the clamp, some have |n x h| below alpha
    // (otherwise the test above would not exercise the cancellation it guards against).
    void peakSamplesReachTheLobe() {
        std::mt19937 rng(7u);
        const auto samples = randomSamples(rng, surfaces()[0].surface, TermCase{"default"}, 0.0f,
                                           brdf::kMinRoughness);
        int nearPeak = 0;
        const float alpha = brdf::kMinRoughness * brdf::kMinRoughness;
        for (const auto& p : samples)
            if (brdf::sinSquared(p.n, glm::normalize(p.l + p.v)) < alpha * alpha)
                ++nearPeak;
        QVERIFY2(nearPeak > kSamplesPerCase / 8, qPrintable(QString::number(nearPeak)));
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
