#pragma once
/// @file post_effect_inputs.h
/// Test-only: the synthetic inputs and measures the post-effect tests share
/// (test_render_post_effects, test_render_post_grading): chains built in a line, a gradient with a
/// checker, flat grey, an analytically lit sphere with its depth and normals, and image
/// statistics. Runs through post_test_harness.h.

#include "core/image.h"
#include "core/post_chain.h"
#include "core/post_effects.h"
#include "post_test_harness.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

namespace velvet::test {

/// The images' side (pixels).
inline constexpr int kSize = 64;

inline PostChain chainOf(std::initializer_list<EffectInstance> effects) {
    PostChain c;
    c.effects = effects;
    return c;
}

inline EffectInstance fx(const char* type, std::map<std::string, std::vector<float>> params = {}) {
    EffectInstance e = makeEffect(type);
    for (auto& [k, v] : params)
        e.params[k] = v;
    return e;
}

/// A smooth gradient with a checker, values in [0.05, 0.95].
inline Image pattern(int n = kSize) {
    Image img(n, n, 4);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const float checker = ((x / 8 + y / 8) & 1) ? 0.3f : 0.0f;
            float* p = img.at(x, y);
            p[0] = 0.05f + 0.6f * float(x) / n + checker;
            p[1] = 0.05f + 0.6f * float(y) / n + checker * 0.5f;
            p[2] = 0.5f;
            p[3] = 1.0f;
        }
    return img;
}

inline Image flat(float v, int n = kSize) {
    Image img(n, n, 4);
    for (int i = 0; i < n * n; ++i) {
        img.pixels[size_t(i) * 4 + 0] = img.pixels[size_t(i) * 4 + 1] =
            img.pixels[size_t(i) * 4 + 2] = v;
        img.pixels[size_t(i) * 4 + 3] = 1.0f;
    }
    return img;
}

/// A lit sphere: camera at z = 3 looking at a unit sphere, a light from the upper left. Fills
/// colour, hardware depth, normals and matrices.
inline PostTestInput litSphere(int n = kSize) {
    PostTestInput in;
    in.color = Image(n, n, 4);
    in.depth = Image(n, n, 1);
    in.normals = Image(n, n, 3);
    const glm::mat4 proj = glm::perspective(glm::radians(45.0f), 1.0f, 0.1f, 20.0f);
    const glm::mat4 view = glm::lookAt(glm::vec3(0, 0, 3), glm::vec3(0), glm::vec3(0, 1, 0));
    in.proj = proj;
    in.viewProj = in.prevViewProj = proj * view;
    const glm::mat4 inv = glm::inverse(proj * view);
    const glm::vec3 light = glm::normalize(glm::vec3(-0.5f, 0.6f, 0.7f));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            // Row 0 is the top: NDC y = +1.
            const glm::vec2 ndc((x + 0.5f) / n * 2 - 1, 1 - (y + 0.5f) / n * 2);
            glm::vec4 a = inv * glm::vec4(ndc, -1, 1), b = inv * glm::vec4(ndc, 1, 1);
            const glm::vec3 o = glm::vec3(a) / a.w, d = glm::normalize(glm::vec3(b) / b.w - o);
            const float bq = glm::dot(o, d), c = glm::dot(o, o) - 1.0f, disc = bq * bq - c;
            float* col = in.color.at(x, y);
            col[3] = 1;
            if (disc < 0) {
                in.depth.at(x, y)[0] = 1.0f;
                col[0] = col[1] = col[2] = 0.05f;
                in.normals.at(x, y)[2] = 1;
                continue;
            }
            const glm::vec3 p = o + d * (-bq - std::sqrt(disc));
            const glm::vec3 nrm = glm::normalize(p);
            const glm::vec4 clip = proj * view * glm::vec4(p, 1);
            in.depth.at(x, y)[0] = clip.z / clip.w * 0.5f + 0.5f;
            const float lit = std::max(glm::dot(nrm, light), 0.0f) * 2.0f + 0.05f;
            col[0] = 0.8f * lit, col[1] = 0.5f * lit, col[2] = 0.3f * lit;
            for (int k = 0; k < 3; ++k)
                in.normals.at(x, y)[k] = nrm[k];
        }
    return in;
}

inline double meanOf(const Image& img, int channel) {
    double s = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            s += img.at(x, y)[channel];
    return s / (img.width * img.height);
}

inline double varianceOf(const Image& img, int channel) {
    const double m = meanOf(img, channel);
    double s = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            s += (img.at(x, y)[channel] - m) * (img.at(x, y)[channel] - m);
    return s / (img.width * img.height);
}

inline float maxDiff(const Image& a, const Image& b) {
    float d = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        if (i % 4 != 3)
            d = std::max(d, std::abs(a.pixels[i] - b.pixels[i]));
    return d;
}

inline float luma(const Image& img, int x, int y) {
    const float* p = img.at(x, y);
    return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
}

inline glm::vec3 rgbAt(const Image& img, int x, int y) {
    const float* p = img.at(x, y);
    return {p[0], p[1], p[2]};
}

/// @p chain run through @p post on @p in (post_test_harness.h); a chain that fails to run ends
/// the test program with its message.
inline Image runPostChain(render::PostChainRenderer& post, const PostChain& chain,
                          const PostTestInput& in) {
    Image out;
    std::string error;
    if (!applyPostChain(post, chain, in, out, &error)) {
        std::fprintf(stderr, "post chain failed: %s\n", error.c_str());
        std::abort();
    }
    return out;
}
inline Image runPostChain(render::PostChainRenderer& post, const PostChain& chain,
                          const Image& color) {
    PostTestInput in;
    in.color = color;
    return runPostChain(post, chain, in);
}

} // namespace velvet::test
