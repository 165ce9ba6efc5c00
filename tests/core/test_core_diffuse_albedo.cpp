// The diffuse terms' directional albedo for image-based light (core/diffuse_albedo.h): Lambert's
// is 1; Burley's integral has a closed form head-on and agrees with an independent quadrature
// elsewhere; the shipped table is the integration's; the lookup between the table's nodes stays
// within a stated tolerance of the integral.
#include "core/brdf.h"
#include "core/diffuse_albedo.h"

#include <QtTest>
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

using namespace velvet;

namespace {

constexpr double kPi = std::numbers::pi;

/// Burley's albedo (white colour) by a second, independent rule: cosine-weighted midpoint rule in
/// (mu_l = cos theta_l, phi_l) over the whole circle, calling diffuseBurley() directly (not the
/// dispatch), in double for the angles. d omega (n.l) = mu dmu dphi.
double burleyAlbedoByMu(double NdotV, double roughness, int nMu = 600, int nPhi = 360) {
    const double mu = std::max(NdotV, 1e-4);
    const double r = std::max(roughness, double(brdf::kMinRoughness));
    const glm::dvec3 v(std::sqrt(1.0 - mu * mu), 0.0, mu);
    double sum = 0.0;
    for (int a = 0; a < nMu; ++a) {
        const double ml = (a + 0.5) / nMu;
        const double sl = std::sqrt(1.0 - ml * ml);
        for (int b = 0; b < nPhi; ++b) {
            const double phi = (b + 0.5) / nPhi * 2.0 * kPi;
            const glm::dvec3 l(sl * std::cos(phi), sl * std::sin(phi), ml);
            const glm::dvec3 h = glm::normalize(l + v);
            sum += double(brdf::diffuseBurley(glm::vec3(1.0f), float(r), float(ml), float(mu),
                                              float(glm::dot(l, h)))
                              .x) *
                   ml;
        }
    }
    return sum * (1.0 / nMu) * (2.0 * kPi / nPhi);
}

/// Head-on (v = n), l.h = cos(theta / 2), so (l.h)^2 = (1 + mu) / 2 and F_D90 - 1 = r (1 + mu) -
/// 1/2; with f_v = 1, E = 2 int_0^1 (1 + (r (1 + mu) - 1/2) (1 - mu)^5) mu dmu
/// = 1 + 2 ((r - 1/2) B(2, 6) + r B(3, 6)) = 1 + 2 ((r - 1/2) / 42 + r / 168) = 1 + 5 r / 84 - 1
/// / 42.
double burleyHeadOn(double roughness) {
    const double r = std::max(roughness, double(brdf::kMinRoughness));
    return 1.0 + 5.0 * r / 84.0 - 1.0 / 42.0;
}

} // namespace

class TestCoreDiffuseAlbedo : public QObject {
    Q_OBJECT
private slots:
    // Lambert reflects exactly what it receives (its albedo is 1 at every n.v and roughness), and
    // its lookup is exactly 1 (the irradiance term is Lambert's exact image-based light).
    void lambertIsOne() {
        for (float mu : {1.0f, 0.5f, 0.1f, 0.0f})
            for (float r : {0.0f, 0.5f, 1.0f}) {
                const double e = brdf::integrateDiffuseAlbedo(Diffuse::Lambert, mu, r);
                QVERIFY2(std::abs(e - 1.0) < 1e-4, qPrintable(QString::number(e)));
                QCOMPARE(brdf::diffuseDirectionalAlbedo(Diffuse::Lambert, mu, r), 1.0f);
            }
    }

    // Burley head-on against the closed form 1 + 5 r / 84 - 1 / 42 (the integration and the
    // shipped table's nodes, roughness clamped to kMinRoughness as shading clamps it).
    void burleyHeadOnClosedForm() {
        for (float r : {0.0f, 0.25f, 0.5f, 1.0f}) {
            const double closed = burleyHeadOn(r);
            const double integrated = brdf::integrateDiffuseAlbedo(Diffuse::Burley, 1.0f, r);
            const double looked = brdf::diffuseDirectionalAlbedo(Diffuse::Burley, 1.0f, r);
            qInfo("Burley head-on, roughness %.2f: closed form %.6f, integral %.6f, table %.6f", r,
                  closed, integrated, looked);
            QVERIFY2(std::abs(integrated - closed) < 1e-4, qPrintable(QString::number(integrated)));
            // r = 0.25 lies between two nodes (7.75 / 31): linear in r, so bilinear is exact.
            QVERIFY2(std::abs(looked - closed) < 1e-4, qPrintable(QString::number(looked)));
        }
    }

