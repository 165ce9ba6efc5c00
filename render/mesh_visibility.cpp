// Per-vertex visibility of a mesh from itself: uniform hemisphere rays against the mesh
// through Embree's occlusion queries, the vertices spread over oneTBB's threads.
#include "render/mesh_visibility.h"

#include <algorithm>
#include <cmath>
#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <limits>
#include <numbers>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace velvet::render {
namespace {

// Van der Corput's radical inverse in base 2: the second coordinate of Hammersley's points.
float radicalInverse(std::uint32_t bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 2.3283064365386963e-10f;
}

// A per-vertex offset in [0, 1) (a 32-bit integer hash, Wellons' "lowbias32"): the Hammersley set
// shifted per vertex (Cranley-Patterson rotation), so neighbouring vertices do not share the
// same directions' bias and the interpolated result shows no pattern.
float vertexShift(std::uint32_t x) {
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return float(x >> 8u) * (1.0f / 16777216.0f);
}

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited".
void basis(glm::vec3 n, glm::vec3& b1, glm::vec3& b2) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    b1 = glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    b2 = glm::vec3(b, sign + n.y * n.y * a, -n.y);
}

// The visibility of one vertex (bakeMeshVisibility's per-vertex value) from @p rays rays spread
// uniformly over its hemisphere, starting @p offset above it.
glm::vec4 vertexVisibility(RTCScene scene, const Vertex& vertex, std::uint32_t index, int rays,
                           float offset) {
    const float length = glm::length(vertex.normal);
    if (!(length > 1e-12f)) // no normal: nothing to measure against
        return glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    const glm::vec3 n = vertex.normal / length;
    glm::vec3 b1, b2;
    basis(n, b1, b2);
    const glm::vec3 origin = vertex.position + n * offset;
    const float shiftU = vertexShift(index * 2u + 1u);
    const float shiftV = vertexShift(index * 2u + 2u);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    glm::vec3 occludedSum(0.0f);
    int open = 0;
    for (int r = 0; r < rays; ++r) {
        // Hammersley point r of `rays`, shifted, mapped to the hemisphere uniformly in solid
        // angle (cos theta uniform in [0, 1]).
        const float u = std::fmod((float(r) + 0.5f) / float(rays) + shiftU, 1.0f);
        const float v = std::fmod(radicalInverse(std::uint32_t(r)) + shiftV, 1.0f);
        const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - u * u));
        const float phi = 2.0f * std::numbers::pi_v<float> * v;
        const glm::vec3 d =
            b1 * (sinTheta * std::cos(phi)) + b2 * (sinTheta * std::sin(phi)) + n * u;
        RTCRay ray{};
        ray.org_x = origin.x, ray.org_y = origin.y, ray.org_z = origin.z;
        ray.dir_x = d.x, ray.dir_y = d.y, ray.dir_z = d.z;
        ray.tnear = offset;
        ray.tfar = std::numeric_limits<float>::infinity();
        ray.mask = ~0u;
        rtcOccluded1(scene, &context, &ray);
        if (ray.tfar >= 0.0f) // not occluded: Embree sets tfar to -inf on a hit
            ++open;
        else
            occludedSum += d;
    }
    // The open directions' sum is all directions' minus the occluded ones'; all directions' is
    // taken at its expectation (the uniform hemisphere's mean is n / 2), not at the rays' own sum,
    // so a vertex that sees everything gets exactly its normal rather than the samples' noise
    // (a few degrees with 128 rays, enough to cut a grazing reflection off the open cone).
    const glm::vec3 openSum = n * (0.5f * float(rays)) - occludedSum;
    const float bentLength = glm::length(openSum);
    return glm::vec4(open > 0 && bentLength > 1e-6f ? openSum / bentLength : n,
                     float(open) / float(rays));
}

} // namespace

std::vector<glm::vec4> bakeMeshVisibility(const MeshData& mesh,
                                          const VisibilityBakeOptions& options) {
    if (mesh.triangleCount() == 0 || mesh.vertices.empty())
        return {};
    RTCDevice device = rtcNewDevice(nullptr);
    if (!device)
        return {};
    RTCScene scene = rtcNewScene(device);
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* positions = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.vertices.size()));
    auto* triangles = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.triangleCount()));
    for (size_t i = 0; i < mesh.vertices.size(); ++i)
        for (int k = 0; k < 3; ++k)
            positions[i * 3 + k] = mesh.vertices[i].position[k];
    std::copy(mesh.indices.begin(), mesh.indices.end(), triangles);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene);

    // Rays start a hair above the vertex along its normal and ignore hits closer than that: the
    // mesh's own triangles around the vertex lie in (or, where it is concave, just above) its
    // tangent plane.
    const MeshBounds bounds = meshBounds(mesh);
    const float extent = std::max(glm::length(bounds.size()), 1e-6f);
    const float offset = 1e-4f * extent;
    const std::int64_t vertexCount = std::int64_t(mesh.vertices.size());
    const int rays = int(std::clamp<std::int64_t>(options.rayBudget / vertexCount, 16,
                                                  std::max(options.raysPerVertex, 16)));

    std::vector<glm::vec4> result(mesh.vertices.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.vertices.size(), 64),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t i = range.begin(); i != range.end(); ++i)
                              result[i] = vertexVisibility(scene, mesh.vertices[i],
                                                           std::uint32_t(i), rays, offset);
                      });
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    return result;
}

} // namespace velvet::render
