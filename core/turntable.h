#pragma once
/// @file turntable.h
/// The scenes of a turntable: N frames, each turned by 360 / N degrees about +Y
/// (docs/turntable.md).

#include "core/scene.h"

#include <optional>
#include <string_view>

namespace velvet {

/// What turns. Mesh: the mesh, as on a potter's wheel (the camera, the lights and the
/// environment stay where they are relative to the camera). Light: the environment and the lights
/// (the camera and the mesh stay; the reflections and the shading move over the material).
enum class TurntableMode : int { Mesh, Light };

/// "mesh" or "light".
std::optional<TurntableMode> parseTurntableMode(std::string_view text);
std::string_view turntableModeName(TurntableMode mode);

/// Degrees frame @p frame of @p frames is turned by: 360 frame / frames (frame 0 is the scene as
/// it is; frame N would be frame 0 again, so a looping video has no doubled frame).
float turntableAngleDeg(int frame, int frames);

/// @p scene with everything @p mode turns rotated by @p angleDeg about the +Y axis through the
/// origin (where every preview mesh sits, core/mesh.h), right-handed (counter-clockwise seen from
/// above). Mesh mode turns the mesh by turning the rest of the world the other way (camera target
/// and yaw, lights, environment rotation): the same image, with no mesh transform in the scene
/// (the G-buffer's world-space debug views, normal and position, are then those of the unturned
/// mesh seen from a turned camera).
Scene turntableScene(const Scene& scene, TurntableMode mode, float angleDeg);

} // namespace velvet
