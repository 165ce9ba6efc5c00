#include "core/ibl.h"

#include "core/brdf.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <numbers>

namespace velvet::ibl {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

/// Weight of one GGX half-vector sample in the split-sum integral: f / F * (n.l) / pdf(l) with
/// pdf(l) = D (n.h) / (4 v.h), i.e. 4 V (n.l) (v.h) / (n.h) (Karis 2013, the IntegrateBRDF
/// listing, with glTF's separable visibility V = G / (4 n.l n.v) in place of G).
template <typename T>
void accumulate(T NdotV, T alpha, glm::tvec3<T, glm::defaultp> v, glm::tvec3<T, glm::defaultp> h,
                T& a, T& b) {
    const T VdotH = glm::dot(v, h);
    const glm::tvec3<T, glm::defaultp> l = T(2) * VdotH * h - v;
    const T NdotL = l.z;
    const T NdotH = h.z;
    if (NdotL <= T(0) || VdotH <= T(0))
        return;
    const T a2 = alpha * alpha;
    const T gl = NdotL + std::sqrt(a2 + (T(1) - a2) * NdotL * NdotL);
    const T gv = NdotV + std::sqrt(a2 + (T(1) - a2) * NdotV * NdotV);
    const T vis = T(1) / (gl * gv);
    const T w = T(4) * vis * NdotL * VdotH / NdotH;
    const T x = T(1) - VdotH;
    const T fc = x * x * x * x * x;
    a += (T(1) - fc) * w;
    b += fc * w;
}

} // namespace

glm::vec2 hammersley(std::uint32_t i, std::uint32_t n) {
    std::uint32_t bits = i;
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return {float(i) / float(n), float(bits) * 2.3283064365386963e-10f};
}

glm::vec3 importanceSampleGgx(glm::vec2 xi, float alpha) {
    // Karis 2013, ImportanceSampleGGX: the inverse CDF of D(h) (n.h) in theta_h.
    const float phi = 2.0f * kPi * xi.y;
    const float cosTheta = std::sqrt((1.0f - xi.x) / (1.0f + (alpha * alpha - 1.0f) * xi.x));
    const float sinTheta = std::sqrt(std::max(1.0f - cosTheta * cosTheta, 0.0f));
    return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

glm::vec2 integrateDfg(float NdotV, float perceptualRoughness, int samples) {
    const float rough = std::max(perceptualRoughness, brdf::kMinRoughness);
    const float alpha = rough * rough;
    NdotV = std::clamp(NdotV, 1e-4f, 1.0f);
    const glm::vec3 v(std::sqrt(1.0f - NdotV * NdotV), 0.0f, NdotV);
    float a = 0.0f, b = 0.0f;
    for (int i = 0; i < samples; ++i) {
        const glm::vec3 h = importanceSampleGgx(hammersley(std::uint32_t(i), samples), alpha);
        accumulate<float>(NdotV, alpha, v, h, a, b);
    }
    return glm::vec2(a, b) / float(samples);
}

glm::vec2 integrateDfgQuadrature(float NdotV, float perceptualRoughness, int nU, int nPhi) {
    const double rough = std::max(double(perceptualRoughness), double(brdf::kMinRoughness));
    const double alpha = rough * rough;
    const double nv = std::clamp(double(NdotV), 1e-4, 1.0);
    const glm::dvec3 v(std::sqrt(1.0 - nv * nv), 0.0, nv);
    double a = 0.0, b = 0.0;
    for (int i = 0; i < nU; ++i) {
        const double u = (i + 0.5) / nU;
        const double cosTheta = std::sqrt((1.0 - u) / (1.0 + (alpha * alpha - 1.0) * u));
        const double sinTheta = std::sqrt(std::max(1.0 - cosTheta * cosTheta, 0.0));
        for (int j = 0; j < nPhi; ++j) {
            const double phi = 2.0 * std::numbers::pi * (j + 0.5) / nPhi;
            const glm::dvec3 h(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
            accumulate<double>(nv, alpha, v, h, a, b);
        }
    }
    const double n = double(nU) * nPhi;
    return glm::vec2(float(a / n), float(b / n));
}

glm::vec2 dfgTexelParams(int i, int j, int size) {
    return {(float(i) + 0.5f) / float(size), (float(j) + 0.5f) / float(size)};
}

glm::vec3 specularAlbedo(glm::vec3 f0, glm::vec2 dfg, bool multiScatter) {
    const glm::vec3 single = f0 * dfg.x + dfg.y;
    if (!multiScatter)
        return single;
    // Fdez-Agüera 2019, eq. 16 (the f90 = 1 form used throughout Velvet).
    const float ess = dfg.x + dfg.y;
    const float ems = 1.0f - ess;
    const glm::vec3 favg = f0 + (1.0f - f0) / 21.0f;
    const glm::vec3 fmsEms = ems * single * favg / (1.0f - ems * favg);
    return single + fmsEms;
}

float roughnessOfLevel(int level, int levels) {
    return levels > 1 ? float(level) / float(levels - 1) : 0.0f;
}

float lodOfRoughness(float perceptualRoughness, int levels) {
    return std::clamp(perceptualRoughness, 0.0f, 1.0f) * float(std::max(levels - 1, 0));
}

float sourceLod(float pdf, int sampleCount, int faceSize) {
    const float omegaS = 1.0f / (float(sampleCount) * std::max(pdf, 1e-8f));
    const float omegaP = 4.0f * kPi / (6.0f * float(faceSize) * float(faceSize));
    return std::max(0.5f * std::log2(omegaS / omegaP) + 1.0f, 0.0f);
}

} // namespace velvet::ibl
