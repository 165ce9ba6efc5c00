#pragma once
/// @file scene.h
/// A scene: camera, lights, environment, preview mesh, the material assigned to it, post chain.

#include "core/material.h"
#include "core/post_chain.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {

/// An orbit camera around a target (yaw/pitch in degrees, Y up, right-handed).
struct Camera {
    glm::vec3 target{0.0f};
    float yawDeg = 0.0f;    ///< rotation about +Y; 0 looks down -Z from +Z
    float pitchDeg = 10.0f; ///< elevation, positive looks down on the target
    float distance = 4.5f;  ///< metres from target (a unit sphere fills ~70 % of the height)
    float fovYDeg = 35.0f;  ///< vertical field of view (perspective)
    float nearPlane = 0.05f;
    float farPlane = 100.0f;
    bool orthographic = false;
    float orthoHeight = 2.2f; ///< visible height in metres (orthographic)
    bool operator==(const Camera&) const = default;
};

/// Light types. Units (docs/units.md): directional in lux, point/spot in candela,
/// area in nits, ambient as a multiplier of scene-linear white.
enum class LightType : int { Directional, Point, Spot, Area, Ambient };
enum class AreaShape : int { Sphere, Rectangle };

struct Light {
    LightType type = LightType::Directional;
    std::string name;
    glm::vec3 color{1.0f}; ///< scene-linear Rec.709
    float intensity = 3.0f;
    glm::vec3 position{0.0f, 2.0f, 0.0f};
    glm::vec3 direction{-0.4f, -0.7f,
                        -0.6f}; ///< the way the light travels (directional, spot, area)
    float range = 10.0f;        ///< influence radius in metres (point, spot, area)
    float innerConeDeg = 20.0f; ///< spot: full intensity inside this half-angle
    float outerConeDeg = 30.0f; ///< spot: zero outside this half-angle
    AreaShape shape = AreaShape::Sphere;
    glm::vec2 size{0.5f}; ///< area: radius (sphere, x) or width × height (rectangle)
    /// @name Shadows (docs/shadows.md)
    /// Whether the light casts shadows from the preview mesh (directional, spot, point and area
    /// lights; at most render::kMaxShadowLights of them, the strongest at the mesh, do).
    /// @{
    bool castShadows = false;
    /// Directional: the source's angular diameter in degrees (the sun's is about 0.53°), which
    /// widens the penumbra with the distance to the occluder (PCSS); shading treats it as a point.
    float sourceAngleDeg = 2.0f;
    /// Point and spot: the source's radius in metres, for the penumbra only (area lights use their
    /// own size).
    float sourceRadius = 0.05f;
    /// @}
    bool operator==(const Light&) const = default;
};

/// How the environment appears behind the mesh.
enum class BackgroundMode : int { Sharp, Blurred, SolidColor, ProceduralFbm };

/// The floor under the mesh (docs/shadows.md): none, a shadow catcher (the background shows
/// through, darkened where the mesh shadows or occludes it) or a plain diffuse-ish material that
/// fades into the background with distance. Its height follows the mesh's lowest point.
enum class GroundMode : int { Off, ShadowCatcher, Plain };

struct Environment {
    std::string hdri;         ///< equirectangular HDR/EXR path; empty: uniform `color`
    glm::vec3 color{1.0f};    ///< uniform radiance when no HDRI is set
    float intensity = 1.0f;   ///< multiplier on the environment's radiance
    float rotationDeg = 0.0f; ///< rotation about +Y
    BackgroundMode background = BackgroundMode::Sharp;
    glm::vec3 backgroundColor{0.18f}; ///< for BackgroundMode::SolidColor
    /// @name The look-dev stage: ground and screen-space ambient occlusion (docs/shadows.md)
    /// Off by default so that a scene file that names neither keeps its image; the editor's mesh
    /// chooser applies groundDefaultsFor() the new mesh.
    /// @{
    GroundMode ground = GroundMode::Off;
    glm::vec3 groundColor{0.18f}; ///< scene-linear albedo of GroundMode::Plain
    float groundRoughness = 0.7f; ///< perceptual roughness of GroundMode::Plain
    /// Screen-space ambient occlusion (GTAO) on the environment's and ambient lights' light,
    /// multiplied with the material's occlusion map.
    bool ambientOcclusion = false;
    float occlusionRadius = 0.3f; ///< world-space radius of the occlusion search, metres
    /// @}
    bool operator==(const Environment&) const = default;
};

enum class PreviewMeshKind : int {
    Sphere,
    Cube,
    RoundedCube,
    Plane,
    ClothDrape,
    ShaderBall,
    Custom
};

struct MeshRef {
    PreviewMeshKind kind = PreviewMeshKind::Sphere;
    std::string file; ///< for Custom
    bool operator==(const MeshRef&) const = default;
};

struct Scene {
    Camera camera;
    std::vector<Light> lights;
    Environment environment;
    MeshRef mesh;
    Material material;
    std::string materialPreset; ///< where `material` came from, if a preset file (informational)
    PostChain post;
    /// The atlas document (core/atlas_document.h) the scene was authored with, absolute; empty:
    /// none. Loaded and saved beside the scene by the editor (scene version 2).
    std::string atlases;
    bool operator==(const Scene&) const = default;
};

/// File and panel names of the enumerations above, lowercase-hyphenated, in enum order
/// ("directional", "rounded-cube", "solid-color", …).
std::span<const std::string_view> lightTypeNames();
std::span<const std::string_view> areaShapeNames();
std::span<const std::string_view> backgroundModeNames();
std::span<const std::string_view> previewMeshKindNames();
std::span<const std::string_view> groundModeNames();

/// The look-dev stage a preview mesh is shown on by default: the cloth drape and the shader ball
/// stand on a shadow-catching ground with ambient occlusion, the other meshes float (no ground,
/// no occlusion). Applied by the editor when the mesh changes (core/scene.h's Environment
/// defaults stay Off, so files that do not mention a ground keep their image).
void applyStageDefaults(Environment& environment, PreviewMeshKind kind);
/// Whether @p environment's ground and occlusion are @p kind's stage defaults.
bool hasStageDefaults(const Environment& environment, PreviewMeshKind kind);

/// Whether the image of @p scene depends on FrameSettings::time: the procedural FBM background
/// drifts, or an enabled post effect reads time (postChainReadsTime). A still scene needs no new
/// frame until something changes.
bool sceneReadsTime(const Scene& scene);

} // namespace velvet
