#pragma once
/// @file reference_table.h
/// The viewport against the ground truth (issue 15's goal): a library preset on a preview mesh
/// under a light rig, drawn by the real-time renderer (render/) and path traced by the reference
/// (reference/), compared pixel by pixel with CIEDE2000 after the same display transform
/// (core/image_compare.h), over the pixels the mesh covers. `velvet compare --table` prints the
/// whole table (docs/reference-renderer.md); tests/app/test_app_reference_table holds the goal
/// (mean < 2, 95th percentile < 5) and the recorded bounds of the cases that miss it.

#include "core/diagnostics.h"
#include "core/image.h"
#include "core/image_compare.h"
#include "core/scene.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace velvet::cli {

/// One row: preset (a file stem in resources/presets), mesh, rig (core/light_rigs.h id).
struct ReferenceTableCase {
    std::string preset;
    PreviewMeshKind mesh = PreviewMeshKind::Sphere;
    std::string rig;
};

struct ReferenceTableOptions {
    int size = 48;       ///< square image side, pixels
    int supersample = 4; ///< viewport samples per pixel side (box-filtered, as the reference's)
    /// Reflection samples per viewport sample (FrameSettings::reflectionSamples), as the editor's
    /// viewport draws them at rest; 0: the split sum of an interactive frame.
    int reflectionSamples = 16; // render::kRefinementReflectionSamples (reference_table.cpp)
    /// The viewport's reflections of the mesh in itself (FrameSettings::screenSpaceReflections).
    bool screenSpaceReflections = true;
    int samples = 64; ///< reference samples per pixel
    int bounces = 4;  ///< reference path vertices after the first hit
    std::uint64_t seed = 1;
    int threads = 0; ///< reference threads; 0: all cores
};

struct ReferenceTableRow {
    ReferenceTableCase c;
    DeltaEStats stats; ///< over the pixels the mesh covers fully
    Image deltaE; ///< per pixel, 0 where the mesh does not cover the pixel fully (coverage < 1)
    Image viewport, reference; ///< both display-referred (defaultDisplayTransform), RGB
    double viewportMs = 0.0;   ///< the viewport's frames (with the environment bake)
    double referenceMs = 0.0;  ///< the path tracer
};

/// The goal of issue 15: mean ΔE2000 < 2 and 95th percentile < 5.
inline bool meetsReferenceGoal(const DeltaEStats& s) {
    return s.mean < 2.0 && s.p95 < 5.0;
}

/// The library's presets: the stems of resources/presets/*.json, sorted.
std::vector<std::string> libraryPresets();

/// The scene of @p c: the preset on the look-dev stage (`velvet render PRESET`'s scene, default
/// HDRI and framing) with @p c's mesh and rig and the editor's stage defaults for the mesh
/// (screen-space occlusion on the shader ball) except the ground, which the reference does not
/// have. nullopt + problems when the preset cannot be read.
std::optional<Scene> referenceTableScene(const ReferenceTableCase& c, Problems& problems);

/// Measures cases one after another with one headless context and renderer.
class ReferenceTable {
public:
    ReferenceTable();
    ~ReferenceTable();
    /// Creates the headless context and the renderer; false + why when it cannot.
    bool start(std::string* error);
    /// Renders and compares @p c; false + why when a render fails or the preset is unreadable.
    bool measure(const ReferenceTableCase& c, const ReferenceTableOptions& options,
                 ReferenceTableRow& row, std::string* error);

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

/// A Markdown table header and one row ("| gold | sphere | three-point | 1.23 | 3.45 | 7.89 |
/// yes |"), for the command and BENCHMARKS.md.
std::string referenceTableHeader();
std::string referenceTableLine(const ReferenceTableRow& row);

} // namespace velvet::cli
