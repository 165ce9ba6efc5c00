#pragma once
/// @file camera.h
/// View and projection matrices of a core Camera (pure GLM; the renderer and the tests share them).

#include "core/scene.h"

#include <glm/mat4x4.hpp>

namespace velvet::render {

/// World position of the orbit camera's eye.
glm::vec3 cameraEye(const Camera& camera);
/// World -> view (right-handed, looking down -Z).
glm::mat4 viewMatrix(const Camera& camera);
/// View -> clip (OpenGL clip space, depth -1..1) for the aspect width / height.
glm::mat4 projectionMatrix(const Camera& camera, float aspect);

} // namespace velvet::render
