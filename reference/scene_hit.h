#pragma once
/// @file scene_hit.h
/// The path tracer's scene (internal to reference/): the material at a hit (parameters x texture
/// slots, the material graph's CPU twin), the lights, and the two ray queries through Embree
/// (scene_hit.cpp, the only file with Embree's headers besides reference_renderer.cpp).

#include "core/brdf.h"
#include "core/image.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "reference/graph_material.h"
#include "reference/path_sampling.h"

#include <memory>
#include <vector>

namespace velvet::reference::detail {

// ---- Material at a hit: parameters and texture slots (glTF: factor x texture) ----
struct Textures {
    std::shared_ptr<const Image> baseColor, metallicRoughness, specRoughMetal, normal, emissive,
        occlusion;
    // The KHR lobes' slots (factor x texture, the channels of texture_ref.h).
    std::shared_ptr<const Image> clearcoat, clearcoatRoughness, sheenColor, sheenRoughness,
        specular, specularColor, anisotropy;
};

struct LocalLight {
    const Light* light;
    glm::vec3 dir, axisX, axisY; // direction the light travels (unit); rectangle axes
    glm::vec3 radiance;          // colour x intensity
    float cosOuter = 0, cosInner = 0;
};

struct Context {
    void* scene = nullptr; ///< the RTCScene (Embree's type stays in the .cpp files)
    const MeshData* mesh = nullptr;
    brdf::Surface surface;
    Textures tex;
    const GraphMaterial* graph = nullptr; ///< the material graph, when it feeds any input
    float normalScale = 1;
    float occlusionStrength = 1;
    float anisotropyRotation = 0; ///< degrees, counter-clockwise from the tangent
    EnvironmentLight env;
    std::vector<LocalLight> lights;
    BackgroundMode background = BackgroundMode::Sharp;
    glm::vec3 backgroundColor{0.18f};
    int maxBounces = 4;
    float sceneScale = 1;
};

struct Hit {
    float t;
    glm::vec3 p, n, ng;
    brdf::Surface s;
    /// The material's occlusion at the hit, 1 - strength (1 - ao) (the texture's R or the
    /// graph's output, as gbuffer.frag), which scales the indirect light arriving there.
    float occlusion = 1;
};

/// The first surface along o + t d, t < tMax, with its material evaluated and its shading frame
/// facing the ray; false when the ray escapes.
bool intersect(const Context& ctx, glm::vec3 o, glm::vec3 d, float tMax, Hit& hit);
/// Whether anything lies along o + t d, t < tMax.
bool occluded(const Context& ctx, glm::vec3 o, glm::vec3 d, float tMax);

} // namespace velvet::reference::detail
