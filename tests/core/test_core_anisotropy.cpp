// KHR_materials_anisotropy in core (issue 13): the anisotropic GGX twins of core/brdf.h are
// normalised, reduce to the isotropic terms when alpha_t = alpha_b, stretch the highlight along
// the anisotropy direction and never reflect more than comes in; strength 0 changes nothing; the
// parameters load with defaults from old files; the material output carries the direction.
#include "core/brdf.h"
#include "core/graph/graph_compiler.h"
#include "core/graph/graph_eval.h"
#include "graph_test_util.h"

#include <QtTest>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <numbers>
#include <random>

using namespace velvet;

namespace {

constexpr double kPi = std::numbers::pi;

/// A unit vector at polar angle @p theta from +Z and azimuth @p phi from +X.
glm::vec3 dir(double theta, double phi) {
    return glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                     float(std::cos(theta)));
}

/// Integral over the hemisphere around n = +Z of @p f(w) dw, with kU x kPhi nodes: theta =
/// pi/2 u^2 puts them where narrow lobes live.
template <class F>
double integrateHemisphere(int kU, int kPhi, F f) {
    double sum = 0.0;
    for (int i = 0; i < kU; ++i) {
        const double u = (i + 0.5) / kU;
        const double theta = 0.5 * kPi * u * u, dTheta = kPi * u / kU;
        for (int j = 0; j < kPhi; ++j) {
            const double phi = (j + 0.5) / kPhi * 2.0 * kPi;
            sum += f(dir(theta, phi)) * std::sin(theta) * dTheta * (2.0 * kPi / kPhi);
        }
    }
    return sum;
}

/// Integral over the hemisphere of D(h) (n.h), n = +Z, t = +X, b = +Y.
double integrateD(float at, float ab) {
    return integrateHemisphere(1500, 360, [&](glm::vec3 h) {
        return double(brdf::distributionGGXAnisotropic(h.z, h.x, h.y, at, ab)) * h.z;
    });
}

/// Directional albedo of evalDirectional (which includes n.l) towards @p v, n = +Z.
double albedo(const brdf::Surface& s, glm::vec3 v) {
    return integrateHemisphere(600, 240, [&](glm::vec3 l) {
        return double(brdf::evalDirectional(s, glm::vec3(0, 0, 1), v, l).x);
    });
}

/// A white metal: Fresnel 1 everywhere, so the albedo is the D V lobe's alone.
brdf::Surface whiteMetal(float roughness, float strength, glm::vec3 t) {
    brdf::Surface s;
    s.baseColor = glm::vec3(1.0f);
    s.metallic = 1.0f;
    s.roughness = roughness;
    s.anisotropyStrength = strength;
    s.anisotropyDirection = t;
    return s;
}

} // namespace

class TestCoreAnisotropy : public QObject {
    Q_OBJECT
private slots:
    void alphas() {
        // KHR_materials_anisotropy: alpha_t = mix(alpha, 1, s^2), alpha_b = alpha = r^2.
        QCOMPARE(brdf::anisotropicAlphas(0.5f, 0.0f), glm::vec2(0.25f, 0.25f));
        QCOMPARE(brdf::anisotropicAlphas(0.5f, 1.0f), glm::vec2(1.0f, 0.25f));
        const glm::vec2 a = brdf::anisotropicAlphas(0.5f, 0.6f);
        QVERIFY(std::abs(a.x - (0.25f + 0.75f * 0.36f)) < 1e-6f);
        // Clamped like every lobe.
        const float m = brdf::kMinRoughness * brdf::kMinRoughness;
        QCOMPARE(brdf::anisotropicAlphas(0.0f, 0.0f), glm::vec2(m, m));
    }

    void distributionIsNormalised() {
        for (auto [at, ab] : std::array<std::pair<float, float>, 5>{
                 {{0.25f, 0.25f}, {0.5f, 0.1f}, {1.0f, 0.2f}, {0.3f, 0.08f}, {0.7f, 0.45f}}}) {
            const double integral = integrateD(at, ab);
            QVERIFY2(std::abs(integral - 1.0) < 2e-3,
                     qPrintable(QString("at %1 ab %2: %3").arg(at).arg(ab).arg(integral)));
        }
    }

