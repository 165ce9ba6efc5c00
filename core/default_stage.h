#pragma once
/// @file default_stage.h
/// The look-dev stage a new document starts on (the editor's File > New, `velvet render` without
/// FILE): the default scene (core/document_io.h) with its HDRI turned so the brightest part of
/// its backdrop sits behind the mesh, a blurred background and a camera that frames the mesh with
/// a little room (docs/default-scene.md). defaultScene() itself is left as it was: it is the
/// scene of the golden image (tests/render/test_render_golden.cpp), which must not change.

#include "core/diagnostics.h"
#include "core/image.h"
#include "core/scene.h"

#include <filesystem>
#include <optional>
#include <string>

namespace velvet {

/// How much of the frame's height the framed mesh's bounding sphere fills (the rest is room).
inline constexpr float kStageFill = 0.8f;

/// defaultScene() dressed as the stage: HDRI rotation from hdriDefaultRotationDeg (left as it is,
/// with a warning in @p problems, when the HDRI cannot be read), BackgroundMode::Blurred, and
/// framedCamera(). Never fails.
Scene stageScene(Problems* problems = nullptr);
/// A material preset opened on its own (the editor's File > Open, `velvet render PRESET`): the
/// stage with @p material, so a preset is judged in the same flattering light as a new document.
Scene stageSceneWithMaterial(Material material, Problems* problems = nullptr);

/// Whether a material preset's thumbnail shows it on the cloth drape rather than the sphere:
/// presets tagged "fabric" or "leather" (issue 13: a cloth or a hide reads as itself where folds
/// catch the sheen and show the weave's or the grain's scale; on a sphere it reads as plastic).
bool thumbnailOnDrape(const Material& material);
/// The scene of a material preset's thumbnail, the one rule of the editor's Library
/// (ui/library/thumbnail_renderer.cpp) and `velvet thumbnails`: stageSceneWithMaterial, with the
/// cloth drape on its stage defaults (ground and occlusion, applyStageDefaults) when
/// thumbnailOnDrape, as the editor shows the drape when an artist picks it.
Scene thumbnailScene(Material material, Problems* problems = nullptr);

/// Environment::rotationDeg (0 to 360, whole degrees) that puts the brightest part of the
/// backdrop of @p equirect (an equirectangular radiance map, as core/spherical_harmonics.h lays
/// it out) behind the mesh, i.e. in the direction a camera at yaw 0 looks (-Z). The backdrop is
/// the band from 35 degrees below to 20 degrees above the horizon (what the default camera,
/// pitched 10 degrees down with a 35 degree field of view, sees around the mesh, with margin);
/// each azimuth scores the solid-angle-weighted luminance (Rec. 709 Y) of the band under a 60
/// degree wide Hann window (a widescreen frame's field of view; the smooth window centres a
/// bright area rather than placing it anywhere it fits), each pixel's luminance clamped at the
/// band's 99th percentile, so a large bright area (a softbox, a lit sky) outweighs a tiny hot
/// one (the sun) that would leave the rest of the frame dark.
float backdropRotationDeg(const Image& equirect);

/// backdropRotationDeg of the HDRI file @p hdri: for the shipped HDRIs (resources/hdri) a table
/// of their answers (reading and scoring one takes 50-120 ms), for any other file
/// computeHdriDefaultRotationDeg. nullopt + @p error when the file cannot be read.
std::optional<float> hdriDefaultRotationDeg(const std::filesystem::path& hdri,
                                            std::string* error = nullptr);
/// backdropRotationDeg of the file @p hdri, read once per file and modification time.
std::optional<float> computeHdriDefaultRotationDeg(const std::filesystem::path& hdri,
                                                   std::string* error = nullptr);

/// @p camera aimed at the centre of a mesh whose bounding sphere has @p radius (every preview
/// mesh fits the unit sphere at the origin, core/mesh.h) from the distance at which that sphere
/// fills @p fill of the vertical field of view (and of the orthographic height).
Camera framedCamera(Camera camera, float radius = 1.0f, float fill = kStageFill);

} // namespace velvet
