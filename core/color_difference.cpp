#include "core/color_difference.h"

#include "core/color_management.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace velvet {
namespace {

constexpr double kPi = std::numbers::pi;
double radians(double degrees) {
    return degrees * kPi / 180.0;
}
double degrees(double radians) {
    return radians * 180.0 / kPi;
}
double pow7(double x) {
    const double x2 = x * x;
    return x2 * x2 * x2 * x;
}

} // namespace

double ciede2000(const Lab& x, const Lab& y, double kL, double kC, double kH) {
    // (2)-(6): a' stretched by G so that near-neutral colours' hue is better behaved.
    const double c1 = std::hypot(x.a, x.b), c2 = std::hypot(y.a, y.b);
    const double cMean = 0.5 * (c1 + c2);
    const double g = 0.5 * (1.0 - std::sqrt(pow7(cMean) / (pow7(cMean) + pow7(25.0))));
    const double a1 = (1.0 + g) * x.a, a2 = (1.0 + g) * y.a;
    const double cp1 = std::hypot(a1, x.b), cp2 = std::hypot(a2, y.b);
    // h' in [0, 360); 0 when a' = b' = 0 (the paper's convention, eq. 4).
    auto hue = [](double b, double ap) {
        if (b == 0.0 && ap == 0.0)
            return 0.0;
        const double h = degrees(std::atan2(b, ap));
        return h < 0.0 ? h + 360.0 : h;
    };
    const double hp1 = hue(x.b, a1), hp2 = hue(y.b, a2);

    // (8)-(10): differences. dh' is 0 when either chroma is 0 (eq. 10 and its note).
    const double dLp = y.L - x.L;
    const double dCp = cp2 - cp1;
    const double chromaProduct = cp1 * cp2;
    double dhp = 0.0;
    if (chromaProduct != 0.0) {
        dhp = hp2 - hp1;
        if (dhp > 180.0)
            dhp -= 360.0;
        else if (dhp < -180.0)
            dhp += 360.0;
    }
    const double dHp = 2.0 * std::sqrt(chromaProduct) * std::sin(radians(dhp / 2.0));

    // (12)-(17): weights. The mean hue is the sum when a chroma is 0 (eq. 14's note); otherwise
    // the mean taken the short way round the circle.
    const double lMean = 0.5 * (x.L + y.L);
    const double cpMean = 0.5 * (cp1 + cp2);
    double hpMean = hp1 + hp2;
    if (chromaProduct != 0.0) {
        if (std::abs(hp1 - hp2) <= 180.0)
            hpMean = 0.5 * (hp1 + hp2);
        else if (hp1 + hp2 < 360.0)
            hpMean = 0.5 * (hp1 + hp2 + 360.0);
        else
            hpMean = 0.5 * (hp1 + hp2 - 360.0);
    }
    const double t = 1.0 - 0.17 * std::cos(radians(hpMean - 30.0)) +
                     0.24 * std::cos(radians(2.0 * hpMean)) +
                     0.32 * std::cos(radians(3.0 * hpMean + 6.0)) -
                     0.20 * std::cos(radians(4.0 * hpMean - 63.0));
    const double dTheta = 30.0 * std::exp(-std::pow((hpMean - 275.0) / 25.0, 2.0));
    const double rc = 2.0 * std::sqrt(pow7(cpMean) / (pow7(cpMean) + pow7(25.0)));
    const double l50 = (lMean - 50.0) * (lMean - 50.0);
    const double sl = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
    const double sc = 1.0 + 0.045 * cpMean;
    const double sh = 1.0 + 0.015 * cpMean * t;
    const double rt = -std::sin(radians(2.0 * dTheta)) * rc;

    const double l = dLp / (kL * sl), c = dCp / (kC * sc), h = dHp / (kH * sh);
    return std::sqrt(std::max(0.0, l * l + c * c + h * h + rt * c * h));
}

Lab xyzToLab(const glm::dvec3& xyz) {
    // The D65 white as the sRGB matrix below maps RGB (1, 1, 1) (its rows' sums), so that sRGB
    // white is exactly L* = 100, a* = b* = 0 (CIE 15:2004's D65, 0.95047 / 1.08883, differs in
    // the fifth digit).
    constexpr double kWhite[3] = {0.9505, 1.0, 1.0890};
    constexpr double kEpsilon = 216.0 / 24389.0, kKappa = 24389.0 / 27.0;
    auto f = [](double t) { return t > kEpsilon ? std::cbrt(t) : (kKappa * t + 16.0) / 116.0; };
    const double fx = f(xyz.x / kWhite[0]), fy = f(xyz.y / kWhite[1]), fz = f(xyz.z / kWhite[2]);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Lab srgbToLab(const glm::vec3& encoded) {
    glm::dvec3 rgb;
    for (int i = 0; i < 3; ++i)
        rgb[i] = srgbToLinear(std::clamp(encoded[i], 0.0f, 1.0f));
    // Linear sRGB (Rec.709 primaries, D65) to XYZ, IEC 61966-2-1 section 5.2.
    const glm::dvec3 xyz{0.4124 * rgb.r + 0.3576 * rgb.g + 0.1805 * rgb.b,
                         0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b,
                         0.0193 * rgb.r + 0.1192 * rgb.g + 0.9505 * rgb.b};
    return xyzToLab(xyz);
}

} // namespace velvet