    void equalAlphasAreIsotropic() {
        std::mt19937 rng(13);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        const glm::vec3 n(0, 0, 1), t(1, 0, 0), b(0, 1, 0);
        for (int i = 0; i < 2000; ++i) {
            const float alpha = 0.02f + 0.98f * u(rng);
            const glm::vec3 v = dir(0.5 * kPi * u(rng) * 0.98, 2.0 * kPi * u(rng));
            const glm::vec3 l = dir(0.5 * kPi * u(rng) * 0.98, 2.0 * kPi * u(rng));
            const glm::vec3 h = glm::normalize(v + l);
            const float dIso = brdf::distributionGGX(h.z, brdf::sinSquared(n, h), alpha);
            const float dAni =
                brdf::distributionGGXAnisotropic(h.z, glm::dot(t, h), glm::dot(b, h), alpha, alpha);
            QVERIFY2(std::abs(dAni - dIso) <= 2e-5f * dIso + 1e-6f,
                     qPrintable(QString("D %1 vs %2").arg(dAni).arg(dIso)));
            const float vIso = brdf::visibilitySmithGGXCorrelated(l.z, v.z, alpha);
            const float vAni = brdf::visibilitySmithGGXCorrelatedAnisotropic(
                l.z, v.z, v.x, v.y, l.x, l.y, alpha, alpha);
            QVERIFY2(std::abs(vAni - std::min(vIso, 1.0f)) <= 2e-5f * vIso,
                     qPrintable(QString("V %1 vs %2").arg(vAni).arg(vIso)));
        }
    }

    void strengthZeroChangesNothing() {
        // Bit for bit: the anisotropy direction is not even read at strength 0, nor when the
        // distribution is not GGX.
        Material m;
        m.setScalar(ParamId::SheenWeight, 0.5f);
        m.setScalar(ParamId::ClearcoatWeight, 0.3f);
        const brdf::Surface base = brdf::surfaceFromMaterial(m);
        QCOMPARE(base.anisotropyStrength, 0.0f);
        brdf::Surface turned = base;
        turned.anisotropyDirection = glm::normalize(glm::vec3(0.3f, 0.9f, 0.1f));
        brdf::Surface beckmann = base, beckmannAniso = base;
        beckmann.distribution = beckmannAniso.distribution = Distribution::Beckmann;
        beckmannAniso.anisotropyStrength = 0.8f;
        const glm::vec3 n(0, 0, 1);
        for (int i = 0; i < 64; ++i) {
            const glm::vec3 v = dir(0.02 * i, 0.3 * i), l = dir(1.4 - 0.02 * i, 2.0 + 0.1 * i);
            QCOMPARE(brdf::evalDirectional(turned, n, v, l), brdf::evalDirectional(base, n, v, l));
            QCOMPARE(brdf::evalDirectional(beckmannAniso, n, v, l),
                     brdf::evalDirectional(beckmann, n, v, l));
            const brdf::Lobes a = brdf::evalLobes(turned, n, v, l, l, 0.1f);
            const brdf::Lobes b = brdf::evalLobes(base, n, v, l, l, 0.1f);
            QCOMPARE(a.sum(), b.sum());
        }
        QVERIFY(!brdf::usesAnisotropy(base) && !brdf::usesAnisotropy(beckmannAniso));
    }

    void highlightStretchesAlongTheDirection() {
        const glm::vec2 a = brdf::anisotropicAlphas(0.3f, 0.8f);
        for (double theta : {0.05, 0.15, 0.3}) {
            const glm::vec3 alongT = dir(theta, 0.0), alongB = dir(theta, 0.5 * kPi);
            QVERIFY(brdf::distributionGGXAnisotropic(alongT.z, alongT.x, alongT.y, a.x, a.y) >
                    brdf::distributionGGXAnisotropic(alongB.z, alongB.x, alongB.y, a.x, a.y));
        }
        // Through evalDirectional, on a direction turned 30 degrees from +X: seen from above, a
        // light tilted along it lights the surface more than one tilted across it.
        const float r = glm::radians(30.0f);
        const glm::vec3 t(std::cos(r), std::sin(r), 0.0f);
        const brdf::Surface s = whiteMetal(0.3f, 0.8f, t);
        const glm::vec3 n(0, 0, 1), v(0, 0, 1);
        const glm::vec3 lAlong = dir(0.4, r), lAcross = dir(0.4, r + 0.5 * kPi);
        QVERIFY(brdf::evalDirectional(s, n, v, lAlong).x >
                2.0f * brdf::evalDirectional(s, n, v, lAcross).x);
        // And the isotropic surface does not tell them apart.
        const brdf::Surface iso = whiteMetal(0.3f, 0.0f, t);
        QVERIFY(std::abs(brdf::evalDirectional(iso, n, v, lAlong).x -
                         brdf::evalDirectional(iso, n, v, lAcross).x) < 1e-5f);
    }

