#pragma once
/// @file gltf_spec_gloss.h
/// KHR_materials_pbrSpecularGlossiness (archived Khronos extension) to metallic-roughness, the
/// conversion the extension's own sample code gives ("convert-between-workflows", after
/// Babylon.js's): roughness = 1 - glossiness, and metallic solved from the perceived
/// brightness of the diffuse and specular colours so that a dielectric's F0 stays 0.04, base
/// colour blended between the diffuse-derived and specular-derived colours by metallic².
/// Used for factors and, texel by texel, for the textures (docs/interchange.md).

#include "core/image.h"

#include <glm/vec3.hpp>

namespace velvet {

struct SpecGloss {
    glm::vec3 diffuse{1.0f};  ///< linear
    glm::vec3 specular{1.0f}; ///< linear (F0)
    float glossiness = 1.0f;
};
struct MetalRough {
    glm::vec3 baseColor{1.0f};
    float metallic = 0.0f;
    float roughness = 0.0f;
};

MetalRough specGlossToMetalRough(const SpecGloss& sg);

/// Texel-by-texel conversion. @p diffuse (sRGB-encoded RGB, linear A) and @p specGloss
/// (sRGB-encoded RGB specular, linear A glossiness) may be empty (then the factors alone) and of
/// different sizes (resampled to the larger). @p baseColor gets sRGB-encoded RGB and the
/// diffuse alpha, @p metalRough glTF's layout (G roughness, B metallic); both at factor 1.
void specGlossImages(const Image& diffuse, const Image& specGloss, const SpecGloss& factors,
                     float diffuseAlphaFactor, Image& baseColor, Image& metalRough);

} // namespace velvet