    // Away from head-on: the integration against the independent cosine-weighted rule, and
    // Burley's energy as the paper describes it (not conserved): darker than Lambert at grazing
    // when smooth, brighter when rough. The values are printed.
    void burleyAgainstIndependentQuadrature() {
        double worst = 0.0;
        for (float r : {0.0f, 0.3f, 0.7f, 1.0f})
            for (float mu : {0.9f, 0.6f, 0.3f, 0.1f, 0.02f}) {
                const double e = brdf::integrateDiffuseAlbedo(Diffuse::Burley, mu, r);
                const double q = burleyAlbedoByMu(mu, r);
                worst = std::max(worst, std::abs(e - q));
                QVERIFY2(
                    std::abs(e - q) < 2e-4,
                    qPrintable(
                        QString("E(%1, %2) = %3, quadrature %4").arg(mu).arg(r).arg(e).arg(q)));
            }
        qInfo("Burley albedo: integral vs independent quadrature, worst difference %.2e", worst);
        const double smoothGrazing = brdf::integrateDiffuseAlbedo(Diffuse::Burley, 0.05f, 0.0f);
        const double roughGrazing = brdf::integrateDiffuseAlbedo(Diffuse::Burley, 0.05f, 1.0f);
        qInfo("Burley albedo at n.v 0.05: %.4f smooth, %.4f rough (Lambert 1)", smoothGrazing,
              roughGrazing);
        QVERIFY(smoothGrazing < 0.8);
        QVERIFY(roughGrazing > 1.2);
    }

    // The shipped table (core/diffuse_albedo_table.inc) is the integration's: regenerate it with
    // `velvet diffuse-table > core/diffuse_albedo_table.inc` when Burley's term changes.
    void shippedTableMatchesTheIntegration() {
        const std::vector<float> integrated = brdf::integrateBurleyAlbedoTable();
        const std::vector<float>& shipped = brdf::burleyAlbedoLut();
        QCOMPARE(shipped.size(), size_t(brdf::kSheenLutSize) * brdf::kSheenLutSize);
        QCOMPARE(shipped.size(), integrated.size());
        float worst = 0.0f;
        for (size_t i = 0; i < shipped.size(); ++i)
            worst = std::max(worst, std::abs(shipped[i] - integrated[i]));
        QVERIFY2(worst < 1e-6f, qPrintable(QString("shipped table off by %1; run `velvet "
                                                   "diffuse-table > core/diffuse_albedo_table.inc`")
                                               .arg(worst)));
        QVERIFY(*std::min_element(shipped.begin(), shipped.end()) > 0.4f); // not empty
    }

    // Between the nodes the bilinear lookup (as the GPU samples it) stays within 1 % of the
    // integral over the whole domain: 40 x 40 points off the 32 x 32 grid, grazing included (the
    // worst, 0.7 %, is in the first column, n.v < 1/31, where (1 - n.v)^5 bends most).
    void lookupBetweenNodes() {
        double worst = 0.0;
        float worstMu = 0.0f, worstR = 0.0f;
        for (int j = 0; j < 40; ++j)
            for (int i = 0; i < 40; ++i) {
                const float mu = (float(i) + 0.37f) / 40.0f, r = (float(j) + 0.61f) / 40.0f;
                const double e = brdf::integrateDiffuseAlbedo(Diffuse::Burley, mu, r, 48, 24);
                const double rel =
                    std::abs(brdf::diffuseDirectionalAlbedo(Diffuse::Burley, mu, r) / e - 1.0);
                if (rel > worst) {
                    worst = rel;
                    worstMu = mu;
                    worstR = r;
                }
            }
        qInfo("Burley albedo table between nodes: worst relative error %.4f %% (n.v %.3f, "
              "roughness %.3f)",
              100.0 * worst, worstMu, worstR);
        QVERIFY2(worst < 0.01, qPrintable(QString::number(worst)));
    }
};

QTEST_GUILESS_MAIN(TestCoreDiffuseAlbedo)
#include "test_core_diffuse_albedo.moc"
