#include "core/lights.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace velvet::lights {

namespace {
float saturate(float x) {
    return std::clamp(x, 0.0f, 1.0f);
}
constexpr float kPi = 3.14159265358979f;
} // namespace

float windowFalloff(float distance, float range) {
    if (range <= 0.0f)
        return 0.0f;
    const float r = distance / range;
    const float w = saturate(1.0f - r * r * r * r);
    return w * w;
}

float distanceAttenuation(float distance, float range) {
    const float d2 = std::max(distance * distance, kMinLightDistance * kMinLightDistance);
    return windowFalloff(distance, range) / d2;
}

float spotConeAttenuation(float cosAngle, float cosOuter, float cosInner) {
    // GLSL smoothstep with edge0 = cosOuter, edge1 = max(cosInner, cosOuter + 1e-4).
    const float edge1 = std::max(cosInner, cosOuter + 1e-4f);
    const float t = saturate((cosAngle - cosOuter) / (edge1 - cosOuter));
    return t * t * (3.0f - 2.0f * t);
}

glm::vec3 sphereRepresentativePoint(glm::vec3 toCenter, glm::vec3 reflection, float radius) {
    // Karis 2013 eq. 11: the centre moved towards the ray by at most the radius.
    const glm::vec3 centerToRay = glm::dot(toCenter, reflection) * reflection - toCenter;
    const float len = std::max(glm::length(centerToRay), 1e-6f);
    return toCenter + centerToRay * saturate(radius / len);
}

glm::vec3 rectangleRepresentativePoint(glm::vec3 toCenter, glm::vec3 axisX, glm::vec3 axisY,
                                       float halfX, float halfY, glm::vec3 reflection) {
    const glm::vec3 normal = glm::cross(axisX, axisY);
    const float denom = glm::dot(reflection, normal);
    glm::vec3 onPlane = toCenter - glm::dot(toCenter, normal) * normal; // projection of the point
    if (std::abs(denom) > 1e-4f) {
        const float t = glm::dot(toCenter, normal) / denom;
        if (t > 0.0f)
            onPlane = reflection * t;
    }
    const glm::vec3 local = onPlane - toCenter;
    const float x = std::clamp(glm::dot(local, axisX), -halfX, halfX);
    const float y = std::clamp(glm::dot(local, axisY), -halfY, halfY);
    return toCenter + axisX * x + axisY * y;
}

float areaSpecularNormalization(float alpha, float widen) {
    const float widened = saturate(alpha + widen);
    const float ratio = alpha / std::max(widened, 1e-6f);
    return ratio * ratio;
}

float sphereIlluminancePerNit(float distance, float radius, float range) {
    const float d = std::max(distance, std::max(radius, kMinLightDistance));
    return kPi * (radius * radius) / (d * d) * windowFalloff(distance, range);
}

void rectangleAxes(glm::vec3 normal, glm::vec3& axisX, glm::vec3& axisY) {
    const glm::vec3 up = std::abs(normal.y) < 0.999f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    axisX = glm::normalize(glm::cross(up, normal));
    axisY = glm::cross(normal, axisX);
}

float rectangleIlluminancePerNit(float distance, float cosLight, float halfX, float halfY,
                                 float range) {
    const float d = std::max(distance, kMinLightDistance);
    return 4.0f * halfX * halfY * saturate(cosLight) / (d * d) * windowFalloff(distance, range);
}

} // namespace velvet::lights
