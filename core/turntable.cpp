#include "core/turntable.h"

#include <cmath>
#include <glm/trigonometric.hpp>

namespace velvet {
namespace {

/// R_y(angle) applied to @p v: right-handed about +Y, so +X goes towards -Z.
glm::vec3 rotateY(const glm::vec3& v, float angleDeg) {
    const float a = glm::radians(angleDeg), c = std::cos(a), s = std::sin(a);
    return {c * v.x + s * v.z, v.y, -s * v.x + c * v.z};
}

/// Turns the world around the origin by @p angleDeg: the environment, the lights and (when
/// @p camera) the camera. Each follows its own convention: Environment::rotationDeg already
/// rotates the map by +rotation about +Y (toEnvironment in common_environment.glsl maps a world
/// direction d to R_y(-rotation) d), and the camera's eye offset (sin yaw, cos yaw) turns by
/// R_y(angle) when the yaw grows by the angle (render/camera.cpp).
void turnWorld(Scene& scene, float angleDeg, bool camera) {
    scene.environment.rotationDeg = std::fmod(scene.environment.rotationDeg + angleDeg, 360.0f);
    for (Light& light : scene.lights) {
        light.position = rotateY(light.position, angleDeg);
        light.direction = rotateY(light.direction, angleDeg);
    }
    if (camera) {
        scene.camera.target = rotateY(scene.camera.target, angleDeg);
        scene.camera.yawDeg = std::fmod(scene.camera.yawDeg + angleDeg, 360.0f);
    }
}

} // namespace

std::optional<TurntableMode> parseTurntableMode(std::string_view text) {
    if (text == "mesh")
        return TurntableMode::Mesh;
    if (text == "light")
        return TurntableMode::Light;
    return std::nullopt;
}

std::string_view turntableModeName(TurntableMode mode) {
    return mode == TurntableMode::Mesh ? "mesh" : "light";
}

float turntableAngleDeg(int frame, int frames) {
    return frames > 0 ? 360.0f * float(frame) / float(frames) : 0.0f;
}

Scene turntableScene(const Scene& scene, TurntableMode mode, float angleDeg) {
    Scene out = scene;
    if (mode == TurntableMode::Mesh)
        turnWorld(out, -angleDeg, true); // the mesh turns by +angle: the world by -angle
    else
        turnWorld(out, angleDeg, false);
    return out;
}

} // namespace velvet
