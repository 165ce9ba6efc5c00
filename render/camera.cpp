#include "render/camera.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

namespace velvet::render {

glm::vec3 cameraEye(const Camera& c) {
    const float yaw = glm::radians(c.yawDeg), pitch = glm::radians(c.pitchDeg);
    const glm::vec3 offset(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                           std::cos(pitch) * std::cos(yaw));
    return c.target + c.distance * offset;
}

glm::mat4 viewMatrix(const Camera& c) {
    return glm::lookAt(cameraEye(c), c.target, glm::vec3(0.0f, 1.0f, 0.0f));
}

glm::mat4 projectionMatrix(const Camera& c, float aspect) {
    if (c.orthographic) {
        const float h = 0.5f * c.orthoHeight, w = h * aspect;
        return glm::ortho(-w, w, -h, h, c.nearPlane, c.farPlane);
    }
    return glm::perspective(glm::radians(c.fovYDeg), aspect, c.nearPlane, c.farPlane);
}

} // namespace velvet::render
