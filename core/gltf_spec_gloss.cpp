#include "core/gltf_spec_gloss.h"

#include "core/color_management.h"
#include "core/image_ops.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>

namespace velvet {
namespace {

constexpr float kDielectricF0 = 0.04f;
constexpr float kEpsilon = 1e-6f;

float perceivedBrightness(glm::vec3 c) {
    return std::sqrt(0.299f * c.r * c.r + 0.587f * c.g * c.g + 0.114f * c.b * c.b);
}

/// The metallic m for which the diffuse and specular brightness are those of a metal-rough
/// material: 0.04 m² + b m + (0.04 - specular) = 0, b = diffuse (1 - s) / 0.96 + specular -
/// 0.08 (the extension's sample code).
float solveMetallic(float diffuse, float specular, float oneMinusSpecularStrength) {
    if (specular < kDielectricF0)
        return 0.0f;
    const float a = kDielectricF0;
    const float b =
        diffuse * oneMinusSpecularStrength / (1.0f - kDielectricF0) + specular - 2.0f * a;
    const float c = kDielectricF0 - specular;
    const float d = std::max(b * b - 4.0f * a * c, 0.0f);
    return std::clamp((-b + std::sqrt(d)) / (2.0f * a), 0.0f, 1.0f);
}

Image sized(const Image& image, int w, int h) {
    if (image.empty() || (image.width == w && image.height == h))
        return image;
    std::string ignored;
    return resize(image, w, h, &ignored);
}

} // namespace

MetalRough specGlossToMetalRough(const SpecGloss& sg) {
    const float oneMinus = 1.0f - std::max({sg.specular.r, sg.specular.g, sg.specular.b});
    MetalRough out;
    out.metallic =
        solveMetallic(perceivedBrightness(sg.diffuse), perceivedBrightness(sg.specular), oneMinus);
    const glm::vec3 fromDiffuse =
        sg.diffuse * (oneMinus / (1.0f - kDielectricF0) / std::max(1.0f - out.metallic, kEpsilon));
    const glm::vec3 fromSpecular =
        (sg.specular - glm::vec3(kDielectricF0 * (1.0f - out.metallic))) /
        std::max(out.metallic, kEpsilon);
    const float t = out.metallic * out.metallic;
    out.baseColor = glm::clamp(fromDiffuse + (fromSpecular - fromDiffuse) * t, 0.0f, 1.0f);
    out.roughness = std::clamp(1.0f - sg.glossiness, 0.0f, 1.0f);
    return out;
}

void specGlossImages(const Image& diffuse, const Image& specGloss, const SpecGloss& factors,
                     float diffuseAlphaFactor, Image& baseColor, Image& metalRough) {
    const int w = std::max({diffuse.width, specGloss.width, 1});
    const int h = std::max({diffuse.height, specGloss.height, 1});
    const Image d = sized(diffuse, w, h), s = sized(specGloss, w, h);
    baseColor = Image(w, h, 4);
    metalRough = Image(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            SpecGloss sg = factors;
            float alpha = diffuseAlphaFactor;
            if (!d.empty()) {
                const glm::vec4 t = d.rgba(x, y);
                sg.diffuse *= glm::vec3(srgbToLinear(t.r), srgbToLinear(t.g), srgbToLinear(t.b));
                alpha *= t.a;
            }
            if (!s.empty()) {
                const glm::vec4 t = s.rgba(x, y);
                sg.specular *= glm::vec3(srgbToLinear(t.r), srgbToLinear(t.g), srgbToLinear(t.b));
                sg.glossiness *= t.a;
            }
            const MetalRough mr = specGlossToMetalRough(sg);
            float* b = baseColor.at(x, y);
            b[0] = linearToSrgb(mr.baseColor.r);
            b[1] = linearToSrgb(mr.baseColor.g);
            b[2] = linearToSrgb(mr.baseColor.b);
            b[3] = alpha;
            float* m = metalRough.at(x, y);
            m[0] = 1.0f;
            m[1] = mr.roughness;
            m[2] = mr.metallic;
        }
}

} // namespace velvet