    void whiteFurnaceBound() {
        // A white metal's single-scattering albedo is at most 1 (it loses energy, never gains
        // it), and anisotropy changes it only a little. With the multiple-scattering compensation
        // (core/brdf_energy.h, E of the isotropic lobe at the base roughness) the isotropic lobe
        // keeps all of it and the stretched one, rougher along t, still gains none.
        for (float roughness : {0.3f, 0.6f}) {
            for (float strength : {0.0f, 0.5f, 1.0f}) {
                for (double thetaV : {0.0, 0.7, 1.3}) {
                    for (double phiV : {0.0, 0.8}) {
                        brdf::Surface s = whiteMetal(roughness, strength, glm::vec3(1, 0, 0));
                        const double compensated = albedo(s, dir(thetaV, phiV));
                        QVERIFY2(compensated <= 1.0 + 1e-2 && compensated > 0.5,
                                 qPrintable(QString("compensated r %1 s %2 view %3/%4: %5")
                                                .arg(roughness)
                                                .arg(strength)
                                                .arg(thetaV)
                                                .arg(phiV)
                                                .arg(compensated)));
                        if (strength == 0.0f)
                            QVERIFY(std::abs(compensated - 1.0) < 1e-2);
                        s.multipleScattering = false;
                        const double e = albedo(s, dir(thetaV, phiV));
                        QVERIFY2(e <= 1.0 + 2e-3 && e > 0.3,
                                 qPrintable(QString("r %1 s %2 view %3/%4: %5")
                                                .arg(roughness)
                                                .arg(strength)
                                                .arg(thetaV)
                                                .arg(phiV)
                                                .arg(e)));
                    }
                }
            }
        }
    }

    void parametersAndOldFiles() {
        const ParamMeta& strength = paramMeta(ParamId::AnisotropyStrength);
        const ParamMeta& rotation = paramMeta(ParamId::AnisotropyRotation);
        QCOMPARE(std::string(strength.id), std::string("lobes.anisotropy.strength"));
        QCOMPARE(std::string(rotation.id), std::string("lobes.anisotropy.rotation"));
        QCOMPARE(rotation.min, -180.0f);
        QCOMPARE(rotation.max, 180.0f);
        QCOMPARE(std::string(textureSlotMeta(TextureSlot::Anisotropy).id),
                 std::string("anisotropy"));
        QVERIFY(!textureSlotMeta(TextureSlot::Anisotropy).isColor);
        // Before the BRDF term choices, after the sheen.
        QVERIFY(int(ParamId::AnisotropyStrength) == int(ParamId::SheenRoughness) + 1);
        QVERIFY(int(ParamId::AnisotropyRotation) + 1 == int(ParamId::Distribution));
        const Material m;
        QCOMPARE(m.scalar(ParamId::AnisotropyStrength), 0.0f);
        QCOMPARE(m.scalar(ParamId::AnisotropyRotation), 0.0f);
    }

    void materialOutputCarriesTheDirection() {
        using namespace graph;
        const NodeType* out = findNodeType(kOutputTypeId);
        QVERIFY(out);
        const int dirIn = out->inputIndex("anisotropyDirection");
        QVERIFY(dirIn >= 0);
        QCOMPARE(out->inputs[size_t(dirIn)].type, PortType::Vec2);
        QCOMPARE(paramForOutputInput(PortIndex(dirIn)), ParamId::Count);
        QCOMPARE(outputInputForParam(ParamId::AnisotropyStrength),
                 out->inputIndex("anisotropyStrength"));
        QCOMPARE(outputInputForParam(ParamId::AnisotropyRotation),
                 out->inputIndex("anisotropyRotation"));

        Graph g;
        const NodeId o = test::add(g, kOutputTypeId);
        const NodeId weave = test::add(g, "fabric.weave");
        test::mustConnect(g, test::link(g, weave, "direction", o, "anisotropyDirection"));
        const CompiledGraph c = compileGraph(g);
        QVERIFY2(c.ok, c.error.c_str());
        QVERIFY(c.glsl.find("    vec2 anisotropyDirection;\n") != std::string::npos);
        QVERIFY(c.glsl.find("    float anisotropyStrength;\n") != std::string::npos);
        QVERIFY(c.glsl.find("    float anisotropyRotation;\n") != std::string::npos);
        QVERIFY(c.glsl.find("m.anisotropyDirection = vec2(1.0, 0.0);") != std::string::npos);
        QVERIFY(c.glsl.find("m.anisotropyDirection = ") !=
                c.glsl.rfind("m.anisotropyDirection = "));

        // The CPU twin hands the yarn direction over: unit, along U or V.
        const GraphEvaluator eval(g);
        bool sawU = false, sawV = false;
        for (int i = 0; i < 64; ++i) {
            const glm::vec2 uv(0.013f * i, 0.007f * i);
            const GraphSample s = eval.evaluate(uv);
            QVERIFY(s.outputInputs[size_t(dirIn)].has_value());
            const glm::vec2 d(*s.outputInputs[size_t(dirIn)]);
            QVERIFY(std::abs(glm::length(d) - 1.0f) < 1e-3f);
            sawU |= std::abs(d.x) > 0.99f;
            sawV |= std::abs(d.y) > 0.99f;
        }
        QVERIFY(sawU || sawV);
    }
};

QTEST_APPLESS_MAIN(TestCoreAnisotropy)
#include "test_core_anisotropy.moc"
