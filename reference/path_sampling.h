#pragma once
/// @file path_sampling.h
/// The path tracer's building blocks (internal to reference/): its random numbers, the camera
/// rays that match render/camera.cpp, and the importance-sampled environment light.

#include "core/image.h"
#include "core/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <numbers>
#include <vector>

namespace velvet::reference::detail {

inline constexpr float kPi = std::numbers::pi_v<float>;

inline std::uint64_t mix64(std::uint64_t x) { // splitmix64's finaliser
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

/// The first two dimensions of the Sobol sequence (Sobol 1967): the base-2 radical inverse of
/// @p i (dimension 0) and the dimension whose direction numbers are v_1 = 1/2,
/// v_k = v_(k-1) xor v_(k-1)/2 (dimension 1), as 32-bit fractions. Together a (0, 2)-sequence:
/// every aligned block of 2^m points puts one point in each of the 2^m elementary intervals.
inline std::uint32_t sobol2d(std::uint32_t i, int dimension) {
    std::uint32_t result = 0;
    if (dimension == 0) {
        for (std::uint32_t v = 1u << 31; i; i >>= 1, v >>= 1)
            result ^= (i & 1u) ? v : 0u;
    } else {
        for (std::uint32_t v = 1u << 31; i; i >>= 1, v ^= v >> 1)
            result ^= (i & 1u) ? v : 0u;
    }
    return result;
}

/// Owen's nested uniform scramble of the base-2 digits of @p x, keyed by @p seed, by hashing
/// (Burley 2020, "Practical Hash-based Owen Scrambling", after Laine & Karras 2011): each digit
/// is flipped or not by a hash of the digits above it. A permutation that keeps a (0, m, 2)-net a
/// net; on a sample index, it keeps each aligned block of 2^m indices a block.
inline std::uint32_t reverseBits(std::uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
}
inline std::uint32_t owenScramble(std::uint32_t x, std::uint32_t seed) {
    x = reverseBits(x);
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return reverseBits(x);
}

/// One path's random numbers: PCG32 (O'Neill 2014), one stream per (pixel, sample), so the image
/// does not depend on which thread drew which pixel. With stratify(), the first
/// kStratifiedDimensions numbers come instead from the pixel's scrambled Sobol points (a
/// quasi-Monte Carlo sampler: the camera ray's position in the pixel, then each vertex's light,
/// environment and BRDF samples while they last, which carry most of a preview's variance; the
/// one-dimensional choices take decision()), in pairs:
/// numbers 2p and 2p + 1 are sample @p index of a 2D (0, 2)-sequence whose index is shuffled
/// and whose coordinates are scrambled by Owen scrambling with random keys per pair and per
/// dimension (Burley 2020's shuffled scrambled Sobol; the shuffle is what keeps pairs from
/// correlating, as Kollig & Keller 2002's padding does), so each pair is uniformly distributed
/// and independent of the others (unbiased) while any 2^m consecutive samples of a pixel stay
/// stratified. Beyond them, and without stratify(), plain PCG32.
struct Rng {
    static constexpr int kStratifiedDimensions = 12;
    std::uint64_t state, inc;
    std::uint32_t sampleIndex = 0;
    std::uint64_t scramble = 0;
    int dimension = kStratifiedDimensions; // no stratified numbers until stratify()
    Rng(std::uint64_t seed, std::uint64_t stream) : state(0), inc((stream << 1u) | 1u) {
        next();
        state += seed;
        next();
    }
    /// Sample @p index of the pixel whose scrambling keys come from @p pixelKey.
    void stratify(std::uint32_t index, std::uint64_t pixelKey) {
        sampleIndex = index;
        scramble = pixelKey;
        dimension = 0;
    }
    std::uint32_t next() {
        const std::uint64_t old = state;
        state = old * 6364136223846793005ULL + inc;
        const auto xorshifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
        const auto rot = std::uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }
    /// A number for a one-dimensional choice (a lobe, Russian roulette): always PCG32, so the
    /// stratified numbers stay in pairs, one 2D sample each.
    float decision() { return float(next() >> 8) * (1.0f / 16777216.0f); }
    /// The next number of the path; consecutive calls in twos are one 2D sample.
    float uniform() {
        std::uint32_t bits;
        if (dimension < kStratifiedDimensions) {
            // The pair's index shuffle, and its two coordinates' scrambles from a second hash.
            const std::uint64_t pairKey =
                mix64(scramble + 0x9e3779b97f4a7c15ULL * std::uint64_t(dimension / 2 + 1));
            const std::uint64_t keys = mix64(pairKey);
            const int coordinate = dimension & 1;
            const std::uint32_t index = owenScramble(sampleIndex, std::uint32_t(pairKey));
            bits =
                owenScramble(sobol2d(index, coordinate), std::uint32_t(keys >> (32 * coordinate)));
            ++dimension;
        } else {
            bits = next();
        }
        return float(bits >> 8) * (1.0f / 16777216.0f);
    }
};

inline float luminance(glm::vec3 c) {
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}
inline float maxComponent(glm::vec3 c) {
    return std::max(c.r, std::max(c.g, c.b));
}
inline float powerHeuristic(float a, float b) {
    const float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

inline void basis(glm::vec3 n, glm::vec3& t, glm::vec3& b) { // Duff et al. 2017
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

// ---- Camera: the same orbit and projection as render/camera.cpp (glm::lookAt, perspective) ----
struct CameraRays {
    glm::vec3 eye, forward, right, up;
    float tanHalfY = 0, aspect = 1;
    bool ortho = false;
    float orthoHalf = 1;
    CameraRays(const Camera& c, int w, int h) {
        const float yaw = glm::radians(c.yawDeg), pitch = glm::radians(c.pitchDeg);
        eye = c.target + c.distance * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                                std::cos(pitch) * std::cos(yaw));
        forward = glm::normalize(c.target - eye);
        right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
        up = glm::cross(right, forward);
        aspect = float(w) / float(std::max(h, 1));
        tanHalfY = std::tan(glm::radians(c.fovYDeg) * 0.5f);
        ortho = c.orthographic;
        orthoHalf = 0.5f * c.orthoHeight;
    }
    /// ndc in [-1, 1]^2, y up.
    void ray(float nx, float ny, glm::vec3& o, glm::vec3& d) const {
        if (ortho) {
            o = eye + right * (nx * orthoHalf * aspect) + up * (ny * orthoHalf);
            d = forward;
        } else {
            o = eye;
            d = glm::normalize(forward + right * (nx * tanHalfY * aspect) + up * (ny * tanHalfY));
        }
    }
};

// ---- Environment: radiance x intensity + ambient lights, importance-sampled by a 2D CDF ----
struct EnvironmentLight {
    Image image; // RGB equirect
    float intensity = 1, c = 1, s = 0;
    glm::vec3 ambient{0.0f};
    std::vector<float> marginal, conditional; // CDFs, rows then columns of each row
    float total = 0;

    glm::vec3 toEnv(glm::vec3 d) const { return {c * d.x - s * d.z, d.y, s * d.x + c * d.z}; }
    glm::vec3 fromEnv(glm::vec3 e) const { return {c * e.x + s * e.z, e.y, -s * e.x + c * e.z}; }

    glm::vec3 texel(int x, int y) const {
        x = ((x % image.width) + image.width) % image.width;
        y = std::clamp(y, 0, image.height - 1);
        const float* p = image.at(x, y);
        return {p[0], p[1], p[2]};
    }
    /// Bilinear, repeat in u, clamp in v, texel centres at (i + 0.5) / size (GL_LINEAR).
    glm::vec3 radiance(glm::vec3 worldDir) const {
        const glm::vec3 d = toEnv(worldDir);
        const float u = 0.5f + std::atan2(d.x, -d.z) / (2.0f * kPi);
        const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
        const float fx = u * image.width - 0.5f, fy = v * image.height - 0.5f;
        const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
        const float ax = fx - x0, ay = fy - y0;
        const glm::vec3 t = glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), ax),
                                     glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), ax), ay);
        return t * intensity + ambient;
    }
    void build() {
        const int w = image.width, h = image.height;
        conditional.assign(size_t(w) * h, 0.0f);
        marginal.assign(size_t(h), 0.0f);
        double average = 0;
        for (float v : image.pixels)
            average += v;
        // A floor of 1 % of the mean keeps the pdf positive where bilinear filtering still sees
        // light (a dark texel next to a bright one).
        const float floor =
            float(average / std::max<size_t>(image.pixels.size(), 1)) * 0.01f + 1e-8f;
        double rowSum = 0;
        for (int y = 0; y < h; ++y) {
            const float sinTheta = std::sin((float(y) + 0.5f) / float(h) * kPi);
            double sum = 0;
            for (int x = 0; x < w; ++x) {
                sum += (luminance(texel(x, y)) + floor) * sinTheta;
                conditional[size_t(y) * w + x] = float(sum);
            }
            for (int x = 0; x < w; ++x)
                conditional[size_t(y) * w + x] /= float(std::max(sum, 1e-30));
            rowSum += sum;
            marginal[size_t(y)] = float(rowSum);
        }
        total = float(rowSum);
        for (float& m : marginal)
            m /= std::max(total, 1e-30f);
    }
    float rowPdf(int y) const { return marginal[y] - (y ? marginal[y - 1] : 0.0f); }
    float colPdf(int x, int y) const {
        const float* row = conditional.data() + size_t(y) * image.width;
        return row[x] - (x ? row[x - 1] : 0.0f);
    }
    /// Solid-angle pdf of world direction @p d.
    float pdf(glm::vec3 worldDir) const {
        const glm::vec3 d = toEnv(worldDir);
        const float u = 0.5f + std::atan2(d.x, -d.z) / (2.0f * kPi);
        const float theta = std::acos(std::clamp(d.y, -1.0f, 1.0f));
        const float sinTheta = std::sin(theta);
        if (sinTheta <= 1e-6f)
            return 0.0f;
        const int x = std::clamp(int(u * image.width), 0, image.width - 1);
        const int y = std::clamp(int(theta / kPi * image.height), 0, image.height - 1);
        const float pUv = rowPdf(y) * colPdf(x, y) * float(image.width * image.height);
        return pUv / (2.0f * kPi * kPi * sinTheta);
    }
    glm::vec3 sample(float a, float b, float& pdfOut) const {
        const int y = int(std::lower_bound(marginal.begin(), marginal.end(), a) - marginal.begin());
        const int yy = std::min(y, image.height - 1);
        const float* row = conditional.data() + size_t(yy) * image.width;
        const int x =
            std::min(int(std::lower_bound(row, row + image.width, b) - row), image.width - 1);
        // Uniform inside the texel, from the remainders of the two draws.
        const float r0 = yy ? marginal[yy - 1] : 0.0f, c0 = x ? row[x - 1] : 0.0f;
        const float fy = std::clamp((a - r0) / std::max(rowPdf(yy), 1e-30f), 0.0f, 1.0f);
        const float fx = std::clamp((b - c0) / std::max(colPdf(x, yy), 1e-30f), 0.0f, 1.0f);
        const float u = (float(x) + fx) / image.width, v = (float(yy) + fy) / image.height;
        const float phi = (u - 0.5f) * 2.0f * kPi, theta = v * kPi;
        const glm::vec3 e(std::sin(theta) * std::sin(phi), std::cos(theta),
                          -std::sin(theta) * std::cos(phi));
        const glm::vec3 d = fromEnv(e);
        pdfOut = pdf(d);
        return d;
    }
};

} // namespace velvet::reference::detail
